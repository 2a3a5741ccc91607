// The patterns drawn on objects, written once for the CPU renderer (double)
// and the kernels (float): a pattern's brightness at pattern coordinates
// (u, v), the gap bound of a cutout plane's holes, and each solid kind's
// pattern coordinates in its own frame w = anchor⁻¹·q (the anchor a ball's
// centre, a box's centre, a point of a tube's axis; each side computes w
// its own way). Valid C++ (namespace sol::kernel, double) and GLSL (float),
// as sol/box_bound.h; the C++ side is the reference's own arithmetic,
// operation for operation.
#ifndef SOL_PATTERNS_H
#define SOL_PATTERNS_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
namespace sol::kernel {
#define SOL_SHARED_FUNCTION inline
#define SOL_PATTERN_VEC2 glm::dvec2
#define SOL_PATTERN_VEC3 glm::dvec3
#define sol_atan2(y, x) std::atan2(y, x)
#define sol_hypot(x, y) std::hypot(x, y)
#define sol_fmod(x, y) std::fmod(x, y)
using std::abs;
using std::asinh;
using std::exp;
using std::floor;
using std::max;
using std::min;
using std::sqrt;
#else
#define SOL_SHARED_FUNCTION
#define SOL_PATTERN_VEC2 vec2
#define SOL_PATTERN_VEC3 vec3
#define sol_atan2(y, x) atan(y, x)
#define sol_hypot(x, y) length(vec2(x, y))
#define sol_fmod(x, y) mod(x, y)
#endif

// The brightness of pattern `pattern` (a kPattern* code) at (u, v): 1 on
// the circles' discs (radius kCircleRadius about the points of the unit
// grid) and on the checker's light squares (floor(u) + floor(v) even),
// kCircleDark and kCheckerDark elsewhere; 1 without a pattern.
SOL_SHARED_FUNCTION SOL_REAL sol_pattern_factor(int pattern, SOL_REAL u, SOL_REAL v) {
  if (pattern == kPatternCircles) {
    const SOL_REAL du = u - floor(u) - 0.5, dv = v - floor(v) - 0.5;
    return du * du + dv * dv < kCircleRadius * kCircleRadius ? 1.0 : kCircleDark;
  }
  if (pattern == kPatternChecker) return sol_fmod(floor(u) + floor(v), 2.0) == 0.0 ? 1.0 : kCheckerDark;
  return 1.0;
}

// A lower bound of the distance from a point at world (u, v) and height z,
// ez = e^{z}, to the solid part of a cutout plane z = c (its discs or light
// squares), to be combined with |z − c| by max; 0 where it cannot help.
// A point of the plane at planar offset (Δx, Δy) is at distance at least
// asinh(|Δx| e^{−z}) and asinh(|Δy| e^{z}) (the planes x, y = const through
// it). Checker, over a dark square: the light squares nearest in either
// sense share an edge with it. Circles: the nearest disc is the cell's own
// (the cells are the grid's Voronoi cells), inside the square [0.2, 0.8]²
// of the cell, and max(|Δx| e^{−z}, |Δy| e^{z}) ≥ e^{−|z|} |Δ| / √2 with
// |Δ| the planar gap to the disc.
SOL_SHARED_FUNCTION SOL_REAL sol_cutout_gap_bound(int pattern, SOL_REAL u, SOL_REAL v, SOL_REAL ez) {
  const SOL_REAL fu = u - floor(u), fv = v - floor(v);
  if (pattern == kPatternChecker) {
    if (sol_fmod(floor(u) + floor(v), 2.0) == 0.0) return 0.0;  // on a light square
    return asinh(min(min(fu, 1.0 - fu) / ez, min(fv, 1.0 - fv) * ez));
  }
  if (pattern != kPatternCircles) return 0.0;
  const SOL_REAL du = abs(fu - 0.5), dv = abs(fv - 0.5);
  const SOL_REAL r = kCircleRadius;
  const SOL_REAL boxes = max(max(SOL_REAL(0.0), du - r) / ez, max(SOL_REAL(0.0), dv - r) * ez);
  const SOL_REAL gap = max(SOL_REAL(0.0), sol_hypot(du, dv) - r);
  return asinh(max(boxes, min(ez, 1.0 / ez) * gap / sqrt(SOL_REAL(2.0))));
}

// A ball's pattern coordinates at w = centre⁻¹·q: kPatternCellsPerRadian
// times its longitude atan2(w_y, w_x) and latitude atan2(w_z, |w_xy|).
SOL_SHARED_FUNCTION SOL_PATTERN_VEC2 sol_ball_pattern_uv(SOL_PATTERN_VEC3 w) {
  return SOL_PATTERN_VEC2(kPatternCellsPerRadian * sol_atan2(w.y, w.x),
                          kPatternCellsPerRadian * sol_atan2(w.z, sol_hypot(w.x, w.y)));
}

// A box's at w = centre⁻¹·q, where its half widths are `half_size`: on the
// face nearest w (the slab whose exact distance term is largest) the two
// coordinates of w along it, in cells of half the smallest half width.
SOL_SHARED_FUNCTION SOL_PATTERN_VEC2 sol_box_pattern_uv(SOL_PATTERN_VEC3 w, SOL_PATTERN_VEC3 half_size) {
  const SOL_REAL tx = asinh((abs(w.x) - half_size.x) * exp(-w.z));
  const SOL_REAL ty = asinh((abs(w.y) - half_size.y) * exp(w.z));
  const SOL_REAL tz = abs(w.z) - half_size.z;
  const SOL_REAL cells = 2.0 / min(min(half_size.x, half_size.y), half_size.z);
  if (tx >= ty && tx >= tz) return cells * SOL_PATTERN_VEC2(w.y, w.z);
  if (ty >= tz) return cells * SOL_PATTERN_VEC2(w.x, w.z);
  return cells * SOL_PATTERN_VEC2(w.x, w.y);
}

// A tube's at w = through⁻¹·q: kPatternCellsPerRadian times the angle
// around the axis and the coordinate along it over the radius; a
// horizontal axis has the unit heading h (in w's frame).
SOL_SHARED_FUNCTION SOL_PATTERN_VEC2 sol_tube_pattern_uv(SOL_PATTERN_VEC3 w, bool vertical, SOL_PATTERN_VEC2 h,
                                                         SOL_REAL radius) {
  if (vertical) return SOL_PATTERN_VEC2(kPatternCellsPerRadian * sol_atan2(w.y, w.x), kPatternCellsPerRadian * w.z / radius);
  const SOL_REAL along = w.x * h.x + w.y * h.y, across = w.y * h.x - w.x * h.y;
  return SOL_PATTERN_VEC2(kPatternCellsPerRadian * sol_atan2(w.z, across), kPatternCellsPerRadian * along / radius);
}

#undef SOL_SHARED_FUNCTION
#undef SOL_PATTERN_VEC2
#undef SOL_PATTERN_VEC3
#undef sol_atan2
#undef sol_hypot
#undef sol_fmod
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_PATTERNS_H
