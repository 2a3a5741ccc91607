// The denoiser and its guides on the kernel against the CPU's (the double
// reference): the albedo and normal AOVs the kernel writes are the CPU
// renderer's; the kernel's filter (compute/shaders/denoise.comp) gives the
// host's (sol::denoise) on the same image within float rounding; the
// albedo and emission are the samples' means; and on a path-traced scene
// the denoised image of N paths is nearer a reference of many paths than
// the raw image of 4N.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <sol/denoise.h>
#include <sol/denoise.hpp>
#include <sol/sol.hpp>
#include <sol/vk/march.hpp>

#include "support/batch_guides.hpp"
#include "support/guides.hpp"
#include "support/kernel.hpp"
#include "support/textures.hpp"

namespace {

using sol::test::expect_no_validation_errors;
using sol::test::glowing_sandwich;
using sol::test::vk_context;

sol::RenderResult render_paths(sol::Renderer& renderer, const sol::Scene& scene, int samples, std::uint64_t seed) {
  sol::RenderOptions o;
  o.width = 64;
  o.height = 48;
  o.samples = samples;
  o.seed = seed;
  o.transport = sol::Transport::Path;
  o.guides = true;  // (the denoiser's)
  return sol::render_scene(renderer, scene, o);
}

// The relative RMS difference of the colours (over the three channels), as render_bench --only path measures.
double relative_error(const sol::RenderResult& a, const sol::RenderResult& reference) {
  double squares = 0.0, reference_squares = 0.0;
  for (std::size_t k = 0; k < a.rgba.size(); ++k) {
    if (k % 4 == 3) continue;
    squares += std::pow(static_cast<double>(a.rgba[k]) - reference.rgba[k], 2.0);
    reference_squares += std::pow(static_cast<double>(reference.rgba[k]), 2.0);
  }
  return std::sqrt(squares / reference_squares);
}

TEST(KernelDenoise, TheAlbedoAndNormalAreTheCpus) {
  // Two worlds: the sandwich's patterned planes in Sol, and lattice-balls'
  // balls in the golden quotient (normals of every direction). Where both
  // devices hit the same object (a silhouette pixel may go either way in
  // float), the albedo agrees to float rounding unless the hit lies on a
  // pattern's edge (at most 2 % of the pixels: the hit point differs by
  // about 1e-5), and the normal's direction within 1e-3.
  for (const char* name : {"sandwich", "lattice-balls"}) {
    const sol::Scene scene = sol::preset_scene(name);
    sol::vk::MarchRenderer kernel(vk_context());
    const sol::RenderResult gpu = sol::test::render(kernel, scene, 48, 36, true);
    const sol::RenderResult cpu = sol::render_cpu(scene, {.width = 48, .height = 36, .guides = true});
    int same = 0, albedo_off = 0;
    for (std::size_t k = 0; k < cpu.object.size(); ++k) {
      if (gpu.object[k] != cpu.object[k]) continue;
      ++same;
      bool off = false;
      double dot = 0.0;
      for (int c = 0; c < 3; ++c) {
        off = off || std::abs(gpu.albedo[3 * k + c] - cpu.albedo[3 * k + c]) > 1e-5;
        dot += static_cast<double>(gpu.normal[3 * k + c]) * cpu.normal[3 * k + c];
      }
      albedo_off += off ? 1 : 0;
      if (cpu.object[k] != 0.0f) {
        EXPECT_GT(dot, 1.0 - 1e-3) << name << " pixel " << k;
      }
    }
    EXPECT_GT(same, 0.97 * static_cast<double>(cpu.object.size())) << name;
    EXPECT_LE(albedo_off, 0.02 * same) << name;
  }
  expect_no_validation_errors();
}

TEST(KernelDenoise, TheGuidesAreTheSamplesMeans) {
  // As the CPU's (denoise_test.cpp): the kernel's albedo and emission of
  // 16 samples equal its colour where that is the albedo or the emission
  // alone (float: the mean of 16 running blends rounds to about 1e-7 of
  // values below 1), and part from the centre's on the edges.
  sol::vk::MarchRenderer kernel(vk_context());
  sol::test::expect_guides_are_the_samples_means(kernel, 1e-5);
  expect_no_validation_errors();
}

TEST(KernelDenoise, TheLightMomentIsTheSamplesMeanSquare) {
  // As the CPU's: the kernel's light moment of 8 samples (the emission
  // guide's w, a running mean in float of squares below about 1, from the
  // march pass, the shade pass and paths from the eye) is the mean of the
  // squares of its samples rendered alone, to float's rounding of the blends.
  sol::vk::MarchRenderer kernel(vk_context());
  sol::test::expect_light_moment_is_the_samples_mean_square(kernel, 1e-5);
  expect_no_validation_errors();
}

TEST(KernelDenoise, BatchesJoinTheirGuides) {
  // As the CPU's: the kernel's batches' albedo and emission (running means
  // in float) joined are one render's (its running mean over all 14) to
  // float's rounding of the blends, 1e-5.
  sol::vk::MarchRenderer kernel(vk_context());
  sol::test::expect_batches_join_the_guides(kernel, 1e-5);
  expect_no_validation_errors();
}

TEST(KernelDenoise, TheKernelsFilterIsTheHosts) {
  // One image (a CPU render of 16 paths a pixel) filtered on the host in
  // double and on the kernel in float: the weights are the same formulas
  // (sol/denoise.h), so the colours differ by float rounding only (the
  // light is about 0.3, float's relative 6e-8 through some 200 weighted
  // sums: 1e-4 leaves room), in one eye and in two.
  const sol::Scene scene = glowing_sandwich();
  sol::CpuRenderer cpu(scene);
  sol::vk::MarchRenderer kernel(vk_context());
  kernel.set_world(scene);
  sol::RenderOptions o{.width = 40, .height = 30, .samples = 16, .transport = sol::Transport::Path, .seed = 5, .guides = true};
  for (const bool stereo : {false, true}) {
    // The noise from the samples' light moment, the filtered light held to
    // it (16 samples) or not (taken as 15), or from the neighbours.
    for (const int kind : {0, 1, 2}) {
      sol::RenderResult image = stereo ? cpu.render_stereo(scene.camera, 0.2, o) : cpu.render(scene.camera, o);
      if (kind == 1) image.samples = sol::kernel::kDenoiseClampSamples - 1;
      if (kind == 2) image.light_moment.clear();
      sol::RenderResult on_host = image, on_device = image;
      cpu.denoise(on_host, stereo ? 2 : 1);
      kernel.denoise(on_device, stereo ? 2 : 1);
      double worst = 0.0, changed = 0.0;
      for (std::size_t k = 0; k < image.rgba.size(); ++k) {
        worst = std::max(worst, std::abs(static_cast<double>(on_host.rgba[k]) - on_device.rgba[k]));
        changed = std::max(changed, std::abs(static_cast<double>(on_host.rgba[k]) - image.rgba[k]));
      }
      EXPECT_LT(worst, 1e-4) << (stereo ? "stereo" : "mono") << ", kind " << kind;
      EXPECT_GT(changed, 0.02) << "the filter changed nothing";
    }
  }
  expect_no_validation_errors();
}

TEST(KernelDenoise, PathsDenoisedBeatFourTimesAsManyRaw) {
  // The glowing sandwich at 64 × 48 on the kernel, against a reference of
  // 256 paths a pixel (another seed): the image of 2 paths denoised is
  // nearer it than the raw image of 8, and that of 8 paths than the raw
  // 32 (the filter's own error at many paths: with the centre's albedo
  // as the guide, about 0.067 on the edges' pixels, it lost there).
  // Measured against 2048 paths on the CPU by render_bench --only path:
  // 2 paths 0.064 denoised against 0.102 raw at 8, 8 paths 0.031 against
  // 0.050 at 32; the reference's own noise, about 0.035, adds to both alike.
  const sol::Scene scene = glowing_sandwich();
  sol::vk::MarchRenderer kernel(vk_context());
  const sol::RenderResult reference = render_paths(kernel, scene, 256, 1000);
  for (const int paths : {2, 8}) {
    sol::RenderResult few = render_paths(kernel, scene, paths, 2);
    const sol::RenderResult many = render_paths(kernel, scene, 4 * paths, 8);
    const double raw_few = relative_error(few, reference);
    kernel.denoise(few);
    const double denoised = relative_error(few, reference), raw_many = relative_error(many, reference);
    std::printf("relative error: %d paths %.4f, denoised %.4f; %d paths %.4f\n", paths, raw_few, denoised, 4 * paths, raw_many);
    EXPECT_LT(denoised, raw_many) << paths;
    EXPECT_LT(denoised, 0.5 * raw_few) << paths;
  }
  expect_no_validation_errors();
}

}  // namespace
