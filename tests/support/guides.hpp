// The denoiser's guides against the colour, for the CPU's tests
// (denoise_test.cpp) and the kernel's (kernel_denoise_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

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

}  // namespace sol::test
