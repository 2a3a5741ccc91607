// Exact Sol distances to the coordinate planes (DESIGN.md §3), usable as
// signed distance functions for sphere tracing, and their gradients.
//
//   plane z = c:  |z - c|                      (the vertical segment is a geodesic)
//   plane x = c:  asinh(|x - c| e^{-z})        (x = c is a totally geodesic H²;
//   plane y = c:  asinh(|y - c| e^{z})          distance in the (x, z) hyperbolic plane)
//
// Gradients are unit vectors in frame components (E1 = e^{z}∂x, E2 = e^{-z}∂y,
// E3 = ∂z), pointing away from the plane: on the surface they are its normal.
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

namespace sol {

inline double sdf_plane_z(const glm::dvec3& p, double c) { return std::abs(p.z - c); }
inline double sdf_plane_x(const glm::dvec3& p, double c) { return std::asinh(std::abs(p.x - c) * std::exp(-p.z)); }
inline double sdf_plane_y(const glm::dvec3& p, double c) { return std::asinh(std::abs(p.y - c) * std::exp(p.z)); }

inline glm::dvec3 sdf_plane_z_gradient(const glm::dvec3& p, double c) {
  return {0.0, 0.0, p.z >= c ? 1.0 : -1.0};
}

// f = asinh(w), w = |x - c| e^{-z}: E1 f = e^{z} ∂x f = sign(x - c)/√(1 + w²),
// E3 f = ∂z f = -w/√(1 + w²).
inline glm::dvec3 sdf_plane_x_gradient(const glm::dvec3& p, double c) {
  const double w = std::abs(p.x - c) * std::exp(-p.z), r = 1.0 / std::sqrt(1.0 + w * w);
  return {(p.x >= c ? 1.0 : -1.0) * r, 0.0, -w * r};
}

// f = asinh(w), w = |y - c| e^{z}: E2 f = sign(y - c)/√(1 + w²), E3 f = w/√(1 + w²).
inline glm::dvec3 sdf_plane_y_gradient(const glm::dvec3& p, double c) {
  const double w = std::abs(p.y - c) * std::exp(p.z), r = 1.0 / std::sqrt(1.0 + w * w);
  return {0.0, (p.y >= c ? 1.0 : -1.0) * r, w * r};
}

}  // namespace sol
