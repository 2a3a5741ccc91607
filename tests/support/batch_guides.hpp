// Renders in batches join their guides (sol::programs::render_batches),
// for the CPU's tests (programs_test.cpp) and the kernel's
// (kernel_denoise_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "sampling.hpp"
#include "support/textures.hpp"

namespace sol::test {

// A render in batches (sol::programs::render_batches, as solrender's
// --time-limit: 14 samples in pairs of 1, 2 and 4) joins every batch's
// albedo and emission as it joins their colours: the guides, like the
// colour, are those of one render of the 14 samples to `tolerance`, the
// normal sample 0's; the first batch's alone differ on the circles' edges.
inline void expect_batches_join_the_guides(sol::Renderer& renderer, double tolerance) {
  const sol::Scene scene = glowing_sandwich();  // (glowing circles: edges of albedo and emission)
  renderer.set_world(scene);
  const sol::RenderOptions base{.width = 24, .height = 18, .transport = sol::Transport::Path, .seed = 4, .guides = true};
  sol::RenderResult first;
  const auto batch = [&](int from, int count, bool aovs) {
    sol::RenderOptions o = base;
    o.first_sample = from;
    o.samples = count;
    o.aovs = aovs;
    sol::RenderResult r = renderer.render(scene.camera, o);
    if (from == 0) first = r;
    return r;
  };
  sol::programs::SamplingGoal goal;
  goal.noise = 1e-9;  // (never reached: all 14)
  goal.max_samples = 14;
  sol::programs::SamplingReport report;
  const sol::RenderResult joined = sol::programs::render_batches(batch, true, goal, report);
  sol::RenderOptions all = base;
  all.samples = 14;
  const sol::RenderResult one = renderer.render(scene.camera, all);
  ASSERT_EQ(report.samples, 14);
  const auto worst = [](const std::vector<float>& a, const std::vector<float>& b, std::size_t stride) {
    double d = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      if (stride != 4 || k % 4 != 3) d = std::max(d, std::abs(static_cast<double>(a[k]) - b[k]));
    }
    return d;
  };
  ASSERT_EQ(joined.albedo.size(), one.albedo.size());
  ASSERT_EQ(joined.emission.size(), one.emission.size());
  EXPECT_LT(worst(joined.rgba, one.rgba, 4), tolerance) << "colour";
  EXPECT_LT(worst(joined.albedo, one.albedo, 3), tolerance) << "albedo";
  EXPECT_LT(worst(joined.emission, one.emission, 3), tolerance) << "emission";
  EXPECT_EQ(joined.normal, one.normal);
  EXPECT_GT(worst(first.albedo, one.albedo, 3), 0.05) << "the first batch's albedo alone";
  // The light moment too (squares up to about 1: the same tolerance), and the count of samples.
  ASSERT_EQ(joined.light_moment.size(), one.light_moment.size());
  EXPECT_LT(worst(joined.light_moment, one.light_moment, 1), tolerance) << "light moment";
  EXPECT_EQ(joined.samples, 14);
  EXPECT_EQ(one.samples, 14);
}

}  // namespace sol::test
