// Composites for the tests of the CPU renderer (tests/composite_test.cpp)
// and of the kernel (tests/kernel_test.cpp): how far a render's hits lie
// from the boundary of the composite they hit, from distances to its parts
// computed here independently of the renderers: the exact Sol distance to
// an exact ball's centre (sol::distance, tested against 50-digit
// references) and the exact distances to a box's three slabs (asinh(s
// e^{∓z}) across the planes x, y = const, |Δz| across z = const).
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace sol::test {

// The signed distance to a part, from its definition: an exact ball's
// d(q, c) − r; a box's largest slab distance, which is 0 exactly on its
// faces (each slab's distance is the exact distance to its nearer plane).
inline double part_distance(const sol::Shape& part, const glm::dvec3& q) {
  if (const auto* b = std::get_if<sol::Ball>(&part)) {
    EXPECT_TRUE(b->exact) << "the checks take exact balls only";
    return sol::distance(q, b->center) - b->radius;
  }
  const auto& box = std::get<sol::Box>(part);
  const double sx = std::abs(q.x - box.center.x) - box.half_size.x * std::exp(box.center.z);
  const double sy = std::abs(q.y - box.center.y) - box.half_size.y * std::exp(-box.center.z);
  const double sz = std::abs(q.z - box.center.z) - box.half_size.z;
  return std::max({std::asinh(sx * std::exp(-q.z)), std::asinh(sy * std::exp(q.z)), sz});
}

// How far q is from lying on the boundary of the composite, and on which
// part's surface it lies (0: A's, 1: B's): on A's surface (|d_A| small)
// where the set keeps A's surface (outside B for a union or a difference,
// inside B for an intersection), or on B's where it keeps B's (outside A
// for a union, inside A otherwise).
struct OnBoundary {
  double residual;
  int part;
};
inline OnBoundary on_boundary(const sol::Composite& c, const glm::dvec3& q) {
  const double a = part_distance(c.parts->a, q), b = part_distance(c.parts->b, q);
  // Where a surface is kept: the other part's distance must have this sign (or be within the residual of it).
  const auto kept = [](double other, bool outside) { return outside ? std::max(0.0, -other) : std::max(0.0, other); };
  const bool union_ = c.op == sol::CompositeOp::Union;
  const double on_a = std::max(std::abs(a), kept(b, c.op != sol::CompositeOp::Intersection));
  const double on_b = std::max(std::abs(b), kept(a, union_));
  return on_a <= on_b ? OnBoundary{on_a, 0} : OnBoundary{on_b, 1};
}

// The hits of a render on scene object `object` (1-based, the AOV's
// code), each against the nearest boundary of `composites` (pairs of the
// 0-based scene object and a composite in world coordinates: an object's,
// or in the quotient each of its images'): how many lie on A's surface and
// on B's, and the largest residual.
struct PartHits {
  int on_a = 0, on_b = 0;
  double farthest = 0.0;
};
inline PartHits hits_on_boundary(const sol::RenderResult& r,
                                 const std::vector<std::pair<int, sol::Composite>>& composites, int object) {
  PartHits h;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    if (static_cast<int>(r.object[k]) != object) continue;
    const glm::dvec3 q(r.px[k], r.py[k], r.pz[k]);
    OnBoundary best{1e30, 0};
    for (const auto& [index, c] : composites) {
      if (index + 1 != object) continue;
      const OnBoundary o = on_boundary(c, q);
      if (o.residual < best.residual) best = o;
    }
    h.farthest = std::max(h.farthest, best.residual);
    (best.part == 0 ? h.on_a : h.on_b) += 1;
  }
  return h;
}

}  // namespace sol::test
