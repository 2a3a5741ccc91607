// Independent high-precision reference for Sol geodesics (tests and bench).
//
// Integrates the Euler–Lagrange equations of the metric in *coordinates*
//   x'' = 2x'z',  y'' = -2y'z',  z'' = -e^{-2z}x'^2 + e^{2z}y'^2
// (DESIGN.md §3) with Boost.Odeint's Bulirsch–Stoer stepper in 50-digit
// arithmetic (Boost.Multiprecision cpp_bin_float_50). It shares no code with
// libsol: a different formulation (coordinates, not frame components), a
// different integrator and a different number type.
#pragma once

#include <array>
#include <cmath>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/numeric/odeint.hpp>
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
};

template <class Real = Real50>
class ReferenceGeodesic {
 public:
  using State = std::array<Real, 6>;  // x, y, z, x', y', z'

  /// Geodesic from the origin with unit frame direction `d` (normalised in Real).
  explicit ReferenceGeodesic(const glm::dvec3& d, Real tolerance = Real(1e-28)) : m_tolerance(tolerance) {
    Real a = d.x, b = d.y, c = d.z;
    const Real n = sqrt(a * a + b * b + c * c);
    a /= n;
    b /= n;
    c /= n;
    // At the origin frame components and coordinate velocity agree.
    m_state = {Real(0), Real(0), Real(0), a, b, c};
  }

  /// Advances to arc length t (monotone calls, t >= current) and returns the point.
  ReferencePoint at(double t) {
    namespace odeint = boost::numeric::odeint;
    const Real target = t;
    if (target != m_t) {
      odeint::bulirsch_stoer<State, Real> stepper(m_tolerance, m_tolerance);
      auto rhs = [](const State& s, State& ds, const Real&) {
        const Real e2z = exp(2 * s[2]);
        ds[0] = s[3];
        ds[1] = s[4];
        ds[2] = s[5];
        ds[3] = 2 * s[3] * s[5];
        ds[4] = -2 * s[4] * s[5];
        ds[5] = -s[3] * s[3] / e2z + e2z * s[4] * s[4];
      };
      const Real dt0 = target > m_t ? Real(0.1) : Real(-0.1);
      odeint::integrate_adaptive(stepper, rhs, m_state, m_t, target, dt0);
      m_t = target;
    }
    const Real ez = exp(m_state[2]);
    ReferencePoint p;
    p.position = {static_cast<double>(m_state[0]), static_cast<double>(m_state[1]), static_cast<double>(m_state[2])};
    p.direction = {static_cast<double>(m_state[3] / ez), static_cast<double>(m_state[4] * ez),
                   static_cast<double>(m_state[5])};
    return p;
  }

 private:
  Real m_tolerance;
  Real m_t = 0;
  State m_state;
};

}  // namespace sol::test
