// Independent high-precision reference for Sol geodesics (tests and bench).
//
// Integrates the Euler–Lagrange equations of the metric in *coordinates*
//   x'' = 2x'z',  y'' = -2y'z',  z'' = -e^{-2z}x'^2 + e^{2z}y'^2
// (docs/mathematics.md) with Boost.Odeint's Bulirsch–Stoer stepper in 50-digit
// arithmetic (Boost.Multiprecision cpp_bin_float_50). It shares no code with
// libsol: a different formulation (coordinates, not frame components), a
// different integrator and a different number type.
#pragma once

#include <array>
#include <cmath>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/numeric/odeint.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

// Boost 1.74's odeint lacks the multiprecision adapter: a number is its own
// value type (the generic trait recurses into number::value_type).
namespace boost::numeric::odeint::detail {
template <>
struct extract_value_type<boost::multiprecision::cpp_bin_float_50, void> {
  using type = boost::multiprecision::cpp_bin_float_50;
};
}  // namespace boost::numeric::odeint::detail

namespace sol::test {

using Real50 = boost::multiprecision::cpp_bin_float_50;

struct ReferencePoint {
  glm::dvec3 position;   // coordinates
  glm::dvec3 direction;  // frame components
  glm::dmat3 transport{1.0};  // column i: frame components of the transported E_i (if requested)
};

/// Geodesic from `start` with frame direction `d`, optionally carrying three
/// vectors by parallel transport, written with the Christoffel symbols of the
/// metric diag(e^{-2z}, e^{2z}, 1) in coordinates:
///   Γ^x_{xz} = -1, Γ^y_{yz} = 1, Γ^z_{xx} = e^{-2z}, Γ^z_{yy} = -e^{2z},
///   W^k' = -Γ^k_{ij} x'^i W^j.
template <class Real = Real50>
class ReferenceGeodesic {
 public:
  using State = std::array<Real, 15>;  // x, y, z, x', y', z', then W1, W2, W3 (coordinates)

  explicit ReferenceGeodesic(const glm::dvec3& d, bool with_transport = false, Real tolerance = Real(1e-28))
      : ReferenceGeodesic(glm::dvec3(0.0), d, with_transport, tolerance) {}

  ReferenceGeodesic(const glm::dvec3& start, const glm::dvec3& d, bool with_transport = false,
                    Real tolerance = Real(1e-28))
      : m_tolerance(tolerance), m_transport(with_transport) {
    Real a = d.x, b = d.y, c = d.z;
    const Real n = sqrt(a * a + b * b + c * c);
    a /= n;
    b /= n;
    c /= n;
    const Real z0 = start.z, ez = exp(z0);
    m_state.fill(Real(0));
    m_state[0] = start.x;
    m_state[1] = start.y;
    m_state[2] = z0;
    // Coordinate velocity of frame components (a, b, c): (e^{z}a, e^{-z}b, c).
    m_state[3] = ez * a;
    m_state[4] = b / ez;
    m_state[5] = c;
    // E1, E2, E3 in coordinates.
    m_state[6] = ez;
    m_state[10] = 1 / ez;
    m_state[14] = 1;
  }

  /// Advances to arc length t (any order of calls) and returns the point.
  ReferencePoint at(double t) {
    namespace odeint = boost::numeric::odeint;
    const Real target = t;
    if (target != m_t) {
      const bool transport = m_transport;
      auto rhs = [transport](const State& s, State& ds, const Real&) {
        const Real e2z = exp(2 * s[2]);
        ds[0] = s[3];
        ds[1] = s[4];
        ds[2] = s[5];
        ds[3] = 2 * s[3] * s[5];
        ds[4] = -2 * s[4] * s[5];
        ds[5] = -s[3] * s[3] / e2z + e2z * s[4] * s[4];
        for (int v = 0; v < 3; ++v) {
          if (!transport) {
            ds[6 + 3 * v] = ds[7 + 3 * v] = ds[8 + 3 * v] = 0;
            continue;
          }
          const Real wx = s[6 + 3 * v], wy = s[7 + 3 * v], wz = s[8 + 3 * v];
          ds[6 + 3 * v] = s[3] * wz + s[5] * wx;
          ds[7 + 3 * v] = -(s[4] * wz + s[5] * wy);
          ds[8 + 3 * v] = -(s[3] * wx / e2z) + e2z * s[4] * wy;
        }
      };
      odeint::bulirsch_stoer<State, Real> stepper(m_tolerance, m_tolerance);
      const Real dt0 = target > m_t ? Real(0.1) : Real(-0.1);
      odeint::integrate_adaptive(stepper, rhs, m_state, m_t, target, dt0);
      m_t = target;
    }
    const Real ez = exp(m_state[2]);
    auto frame = [&](int i) {
      return glm::dvec3(static_cast<double>(m_state[i] / ez), static_cast<double>(m_state[i + 1] * ez),
                        static_cast<double>(m_state[i + 2]));
    };
    ReferencePoint p;
    p.position = {static_cast<double>(m_state[0]), static_cast<double>(m_state[1]), static_cast<double>(m_state[2])};
    p.direction = frame(3);
    if (m_transport) p.transport = glm::dmat3(frame(6), frame(9), frame(12));
    return p;
  }

 private:
  Real m_tolerance;
  bool m_transport;
  Real m_t = 0;
  State m_state;
};

}  // namespace sol::test
