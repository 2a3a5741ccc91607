// Glowing boxes and bound balls as lights, written once for the CPU
// renderer (double) and the kernels (float): next-event estimation draws a
// point of the surface with a density per unit area known in closed form
// (docs/lighting.md, "Glowing boxes and bound balls").
//
// Boxes: uniformly by area. In the box's own frame w = centre⁻¹·q
// the box is [−a, a] × [−b, b] × [−c, c], (a, b, c) its half size, and the
// metric e^{−2z}dx² + e^{2z}dy² + dz² gives its faces the area elements
//   z = ±c: dx dy             (area 4ab each)
//   x = ±a: e^{z} dy dz       (area 4b sinh c each)
//   y = ±b: e^{−z} dx dz      (area 4a sinh c each),
// and each face's unit normal is a frame vector, ±E1, ±E2 or ±E3, which a
// left translation keeps: the same at the box's world point. Valid C++
// (namespace sol::kernel, double) and GLSL (float), as sol/patterns.h.
#ifndef SOL_SURFACE_LIGHT_H
#define SOL_SURFACE_LIGHT_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
namespace sol::kernel {
#define SOL_SHARED_FUNCTION inline
#define SOL_LIGHT_VEC3 glm::dvec3
using std::abs;
using std::asinh;
using std::cos;
using std::cosh;
using std::exp;
using std::log;
using std::sin;
using std::sinh;
using std::sqrt;
using std::max;
#else
#define SOL_SHARED_FUNCTION
#define SOL_LIGHT_VEC3 vec3
#endif

/// The area of the box's surface: 8ab + 8(a + b) sinh c.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_area(SOL_LIGHT_VEC3 half_size) {
  return 8.0 * half_size.x * half_size.y + 8.0 * (half_size.x + half_size.y) * sinh(half_size.z);
}

/// The size next-event estimation picks a box by, as a ball's radius
/// (about its solid angle): its half size's Euclidean length.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_radius(SOL_LIGHT_VEC3 half_size) {
  return sqrt(half_size.x * half_size.x + half_size.y * half_size.y + half_size.z * half_size.z);
}

/// The point of the box's surface (in its own frame) that three uniform
/// numbers in [0, 1) draw with density 1 / sol_box_light_area per unit
/// area: u0 picks a face by its area (z = +c, −c, x = +a, −a, y = +b, −b),
/// u1 and u2 place the point on it, where z follows e^{±z} on the side faces.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_box_light_point(SOL_LIGHT_VEC3 half_size, SOL_REAL u0, SOL_REAL u1, SOL_REAL u2) {
  const SOL_REAL a = half_size.x, b = half_size.y, c = half_size.z;
  const SOL_REAL top = 4.0 * a * b, side_x = 4.0 * b * sinh(c), side_y = 4.0 * a * sinh(c);
  SOL_REAL left = u0 * (2.0 * (top + side_x + side_y));
  const SOL_REAL s = 2.0 * u1 - 1.0;
  // z with density e^{z} on [−c, c]: the inverse of its distribution.
  const SOL_REAL rising = log(exp(-c) + u2 * (exp(c) - exp(-c)));
  if (left < 2.0 * top) return SOL_LIGHT_VEC3(a * s, b * (2.0 * u2 - 1.0), left < top ? c : -c);
  left -= 2.0 * top;
  if (left < 2.0 * side_x) return SOL_LIGHT_VEC3(left < side_x ? a : -a, b * s, rising);
  left -= 2.0 * side_x;
  return SOL_LIGHT_VEC3(a * s, left < side_y ? b : -b, -rising);
}

/// The box's bound at w (its own frame): the largest of the signed exact
/// distances to its three slabs (as sol::Box::distance), 0 on its surface.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_bound(SOL_LIGHT_VEC3 w, SOL_LIGHT_VEC3 half_size) {
  const SOL_REAL tx = asinh((abs(w.x) - half_size.x) * exp(-w.z));
  const SOL_REAL ty = asinh((abs(w.y) - half_size.y) * exp(w.z));
  const SOL_REAL tz = abs(w.z) - half_size.z;
  return tx > ty ? (tx > tz ? tx : tz) : (ty > tz ? ty : tz);
}

/// The outward unit normal (frame components) of the face nearest w, a
/// point on or near the box's surface in its own frame: the face of the
/// slab whose exact distance term is largest (as sol_box_pattern_uv).
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_box_light_normal(SOL_LIGHT_VEC3 w, SOL_LIGHT_VEC3 half_size) {
  const SOL_REAL tx = asinh((abs(w.x) - half_size.x) * exp(-w.z));
  const SOL_REAL ty = asinh((abs(w.y) - half_size.y) * exp(w.z));
  const SOL_REAL tz = abs(w.z) - half_size.z;
  if (tx >= ty && tx >= tz) return SOL_LIGHT_VEC3(w.x >= 0.0 ? 1.0 : -1.0, 0.0, 0.0);
  if (ty >= tz) return SOL_LIGHT_VEC3(0.0, w.y >= 0.0 ? 1.0 : -1.0, 0.0);
  return SOL_LIGHT_VEC3(0.0, 0.0, w.z >= 0.0 ? 1.0 : -1.0);
}

