// A glowing box as a light, written once for the CPU renderer (double) and
// the kernels (float): next-event estimation draws a point of its surface
// uniformly by area, and weighs it by the surface's total area
// (docs/lighting.md, "Glowing boxes"). In the box's own frame w = centre⁻¹·q
// the box is [−a, a] × [−b, b] × [−c, c], (a, b, c) its half size, and the
// metric e^{−2z}dx² + e^{2z}dy² + dz² gives its faces the area elements
//   z = ±c: dx dy             (area 4ab each)
//   x = ±a: e^{z} dy dz       (area 4b sinh c each)
//   y = ±b: e^{−z} dx dz      (area 4a sinh c each),
// and each face's unit normal is a frame vector, ±E1, ±E2 or ±E3, which a
// left translation keeps: the same at the box's world point. Valid C++
// (namespace sol::kernel, double) and GLSL (float), as sol/patterns.h.
#ifndef SOL_BOX_LIGHT_H
#define SOL_BOX_LIGHT_H

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
using std::exp;
using std::log;
using std::sinh;
using std::sqrt;
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

#undef SOL_SHARED_FUNCTION
#undef SOL_LIGHT_VEC3
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_BOX_LIGHT_H
