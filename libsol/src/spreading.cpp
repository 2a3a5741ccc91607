#include "sol/spreading.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "ode.hpp"
#include "sol/closed_form.hpp"
#include "sol/error.hpp"

namespace sol {
namespace {

using detail::State;

template <class T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

template <class T>
Vec3<T> checked_direction(const Vec3<T>& direction, T t, const char* function) {
  const T n = glm::length(direction);
  if (!std::isfinite(n) || n == T(0)) {
    throw InvalidArgument(std::string(function) + ": direction must be finite and non-zero");
  }
  if (!std::isfinite(t) || t < T(0)) throw InvalidArgument(std::string(function) + ": t must be finite and >= 0");
  return direction / n;
}

// An orthonormal pair w1, w2 orthogonal to the unit v with w1 × w2 = v.
template <class T>
void orthonormal_pair(const Vec3<T>& v, Vec3<T>& w1, Vec3<T>& w2) {
  // Against the axis least aligned with v (no cancellation).
  const Vec3<T> a = std::abs(v.x) <= std::abs(v.y) && std::abs(v.x) <= std::abs(v.z) ? Vec3<T>(1, 0, 0)
                    : std::abs(v.y) <= std::abs(v.z)                                  ? Vec3<T>(0, 1, 0)
                                                                                      : Vec3<T>(0, 0, 1);
  w1 = glm::normalize(glm::cross(a, v));
  w2 = glm::cross(v, w1);
}

// The linearised geodesic equations (sol/spreading.hpp) of one field, (ξ, δu)
// at offset o of the state, along the velocity u.
template <class T, class S>
void variation_rhs(const Vec3<T>& u, const S& y, S& r, std::size_t o) {
  const T x1 = y[o], x2 = y[o + 1], x3 = y[o + 2], d1 = y[o + 3], d2 = y[o + 4], d3 = y[o + 5];
  r[o] = d1 + u.x * x3 - u.z * x1;
  r[o + 1] = d2 - u.y * x3 + u.z * x2;
  r[o + 2] = d3;
  r[o + 3] = u.z * d1 + u.x * d3;
  r[o + 4] = -u.z * d2 - u.y * d3;
  r[o + 5] = T(2) * (u.y * d2 - u.x * d1);
}

// jacobi_determinant, its errors naming `function`.
double jacobi_determinant_of(const glm::dvec3& direction, double t, const char* function, double tolerance = 1e-12) {
  const glm::dvec3 v = checked_direction(direction, t, function);
  if (t == 0.0) return 0.0;
  glm::dvec3 w1, w2;
  orthonormal_pair(v, w1, w2);
  // u(s) from the closed form (exact); state: the two fields (ξ, δu), then s.
  const ClosedFormGeodesic<double> geodesic(v);
  auto rhs = [&geodesic](const State<13>& y) {
    const glm::dvec3 u = geodesic.direction_at(y[12]);
    State<13> r;
    variation_rhs(u, y, r, 0);
    variation_rhs(u, y, r, 6);
    r[12] = 1.0;
    return r;
  };
  // ξ grows like s from 0, δu starts at size 1: mixed error control at those scales.
  const double small = std::min(1.0, t);
  const State<13> weights{small, small, small, 1, 1, 1, small, small, small, 1, 1, 1, 1};
  const State<13> start{0, 0, 0, w1.x, w1.y, w1.z, 0, 0, 0, w2.x, w2.y, w2.z, 0};
  const State<13> y = detail::integrate_dormand_prince(rhs, start, t, tolerance, weights, function);
  const glm::dvec3 y1(y[0], y[1], y[2]), y2(y[6], y[7], y[8]);
  const double d = glm::dot(glm::cross(y1, y2), geodesic.direction_at(t));
  if (!std::isfinite(d)) throw OutOfRange(std::string(function) + ": the Jacobi fields overflow; shorten t");
  return d;
}

}  // namespace

double jacobi_determinant(const glm::dvec3& direction, double t) {
  return jacobi_determinant_of(direction, t, "sol::jacobi_determinant");
}

double sphere_area_density(const glm::dvec3& direction, double t) {
  return std::abs(jacobi_determinant_of(direction, t, "sol::sphere_area_density"));
}

double sphere_area_density(const glm::dvec3& direction, double t, double tolerance) {
  if (!(tolerance >= 1e-14 && tolerance <= 1e-4)) {
    throw InvalidArgument("sol::sphere_area_density: tolerance " + std::to_string(tolerance) + " is outside [1e-14, 1e-4]");
  }
  return std::abs(jacobi_determinant_of(direction, t, "sol::sphere_area_density", tolerance));
}

float sphere_area_density(const glm::vec3& direction, float t) {
  // The kernel's method (compute/shaders/sol_spreading.glsl): u and both
  // fields by classical RK4 in float, equal steps of at most kSpreadingStep.
  const glm::vec3 v = checked_direction(direction, t, "sol::sphere_area_density");
  glm::vec3 w1, w2;
  orthonormal_pair(v, w1, w2);
  auto rhs = [](const std::array<float, 15>& y) {
    const glm::vec3 u(y[12], y[13], y[14]);
    std::array<float, 15> r;
    variation_rhs(u, y, r, 0);
    variation_rhs(u, y, r, 6);
    r[12] = u.x * u.z;
    r[13] = -u.y * u.z;
    r[14] = u.y * u.y - u.x * u.x;
    return r;
  };
  std::array<float, 15> y{0, 0, 0, w1.x, w1.y, w1.z, 0, 0, 0, w2.x, w2.y, w2.z, v.x, v.y, v.z};
  const float count = std::max(1.0f, std::ceil(t / static_cast<float>(kernel::kSpreadingStep)));
  if (!(count <= static_cast<float>(detail::kMaxRk4Steps))) {
    detail::too_many_steps("sol::sphere_area_density", detail::kMaxRk4Steps, t);
  }
  const int steps = static_cast<int>(count);
  const float h = t / static_cast<float>(steps);
  auto add = [](const std::array<float, 15>& a, float f, const std::array<float, 15>& k) {
    std::array<float, 15> r;
    for (std::size_t i = 0; i < 15; ++i) r[i] = a[i] + f * k[i];
    return r;
  };
  for (int s = 0; s < steps && t > 0.0f; ++s) {
    const auto k1 = rhs(y), k2 = rhs(add(y, 0.5f * h, k1)), k3 = rhs(add(y, 0.5f * h, k2)), k4 = rhs(add(y, h, k3));
    for (std::size_t i = 0; i < 15; ++i) y[i] += h / 6.0f * (k1[i] + 2.0f * k2[i] + 2.0f * k3[i] + k4[i]);
  }
  const glm::vec3 y1(y[0], y[1], y[2]), y2(y[6], y[7], y[8]), u = glm::normalize(glm::vec3(y[12], y[13], y[14]));
  return std::abs(glm::dot(glm::cross(y1, y2), u));
}

}  // namespace sol
