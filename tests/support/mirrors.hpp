// The mirror's test scenes (tests/render_test.cpp for the CPU renderer,
// tests/kernel_test.cpp for the kernel). The plane x = 0 is totally
// geodesic and (x, y, z) -> (-x, y, z) is an isometry of Sol (and an
// automorphism of its group), so a perfect mirror x = 0 shows what the
// scene without it shows with every object reflected behind it added.
// Ambient light alone: a surface's colour then depends on no direction.
#pragma once

#include <sol/sol.hpp>

namespace sol::test {

// The objects in front of the mirror (x > 0) and a floor z = -1 whose
// circles are symmetric about x = 0; with `mirror`, the perfect mirror x =
// 0, else every object reflected (the floor is its own reflection).
[[gnu::noinline]] inline sol::Scene mirror_scene(bool mirror) {
  sol::Scene s;
  s.camera = {{2.2, -0.4, 0.2}, {-1.0, 0.35, -0.1}, {0.0, 0.0, 1.0}, 90.0};
  s.lights.clear();
  s.ambient = 1.0;
  s.objects = {{sol::PlaneZ{-1.0}, {0.95, 0.75, 0.3}, sol::Pattern::Circles},
               {sol::Ball{{1.0, 0.5, 0.1}, 0.35}, {0.35, 0.6, 0.95}},
               {sol::Box{{0.7, -0.6, -0.3}, {0.15, 0.2, 0.25}}, {0.4, 0.85, 0.45}}};
  if (mirror) {
    sol::SceneObject glass{sol::PlaneX{0.0}, {0.2, 0.2, 0.2}};
    glass.mirror = 1.0;
    s.objects.push_back(glass);
  } else {
    s.objects.push_back({sol::Ball{{-1.0, 0.5, 0.1}, 0.35}, {0.35, 0.6, 0.95}});
    s.objects.push_back({sol::Box{{-0.7, -0.6, -0.3}, {0.15, 0.2, 0.25}}, {0.4, 0.85, 0.45}});
  }
  s.max_distance = 12.0;
  return s;
}

// Pixels whose colours differ by more than `tolerance` in a channel.
inline int colour_differences(const sol::RenderResult& a, const sol::RenderResult& b, double tolerance) {
  int differ = 0;
  for (std::size_t k = 0; k + 3 < a.rgba.size(); k += 4) {
    bool d = false;
    for (std::size_t c = 0; c < 3; ++c) d = d || std::abs(a.rgba[k + c] - b.rgba[k + c]) > tolerance;
    differ += d ? 1 : 0;
  }
  return differ;
}

}  // namespace sol::test
