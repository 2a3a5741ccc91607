// Direction sets shared by the tests and the bench: random unit directions
// (fixed seed) and the stiff and extreme ones of docs/mathematics.md.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace sol::test {

/// `count` unit vectors uniform on the sphere, reproducible from `seed`.
inline std::vector<glm::dvec3> random_directions(int count, unsigned seed = 12345) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::vector<glm::dvec3> out;
  out.reserve(count);
  while (static_cast<int>(out.size()) < count) {
    const glm::dvec3 v(normal(rng), normal(rng), normal(rng));
    if (glm::length(v) > 1e-3) out.push_back(glm::normalize(v));
  }
  return out;
}

/// Unit direction with horizontal part (a, b) scaled to sqrt(1 - c^2); keeps
/// c exact when c is within 1e-12 of ±1.
inline glm::dvec3 direction_with_c(double a, double b, double c) {
  const double h = std::sqrt((1.0 - c) * (1.0 + c));
  const double n = std::hypot(a, b);
  return {a / n * h, b / n * h, c};
}

/// The stiff and extreme directions: every axis, c near ±1, |ab| → 0, a ≈ ±b with c ≈ 0.
inline std::vector<glm::dvec3> stiff_directions() {
  const double s = 1.0 / std::sqrt(2.0);
  std::vector<glm::dvec3> d = {
      {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},  // axes
      {s, s, 0}, {s, -s, 0}, {-s, s, 0}, {-s, -s, 0},                        // straight lines
  };
  for (double c : {1.0 - 1e-12, -(1.0 - 1e-12), 1.0 - 1e-6, -(1.0 - 1e-6), 0.999, -0.999}) {
    d.push_back(direction_with_c(0.6, 0.8, c));
    d.push_back(direction_with_c(-0.3, 0.95, c));
  }
  // |ab| -> 0 with a or b tiny, c moderate.
  for (double tiny : {1e-14, 1e-10, 1e-6, 1e-3}) {
    d.push_back(glm::normalize(glm::dvec3(tiny, 0.8, 0.6)));
    d.push_back(glm::normalize(glm::dvec3(0.8, -tiny, -0.6)));
    d.push_back(glm::normalize(glm::dvec3(-tiny, 0.6, -0.8)));
  }
  // a ≈ ±b and c ≈ 0.
  for (double eps : {1e-12, 1e-8, 1e-4}) {
    d.push_back(glm::normalize(glm::dvec3(s + eps, s, 0.0)));
    d.push_back(glm::normalize(glm::dvec3(s, -s, eps)));
    d.push_back(glm::normalize(glm::dvec3(-s, -s - eps, -eps)));
  }
  return d;
}

/// max(1, |v|) component-wise maximum: the scale error goals are stated in (docs/numerics.md).
inline double error_scale(const glm::dvec3& v) {
  return std::max({1.0, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

/// Largest component-wise difference divided by error_scale(reference).
inline double scaled_error(const glm::dvec3& value, const glm::dvec3& reference) {
  const glm::dvec3 d = glm::abs(value - reference);
  return std::max({d.x, d.y, d.z}) / error_scale(reference);
}

}  // namespace sol::test
