// The edges of what scenes may hold (docs/scene-format.md): cameras at the
// largest accepted coordinates and heights, and a count of the non-finite
// values a render produced (colour and AOVs).
#pragma once

#include <cmath>
#include <vector>

#include <glm/vec3.hpp>
#include <sol/render.hpp>

namespace sol::test {

/// Camera positions at the corners of the accepted ranges: |x|, |y| = 1e15
/// and heights ±80.
inline std::vector<glm::dvec3> extreme_positions() {
  return {{1e15, -1e15, 80.0}, {-1e15, 1e15, -80.0}, {0.5, 0.5, 80.0}, {0.5, 0.5, -80.0}};
}

inline int non_finite_values(const RenderResult& r) {
  int bad = 0;
  for (const std::vector<float>* channel : {&r.rgba, &r.object, &r.distance, &r.px, &r.py, &r.pz, &r.steps}) {
    for (float v : *channel) bad += !std::isfinite(v);
  }
  return bad;
}

}  // namespace sol::test
