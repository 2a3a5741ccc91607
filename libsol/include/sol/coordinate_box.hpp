// Coordinate boxes: the sets [lo, hi] of Sol coordinates (a bound may be
// infinite), the nodes of the tree of bounds over a world's objects
// (sol/bounds_tree.hpp), and the lower bound of the Sol distance from a
// point to anything inside one.
//
// The bound is that of sol::distance_lower_bound, taken over the box: the
// projections (x, y, z) -> (x, z) and -> (y, z) onto the hyperbolic planes
// e^{-2z}dx² + dz² and e^{2z}dy² + dz² do not increase lengths, so the
// distance from q to the box is at least the hyperbolic distance from q's
// projection to the box's, a rectangle [x0, x1] x [z0, z1]. There, for a
// point at height z = q_z + s and horizontal gap g,
//   cosh d = cosh s + ½ g² e^{-(2 q_z + s)} = cosh s + A e^{-s},  A = ½ (g e^{-q_z})²,
// least at the rectangle's nearest x (g the gap of q_x to [x0, x1]), and,
// being convex in s, least over [z0 - q_z, z1 - q_z] at the clamp of its
// free minimum, where sinh s = A e^{-s}: e^{2s} = 1 + 2A. Written as
// d = 2 asinh √(sinh²(s/2) + ½ A e^{-s}) for small distances' accuracy. The
// (y, z) plane is the same with z -> -z (A = ½ (g_y e^{q_z})²). The larger
// of the two is the bound: exact for a box that is a point (it is then
// sol::distance_lower_bound), 0 inside the box, and 1-Lipschitz. Its
// projected part is sol/box_bound.h, which the kernel compiles too. With z
// unbounded it is the distance to the slab's nearer face plane, asinh(g
// e^{∓q_z}); a box's own bound of slab distances (sol::Box::distance) is
// weaker away from the box, where it is about half of this one.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/box_bound.h"

namespace sol {

struct CoordinateBox {
  /// The least and largest coordinates; empty where lo > hi (the default).
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};

  /// The box of every point: for an object unbounded in every direction.
  static CoordinateBox everywhere() {
    const double inf = std::numeric_limits<double>::infinity();
    return {glm::dvec3(-inf), glm::dvec3(inf)};
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  bool contains(const glm::dvec3& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  /// Grows the box to hold `other` as well.
  void add(const CoordinateBox& other) {
    lo = glm::min(lo, other.lo);
    hi = glm::max(hi, other.hi);
  }
  /// A point inside the box to sort it by: the middle of each finite
  /// interval, its finite end where only one is, 0 where neither is.
  glm::dvec3 anchor() const {
    glm::dvec3 a(0.0);
    for (int i = 0; i < 3; ++i) {
      const bool low = std::isfinite(lo[i]), high = std::isfinite(hi[i]);
      a[i] = low && high ? 0.5 * (lo[i] + hi[i]) : low ? lo[i] : high ? hi[i] : 0.0;
    }
    return a;
  }
};


/// A lower bound of the Sol distance from q to every point of the box (see
/// above): 0 inside it, +infinity for an empty box. `e` = (e^{-q_z}, e^{q_z}),
/// which a search of many boxes from one point takes once.
inline double box_distance_lower_bound(const CoordinateBox& box, const glm::dvec3& q, const glm::dvec2& e) {
  if (box.empty()) return std::numeric_limits<double>::infinity();
  const double gx = std::max({0.0, box.lo.x - q.x, q.x - box.hi.x});
  const double gy = std::max({0.0, box.lo.y - q.y, q.y - box.hi.y});
  return std::max(kernel::sol_projected_box_distance(gx, q.z, e.x, 1.0, box.lo.z, box.hi.z),
                  kernel::sol_projected_box_distance(gy, q.z, e.y, -1.0, box.lo.z, box.hi.z));
}

inline double box_distance_lower_bound(const CoordinateBox& box, const glm::dvec3& q) {
  return box_distance_lower_bound(box, q, glm::dvec2(std::exp(-q.z), std::exp(q.z)));
}

}  // namespace sol
