// Progressive refinement of a still view (solview --refine, solxr --refine):
// once the view has not changed for kDelay seconds, frames render at full
// resolution and accumulate jittered samples of every pixel (sol::pixel_sample
// 0, 1, ..., each joining the running mean with weight 1/(k + 1)) up to the
// requested count; after that the finished image is shown again without the
// kernel. Any change of the view starts again.
#pragma once

#include <array>
#include <chrono>
#include <optional>

#include <glm/vec2.hpp>

namespace sol::programs {

class Refinement {
 public:
  static constexpr double kDelay = 0.25;  ///< seconds of a still view before refining
  /// Samples per pixel to accumulate (0: never refine).
  explicit Refinement(int samples) : m_samples(samples) {}

  /// Samples accumulated so far; -1 while not refining.
  int refined() const { return m_refined; }
  int samples() const { return m_samples; }

  /// This frame's view (`key`: whatever determines the image) after `dt`
  /// seconds; `scale` the render scale the view has when moving (a still
  /// view at scale 1 with a single sample has nothing to refine). Returns
  /// false when a change ended a refinement.
  bool update(const std::array<double, 16>& key, double dt, double scale);

  /// What the frame renders: std::nullopt while not refining (the moving
  /// view, at its scale); else the sample to accumulate at full resolution,
  /// or, once all are in, none (reuse(): the finished image again).
  struct Sample {
    glm::dvec2 offset;  ///< in the pixel (sol::pixel_sample)
    double weight;      ///< in the running mean: 1 / (k + 1)
    int index;          ///< k (a path's index, where the samples are paths)
  };
  std::optional<Sample> sample() const;
  bool reuse() const { return m_refined >= 0 && m_refined >= m_samples; }

  /// A frame was shown. Returns the seconds from the end of the pause to the
  /// last sample when this frame completed the refinement (else nullopt);
  /// `full_seconds` then holds the time to the first, full-resolution frame.
  std::optional<double> shown(double* full_seconds = nullptr);

 private:
  int m_samples;
  std::array<double, 16> m_last_key{};
  double m_still_for = 0.0, m_full_s = 0.0;
  int m_refined = -1;
  std::chrono::steady_clock::time_point m_began = std::chrono::steady_clock::now();
};

}  // namespace sol::programs
