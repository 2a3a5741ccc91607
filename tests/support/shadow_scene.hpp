// A scene for the shadow tests (tests/shadow_test.cpp on the CPU,
// tests/kernel_connection_test.cpp for the kernel): a checkered floor
// z = -1, a ball (drawn with its bound) between it and an exact point
// light with shadows, seen from above.
#pragma once

#include <sol/scene.hpp>

namespace sol::test {

// An exact point light at `position` that casts shadows.
inline sol::Light shadowing_light(const glm::dvec3& position) {
  sol::Light light;
  light.type = sol::LightType::Point;
  light.position = position;
  light.exact = true;
  light.shadows = true;
  return light;
}

inline sol::Scene shadow_scene() {
  sol::Scene scene;
  scene.camera = {{0.0, 0.0, 0.3}, {1.0, 1.0, -0.9}, {0.0, 0.0, 1.0}, 80.0};
  scene.objects = {{sol::PlaneZ{-1.0}, {0.8, 0.8, 0.8}, sol::Pattern::Checker},
                   {sol::Ball{{1.2, 1.2, -0.55}, 0.25}, {0.9, 0.5, 0.3}}};
  scene.lights = {shadowing_light({1.3, 1.3, 0.1})};
  scene.ambient = 0.1;
  return scene;
}

}  // namespace sol::test
