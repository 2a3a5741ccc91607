// The render scale that holds a frame rate: solview's --target-fps and
// solxr's display period. Each frame reports its time; every 8th frame (or
// at once when a frame took over twice the target) the scale moves by the
// square root of the ratio of the target time, aimed 10 % below, to the
// smoothed frame time (a frame's cost goes with its pixels, the square of
// the scale), within [min_scale, 1] and outside a 5 % dead band.
#pragma once

namespace sol::programs {

class AdaptiveScale {
 public:
  /// `target_ms`: the frame time to hold (> 0); `min_scale` in (0, 1].
  AdaptiveScale(double target_ms, double min_scale) : m_target_ms(target_ms), m_min_scale(min_scale) {}
  double target_ms() const { return m_target_ms; }
  /// The scale for the next frame, given this one's `scale`, its number
  /// `frame` (from 0) and its time (the first frame's is not counted).
  double next(double scale, long frame, double frame_ms);

 private:
  double m_target_ms, m_min_scale;
  double m_smoothed_ms = 0;
};

}  // namespace sol::programs
