// Rendering until an image is good enough: batches of samples (consecutive
// ranges, RenderOptions::first_sample) until a time limit or a noise target
// is reached (solrender --time-limit, --noise-target).
//
// The batches come in pairs of equal size, the first of each pair summed
// into one half-image A and the second into B: A and B are independent
// estimates of the pixel, so their difference measures the noise of their
// mean (for means of n samples each with variance σ², E[(A − B)²] = 2σ²/n
// and the mean of both has variance σ²/(2n) = E[(A − B)²]/4). A pair is
// twice the size of the one before, or as large as the time left allows.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <sol/renderer.hpp>

namespace sol::programs {

/// When to stop adding samples.
struct SamplingGoal {
  std::optional<double> seconds;  ///< stop before this much time is spent (the batches' times so far predict the next)
  std::optional<double> noise;    ///< stop once noise_estimate falls to this
  int min_samples = 1;            ///< at least these (rounded up to an even count)
  int max_samples = 4096;         ///< at most these
};

/// How the render went.
struct SamplingReport {
  int samples = 0;       ///< per pixel, in all the batches
  double seconds = 0.0;  ///< spent in them
  double noise = -1.0;   ///< the last noise_estimate (-1: none, a single batch)
  bool noise_reached = false;
};

/// The estimated relative error of each pixel of the mean of two
/// half-images a and b (RGBA, 4 floats a pixel, width × height, each the
/// mean of as many samples): sqrt(mean(r²) / 4) over the pixel's 3 × 3
/// neighbourhood (clipped at the image's edges), r = (Ya − Yb) / max(Y,
/// 1e-3) each pixel's relative difference, Y the luminance (0.2126 R +
/// 0.7152 G + 0.0722 B) of the mean (a + b) / 2 (below 1e-3 a pixel is
/// black in 8 bits: its absolute difference counts instead).
std::vector<double> pixel_noise(const std::vector<double>& a, const std::vector<double>& b, int width, int height);
/// The noise of the image: the 99th percentile of pixel_noise (1 % of the
/// pixels may stay noisier: fireflies).
double noise_estimate(const std::vector<double>& a, const std::vector<double>& b, int width, int height);

/// Renders batch by batch: `batch(first, count, aovs)` renders samples
/// [first, first + count) (their mean colour; the AOVs when asked, only
/// for the first batch, with `aovs`), until `goal` says stop. The result is
/// the mean colour of all samples (the first batch's AOVs), as one render
/// of them all would be up to rounding; where every batch has the guides'
/// albedo and emission (RenderOptions::guides), theirs too. `progress`, when set, hears the
/// report after each pair.
RenderResult render_batches(const std::function<RenderResult(int first, int count, bool aovs)>& batch, bool aovs,
                            const SamplingGoal& goal, SamplingReport& report,
                            const std::function<void(const SamplingReport&)>& progress = {});

}  // namespace sol::programs
