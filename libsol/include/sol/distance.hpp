// Exact Sol distances to the coordinate planes (docs/mathematics.md), usable as
// signed distance functions for sphere tracing, and their gradients.
//
//   plane z = c:  |z - c|                      (the vertical segment is a geodesic)
//   plane x = c:  asinh(|x - c| e^{-z})        (x = c is a totally geodesic H²;
//   plane y = c:  asinh(|y - c| e^{z})          distance in the (x, z) hyperbolic plane)
//
// Gradients are unit vectors in frame components (E1 = e^{z}∂x, E2 = e^{-z}∂y,
// E3 = ∂z), pointing away from the plane: on the surface they are its normal.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/vec2.hpp>
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

/// A lower bound of the Sol distance between p and q (docs/mathematics.md): the
/// projections (x, y, z) -> (x, z) and -> (y, z) onto the hyperbolic planes
/// e^{-2z}dx² + dz² and e^{2z}dy² + dz² do not increase lengths, and there
///   cosh d = cosh Δz + ½ Δx² e^{-(z1+z2)},   cosh d = cosh Δz + ½ Δy² e^{z1+z2}.
/// Written as d = 2 asinh √(sinh²(Δz/2) + A/2), A the larger of the two
/// terms, so that small distances keep their relative accuracy.
inline double distance_lower_bound(const glm::dvec3& p, const glm::dvec3& q) {
  const double dz = p.z - q.z, sum = p.z + q.z;
  const double dx = p.x - q.x, dy = p.y - q.y;
  const double a = std::max(0.5 * dx * dx * std::exp(-sum), 0.5 * dy * dy * std::exp(sum));
  const double sh = std::sinh(0.5 * dz);
  return 2.0 * std::asinh(std::sqrt(sh * sh + 0.5 * a));
}

/// Signed distance bound of the ball (center, radius): never more than the
/// true distance to the geodesic ball, so sphere tracing never tunnels; its
/// zero set is the surface drawn (docs/scene-format.md: how it differs from the sphere).
inline double sdf_ball(const glm::dvec3& p, const glm::dvec3& center, double radius) {
  return distance_lower_bound(p, center) - radius;
}

/// Signed distance bound of the tube of `radius` around the line through
/// `through` along coordinate `axis` (0 x, 1 y, 2 z). The line lies in two
/// coordinate planes, and the distance to a set is at least the distance to
/// any set containing it:
///   axis z: {x = x0} ∩ {y = y0}: max(asinh(|Δx| e^{-z}), asinh(|Δy| e^{z}))
///   axis x: {y = y0} ∩ {z = z0}: max(asinh(|Δy| e^{z}), |Δz|)
///   axis y: {x = x0} ∩ {z = z0}: max(asinh(|Δx| e^{-z}), |Δz|)
/// Exact for points in the totally geodesic plane x = x0 or y = y0 that
/// contains the line (there the hyperbolic-plane distance to a geodesic,
/// resp. to a horocycle, is attained); a lower bound elsewhere.
/// Signed distance bound of the tube of `radius` around the horizontal line
/// {through + s (h.x, h.y, 0)}, h ≠ 0 a coordinate direction. For each point
/// q(s) of the line, d(p, q(s)) is at least the distances to the planes
/// x = q_x(s) and y = q_y(s), asinh(A |s - s1|) and asinh(B |s - s2|) with
/// A = |h.x| e^{-z}, B = |h.y| e^{z} (z = p.z, s1, s2 where the line meets
/// x = p.x, y = p.y); the smaller over s of the larger of two such V shapes
/// is reached where they cross:
///   d(p, line) >= max(|Δz|, asinh(|h.y Δx - h.x Δy| / (|h.x| e^{-z} + |h.y| e^{z}))).
/// For h = (1, 0) or (0, 1) this is sdf_tube's bound for the x or y axis.
inline double sdf_tube_horizontal(const glm::dvec3& p, const glm::dvec3& through, const glm::dvec2& h, double radius) {
  const double dx = p.x - through.x, dy = p.y - through.y;
  const double across =
      std::abs(h.y * dx - h.x * dy) / (std::abs(h.x) * std::exp(-p.z) + std::abs(h.y) * std::exp(p.z));
  return std::max(std::asinh(across), std::abs(p.z - through.z)) - radius;
}

inline double sdf_tube(const glm::dvec3& p, const glm::dvec3& through, int axis, double radius) {
  if (axis == 0) return sdf_tube_horizontal(p, through, {1.0, 0.0}, radius);
  if (axis == 1) return sdf_tube_horizontal(p, through, {0.0, 1.0}, radius);
  const double to_x = std::asinh(std::abs(p.x - through.x) * std::exp(-p.z));
  const double to_y = std::asinh(std::abs(p.y - through.y) * std::exp(p.z));
  return std::max(to_x, to_y) - radius;
}

}  // namespace sol
