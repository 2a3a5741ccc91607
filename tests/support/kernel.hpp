// What the Vulkan kernel tests share: one validating context per process,
// the check that it reported no validation error, and the comparison of a
// kernel image with the CPU renderer's.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <sol/render.hpp>
#include <sol/renderer.hpp>
#include <sol/vk/context.hpp>

namespace sol::test {

/// The context every kernel test runs on (lavapipe under ctest), with the
/// validation layer on; created at first use, shared by all tests.
inline sol::vk::Context& vk_context() {
  static sol::vk::Context ctx({.preference = sol::vk::DevicePreference::Auto, .validation = true});
  return ctx;
}

/// Fails the running test for every validation error the context collected.
inline void expect_no_validation_errors() {
  for (const std::string& e : vk_context().validation_errors()) ADD_FAILURE() << "validation: " << e;
}

/// A renderer's image of a scene, width x height (sol::render_scene), with
/// the albedo and normal AOVs too where `guides`.
inline sol::RenderResult render(sol::Renderer& renderer, const sol::Scene& scene, int width, int height, bool guides = false) {
  return sol::render_scene(renderer, scene, {.width = width, .height = height, .guides = guides});
}

/// Both eyes of sol::stereo_eyes(scene.camera, ipd), each width x height, side by side.
inline sol::RenderResult render_stereo(sol::Renderer& renderer, const sol::Scene& scene, int width, int height, double ipd) {
  renderer.set_world(scene);
  return renderer.render_stereo(scene.camera, ipd, {.width = width, .height = height});
}

/// Two renders of one scene at one size, pixel by pixel.
struct ImageComparison {
  int pixels = 0;
  int mask_differs = 0;   ///< pixels where one hits another object (or nothing)
  int color_differs = 0;  ///< same object, some channel differs by more than the threshold
  double distance = 0;    ///< worst |Δ arc length| where both hit
  double worst_color = 0; ///< worst channel difference where the objects agree
};

inline ImageComparison compare_images(const sol::RenderResult& a, const sol::RenderResult& b, float color_threshold) {
  ImageComparison c;
  c.pixels = a.width * a.height;
  for (int k = 0; k < c.pixels; ++k) {
    if (a.object[k] != b.object[k]) {
      ++c.mask_differs;
      continue;
    }
    if (a.object[k] != 0) c.distance = std::max(c.distance, static_cast<double>(std::abs(a.distance[k] - b.distance[k])));
    float e = 0.0f;
    for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(a.rgba[4 * k + ch] - b.rgba[4 * k + ch]));
    c.worst_color = std::max(c.worst_color, static_cast<double>(e));
    c.color_differs += e > color_threshold;
  }
  return c;
}

}  // namespace sol::test
