#include "sampling.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <sol/error.hpp>

namespace sol::programs {
namespace {

double luminance(const std::vector<double>& rgba, std::size_t k) {
  return 0.2126 * rgba[4 * k] + 0.7152 * rgba[4 * k + 1] + 0.0722 * rgba[4 * k + 2];
}

}  // namespace

std::vector<double> pixel_noise(const std::vector<double>& a, const std::vector<double>& b, int width, int height) {
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  // Each pixel's relative difference, squared: (Ya - Yb) / max(Y, 1e-3).
  std::vector<double> r2(w * h), out(w * h);
  for (std::size_t k = 0; k < w * h; ++k) {
    const double ya = luminance(a, k), yb = luminance(b, k);
    const double r = (ya - yb) / std::max(0.5 * (ya + yb), 1e-3);
    r2[k] = r * r;
  }
  for (std::size_t j = 0; j < h; ++j) {
    for (std::size_t i = 0; i < w; ++i) {
      double sum = 0.0;
      int n = 0;
      for (std::size_t y = j > 0 ? j - 1 : 0; y <= std::min(j + 1, h - 1); ++y) {
        for (std::size_t x = i > 0 ? i - 1 : 0; x <= std::min(i + 1, w - 1); ++x) {
          sum += r2[y * w + x];
          ++n;
        }
      }
      out[j * w + i] = std::sqrt(sum / n / 4.0);
    }
  }
  return out;
}

double noise_estimate(const std::vector<double>& a, const std::vector<double>& b, int width, int height) {
  std::vector<double> e = pixel_noise(a, b, width, height);
  if (e.empty()) return 0.0;
  const auto at = static_cast<std::size_t>(std::floor(0.99 * static_cast<double>(e.size() - 1)));
  std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(at), e.end());
  return e[at];
}

RenderResult render_batches(const std::function<RenderResult(int first, int count, bool aovs)>& batch, bool aovs,
                            const SamplingGoal& goal, SamplingReport& report,
                            const std::function<void(const SamplingReport&)>& progress) {
  if (goal.min_samples < 1 || goal.max_samples < goal.min_samples || goal.max_samples > 4096) {
    throw InvalidArgument("sol::programs::render_batches: samples must satisfy 1 <= min <= max <= 4096");
  }
  const auto begin = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count(); };
  report = {};
  RenderResult result;
  std::vector<double> half[2];  // the sums of the pairs' first and second batches
  int counted[2] = {0, 0};
  double device_ms = 0.0;
  std::uint64_t out_of_steps = 0;
  // The guides' albedo, emission and light moment, summed as the colour where every batch has them.
  std::vector<double> albedo, emission, moment;
  bool moments_missing = false;
  int guided = 0;
  int pair = std::max(1, (goal.min_samples + 1) / 2);
  for (;;) {
    for (int side = 0; side < 2; ++side) {
      RenderResult r = batch(report.samples, pair, aovs && report.samples == 0);
      if (report.samples == 0) {
        half[0].assign(r.rgba.size(), 0.0);
        half[1].assign(r.rgba.size(), 0.0);
      } else if (r.rgba.size() != half[0].size()) {
        throw std::logic_error("sol::programs::render_batches: a batch of another size");
      }
      for (std::size_t k = 0; k < r.rgba.size(); ++k) half[side][k] += static_cast<double>(r.rgba[k]) * pair;
      if (!r.albedo.empty() && r.emission.size() == r.albedo.size()) {
        albedo.resize(r.albedo.size(), 0.0);
        emission.resize(r.albedo.size(), 0.0);
        for (std::size_t k = 0; k < r.albedo.size(); ++k) {
          albedo[k] += static_cast<double>(r.albedo[k]) * pair;
          emission[k] += static_cast<double>(r.emission[k]) * pair;
        }
        if (r.light_moment.size() == r.albedo.size() / 3) {
          moment.resize(r.light_moment.size(), 0.0);
          for (std::size_t k = 0; k < r.light_moment.size(); ++k) moment[k] += static_cast<double>(r.light_moment[k]) * pair;
        } else {
          moments_missing = true;
        }
        guided += pair;
      }
      device_ms += r.device_ms;
      out_of_steps += r.rays_out_of_steps;
      if (report.samples == 0) result = std::move(r);  // its size and AOVs (its colour replaced at the end)
      counted[side] += pair;
      report.samples += pair;
    }
    report.seconds = elapsed();
    const int w = result.width, h = static_cast<int>(half[0].size() / 4 / static_cast<std::size_t>(std::max(1, result.width)));
    std::vector<double> a(half[0].size()), b(half[1].size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      a[k] = half[0][k] / counted[0];
      b[k] = half[1][k] / counted[1];
    }
    report.noise = noise_estimate(a, b, w, h);
    report.noise_reached = goal.noise && report.noise <= *goal.noise;
    if (progress) progress(report);
    if (report.noise_reached && report.samples >= goal.min_samples) break;
    // The next pair: twice this one, within the samples and the time left.
    int next = std::min(2 * pair, (goal.max_samples - report.samples) / 2);
    if (goal.seconds) {
      const double per_sample = report.seconds / report.samples;
      // (90 % of the time left: a batch's time varies.)
      const double left = 0.9 * (*goal.seconds - report.seconds);
      next = std::min(next, static_cast<int>(std::floor(left / (2.0 * per_sample))));
    }
    if (next < 1 || (!goal.seconds && !goal.noise && report.samples >= goal.min_samples)) break;
    pair = next;
  }
  // The mean of all samples (the first batch's AOVs kept), and so the guides' albedo and emission where
  // every batch rendered them (else the first batch's).
  for (std::size_t k = 0; k < result.rgba.size(); ++k) {
    result.rgba[k] = static_cast<float>((half[0][k] + half[1][k]) / report.samples);
  }
  const bool joined = guided == report.samples;
  if (joined && result.albedo.size() == albedo.size()) {
    for (std::size_t k = 0; k < albedo.size(); ++k) {
      result.albedo[k] = static_cast<float>(albedo[k] / guided);
      result.emission[k] = static_cast<float>(emission[k] / guided);
    }
  }
  // The light moment likewise, or none (the first batch's alone is not the
  // colour's: the denoiser then takes the neighbours' noise).
  if (joined && !moments_missing && result.light_moment.size() == moment.size()) {
    for (std::size_t k = 0; k < moment.size(); ++k) result.light_moment[k] = static_cast<float>(moment[k] / guided);
  } else {
    result.light_moment.clear();
  }
  result.samples = report.samples;
  result.device_ms = device_ms;
  result.rays_out_of_steps = out_of_steps;
  return result;
}

}  // namespace sol::programs
