// Boxes for the tests of the CPU renderer (tests/box_test.cpp) and of the
// kernel (tests/kernel_test.cpp): a scene with one box, and how far a
// render's hits lie from the faces of the boxes they may lie on.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <sol/sol.hpp>

namespace sol::test {

// The coordinate box of center · B: [x0 ± a e^{z0}] x [y0 ± b e^{-z0}] x [z0 ± c].
struct CoordinateBox {
  glm::dvec3 lo, hi;
};
inline CoordinateBox coordinate_box(const sol::Box& box) {
  const glm::dvec3 half(box.half_size.x * std::exp(box.center.z), box.half_size.y * std::exp(-box.center.z),
                        box.half_size.z);
  return {box.center - half, box.center + half};
}

// How far p is from the boundary of the nearest of `boxes`, from their
// coordinate intervals alone: outside, the largest coordinate excess;
// inside, the least depth; each in Sol lengths to first order (a
// coordinate offset δ at height z is e^{-z} δ along x, e^{z} δ along y).
inline double distance_from_faces(const glm::dvec3& p, const std::vector<sol::Box>& boxes) {
  double nearest = 1e30;
  const glm::dvec3 scale(std::exp(-p.z), std::exp(p.z), 1.0);
  for (const sol::Box& box : boxes) {
    const CoordinateBox c = coordinate_box(box);
    double outside = 0.0, inside = 1e30;
    for (int a = 0; a < 3; ++a) {
      outside = std::max(outside, std::max({0.0, c.lo[a] - p[a], p[a] - c.hi[a]}) * scale[a]);
      inside = std::min(inside, std::min(p[a] - c.lo[a], c.hi[a] - p[a]) * scale[a]);
    }
    nearest = std::min(nearest, outside > 0.0 ? outside : std::max(0.0, inside));
  }
  return nearest;
}

// A render's hits and the farthest of them from the faces of `boxes`.
struct FaceHits {
  int hits = 0;
  double farthest = 0.0;
};
inline FaceHits hits_on_faces(const sol::RenderResult& r, const std::vector<sol::Box>& boxes) {
  FaceHits f;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    if (r.object[k] == 0.0f) continue;
    ++f.hits;
    f.farthest = std::max(f.farthest, distance_from_faces(glm::dvec3(r.px[k], r.py[k], r.pz[k]), boxes));
  }
  return f;
}

// One box in Sol, seen from beside it.
inline sol::Scene box_scene() {
  // (From a preset's world, out of line: GCC 12 warns of an uninitialised
  // light when a default World is built inline here.)
  sol::Scene s = sol::preset_scene("plane");
  s.camera = {{0.0, 0.0, 0.3}, {1.0, 0.4, -0.1}, {0.0, 0.0, 1.0}, 80.0};
  s.objects = {{sol::Box{{1.5, 0.5, 0.2}, {0.3, 0.4, 0.25}}, {0.9, 0.6, 0.3}, sol::Pattern::Checker}};
  s.max_distance = 8.0;
  return s;
}

// The same seen from inside the slab of its x faces (x within the box's x
// range, the camera outside the box, looking along y at it).
inline sol::Scene box_scene_from_its_slab() {
  sol::Scene s = box_scene();
  const CoordinateBox c = coordinate_box(std::get<sol::Box>(s.objects[0].shape));
  s.camera = {{0.5 * (c.lo.x + c.hi.x), c.lo.y - 0.6, 0.2}, {0.0, 1.0, 0.05}, {0.0, 0.0, 1.0}, 90.0};
  return s;
}

// The images around D of a quotient scene's boxes (sol::quotient_images).
inline std::vector<sol::Box> box_images(const sol::Scene& scene) {
  std::vector<sol::Box> out;
  for (const sol::MarchObject& m : sol::quotient_images(scene)) {
    if (const auto* b = std::get_if<sol::Box>(&m.shape)) out.push_back(*b);
  }
  return out;
}

}  // namespace sol::test