/// Whether a path's vertex at wx (the box's own frame) lies on the face
/// that holds the light point wy: within 1e-3 of the surface, on the same
/// face. Next-event estimation leaves such a point to reflection sampling:
/// on a face x or y = const (totally geodesic) their geodesic runs in the
/// face, and on a face z = const it grazes it, a march that may not end.
SOL_SHARED_FUNCTION bool sol_box_light_same_face(SOL_LIGHT_VEC3 wx, SOL_LIGHT_VEC3 wy, SOL_LIGHT_VEC3 half_size) {
  return abs(sol_box_light_bound(wx, half_size)) < 1e-3 &&
         sol_box_light_normal(wx, half_size) == sol_box_light_normal(wy, half_size);
}

// Balls drawn by their bound (sol::sdf_ball): in the ball's own frame w =
// centre⁻¹·q the surface is max(d_xz, d_yz) = r, d_xz the distance of the
// projections to the hyperbolic plane (x, z) (metric e^{−2z}dx² + dz²,
// cosh d_xz = cosh z + x² e^{−z}/2) and d_yz that to (y, z) (e^{2z}dy² +
// dz², cosh d_yz = cosh z + y² e^{z}/2). It has two pieces: A, where
// d_xz = r and d_yz <= r, a cylinder along y over the hyperbolic circle of
// radius r, and B, where d_yz = r and d_xz <= r, one along x. In the upper
// half-plane model (x, e^{z}) of the first plane the circle is Euclidean,
// centre (0, cosh r), radius sinh r: x = sinh r cos φ, e^{z} = cosh r +
// sinh r sin φ, with hyperbolic arc length sinh r dφ / e^{z}; the y-lines
// have |∂y| = e^{z}, orthogonal to it, so A's area element is
// sinh r dφ dy, and |y| <= Y(z) = √(2 (cosh r − cosh z) e^{−z}) on it.
// Likewise B: y = sinh r cos φ, e^{−z} = cosh r + sinh r sin φ, area
// element sinh r dφ dx, |x| <= X(z) = √(2 (cosh r − cosh z) e^{z}).

/// The piece of the bound ball's surface nearest w (its own frame): A
/// (true) where the (x, z) term is the larger, else B.
SOL_SHARED_FUNCTION bool sol_ball_light_piece_a(SOL_LIGHT_VEC3 w) {
  return w.x * w.x * exp(-w.z) >= w.y * w.y * exp(w.z);
}

/// The point of the bound ball's surface (its own frame) that three
/// uniform numbers in [0, 1) draw: u0 picks a piece (A below 1/2), u1 its
/// angle φ = 2π u1, u2 the coordinate along it, uniform on [−Y(z), Y(z)]
/// (A) or [−X(z), X(z)] (B): density sol_ball_light_density per unit area.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_ball_light_point(SOL_REAL radius, SOL_REAL u0, SOL_REAL u1, SOL_REAL u2) {
  const SOL_REAL phi = 6.28318530717958647692 * u1;
  const SOL_REAL lift = log(cosh(radius) + sinh(radius) * sin(phi)), across = sinh(radius) * cos(phi);
  const SOL_REAL room = 2.0 * max(SOL_REAL(0.0), cosh(radius) - cosh(lift));
  const SOL_REAL along = 2.0 * u2 - 1.0;
  if (u0 < 0.5) return SOL_LIGHT_VEC3(across, along * sqrt(room * exp(-lift)), lift);
  return SOL_LIGHT_VEC3(along * sqrt(room * exp(-lift)), across, -lift);
}

/// sol_ball_light_point's density per unit area at w on the surface: a
/// half (the piece) over 2π (the angle), over the coordinate's range 2Y
/// (or 2X), over the area element's sinh r.
SOL_SHARED_FUNCTION SOL_REAL sol_ball_light_density(SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_REAL room = 2.0 * max(SOL_REAL(0.0), cosh(radius) - cosh(w.z));
  const SOL_REAL half_range = sqrt(room * exp(sol_ball_light_piece_a(w) ? -w.z : w.z));
  return 1.0 / (8.0 * 3.14159265358979323846 * sinh(radius) * max(half_range, SOL_REAL(1e-30)));
}

/// The bound's outward unit normal at w (its own frame) on the piece that
/// holds it: the gradient of d_xz, (x, 0, sinh z − x² e^{−z}/2) / sinh d_xz
/// in frame components (A), or of d_yz, (0, y, sinh z + y² e^{z}/2) / sinh d_yz (B).
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_ball_light_normal(SOL_LIGHT_VEC3 w) {
  if (sol_ball_light_piece_a(w)) return normalize(SOL_LIGHT_VEC3(w.x, 0.0, sinh(w.z) - 0.5 * w.x * w.x * exp(-w.z)));
  return normalize(SOL_LIGHT_VEC3(0.0, w.y, sinh(w.z) + 0.5 * w.y * w.y * exp(w.z)));
}

/// The bound at w less the radius (sol::sdf_ball about the origin): 0 on the surface.
SOL_SHARED_FUNCTION SOL_REAL sol_ball_light_bound(SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_REAL a = max(0.5 * w.x * w.x * exp(-w.z), 0.5 * w.y * w.y * exp(w.z));
  const SOL_REAL sh = sinh(0.5 * w.z);
  return 2.0 * asinh(sqrt(sh * sh + 0.5 * a)) - radius;
}

#undef SOL_SHARED_FUNCTION
#undef SOL_LIGHT_VEC3
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_SURFACE_LIGHT_H
