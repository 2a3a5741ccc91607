// The denoiser's guides against the colour, for the CPU's tests
// (denoise_test.cpp) and the kernel's (kernel_denoise_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <sol/sol.hpp>

#include "support/textures.hpp"

namespace sol::test {

// A scene where every sample's colour is its first hit's albedo (the
// direct light with ambient 1 and no fog) or its emission (paths of no
// bounce, no lights, no fog), rendered with `samples` a pixel.
inline sol::RenderResult render_guides(sol::Renderer& renderer, bool emission, int samples) {
  sol::Scene scene = sol::preset_scene("sandwich");
  scene.fog_density = 0.0;
  scene.lights.clear();
  sol::RenderOptions o{.width = 32, .height = 24, .samples = samples, .guides = true};
  if (emission) {
    scene.objects[0].emission = {0.6, 0.5, 0.35};
    scene.objects[1].emission = {0.1, 0.2, 0.3};
    scene.max_bounces = 0;
    o.transport = sol::Transport::Path;
  } else {
    scene.ambient = 1.0;
  }
  return sol::render_scene(renderer, scene, o);
}

// The albedo and emission guides of `samples` a pixel are the samples'
// means: equal to the colour where it is the albedo (or the emission)
// alone, to `tolerance`, and apart from the centre sample's (one sample)
// on the circles' edges. Also run on the kernel (kernel_denoise_test.cpp).
inline void expect_guides_are_the_samples_means(sol::Renderer& renderer, double tolerance) {
  for (const bool emission : {false, true}) {
    const char* which = emission ? "emission" : "albedo";
    const sol::RenderResult many = render_guides(renderer, emission, 16), one = render_guides(renderer, emission, 1);
    const std::vector<float>& guide = emission ? many.emission : many.albedo;
    const std::vector<float>& centre = emission ? one.emission : one.albedo;
    double worst = 0.0;
    int blended = 0;
    for (std::size_t k = 0; k < many.object.size(); ++k) {
      bool apart = false;
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(static_cast<double>(guide[3 * k + c]) - many.rgba[4 * k + c]));
        apart = apart || std::abs(guide[3 * k + c] - centre[3 * k + c]) > 0.01;
      }
      blended += apart ? 1 : 0;
    }
    EXPECT_LT(worst, tolerance) << which;
    // The circles' edges cross a quarter of the pixels at this size (193
    // of 768); the emission's blends lie where the planes' hits give way
    // to misses (47).
    EXPECT_GT(blended, emission ? 20 : 100) << which;
  }
}

// The light moment of a render of 8 samples a pixel is the mean over them
// of the square of each sample's light's luminance (its colour less its
// emission, sol/denoise.h), each taken from a render of that sample alone
// (first_sample: the same sample, path and all): to `tolerance` times the
// larger of 1 and the moment. The glowing sandwich seen through fog (the
// emission less by the fog's transmittance), alone (the kernel shades its
// paths in a pass after the march's) and with an exact ball (paths from the
// eye, march/passes.glsl).
inline void expect_light_moment_is_the_samples_mean_square(sol::Renderer& renderer, double tolerance) {
  for (const bool ball : {false, true}) {
    sol::Scene scene = glowing_sandwich();
    scene.fog_density = 0.1;
    if (ball) {
      const glm::dvec3 ahead = scene.camera.position + 1.5 * glm::normalize(scene.camera.forward);
      scene.objects.push_back({sol::Ball{ahead, 0.3, true}, {0.8, 0.3, 0.2}});
    }
    renderer.set_world(scene);
    sol::RenderOptions o{.width = 20, .height = 15, .samples = 8, .transport = sol::Transport::Path, .seed = 9, .guides = true};
    const sol::RenderResult all = renderer.render(scene.camera, o);
    ASSERT_EQ(all.light_moment.size(), all.object.size());
    EXPECT_EQ(all.samples, 8);
    std::vector<double> squares(all.object.size(), 0.0);
    for (int s = 0; s < o.samples; ++s) {
      sol::RenderOptions one = o;
      one.first_sample = s;
      one.samples = 1;
      one.aovs = s == 0;
      const sol::RenderResult r = renderer.render(scene.camera, one);
      for (std::size_t k = 0; k < squares.size(); ++k) {
        const glm::dvec3 light(r.rgba[4 * k] - r.emission[3 * k], r.rgba[4 * k + 1] - r.emission[3 * k + 1],
                               r.rgba[4 * k + 2] - r.emission[3 * k + 2]);
        squares[k] += std::pow(0.2126 * light.x + 0.7152 * light.y + 0.0722 * light.z, 2.0) / o.samples;
      }
    }
    double worst = 0.0, largest = 0.0;
    int spread = 0;  // pixels whose samples' lights differ (the moment above the mean's square)
    for (std::size_t k = 0; k < squares.size(); ++k) {
      worst = std::max(worst, std::abs(all.light_moment[k] - squares[k]) / std::max(1.0, squares[k]));
      largest = std::max(largest, squares[k]);
      const double mean = 0.2126 * (all.rgba[4 * k] - all.emission[3 * k]) + 0.7152 * (all.rgba[4 * k + 1] - all.emission[3 * k + 1]) +
                          0.0722 * (all.rgba[4 * k + 2] - all.emission[3 * k + 2]);
      spread += squares[k] > mean * mean + 1e-4 ? 1 : 0;
    }
    EXPECT_LT(worst, tolerance) << (ball ? "with the exact ball" : "planes");
    EXPECT_GT(largest, 0.01) << "no light";
    EXPECT_GT(spread, 100) << "samples alike";
  }
}

}  // namespace sol::test
