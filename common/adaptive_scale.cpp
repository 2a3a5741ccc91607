#include "adaptive_scale.hpp"

#include <algorithm>
#include <cmath>

namespace sol::programs {

double AdaptiveScale::next(double scale, long frame, double frame_ms) {
  if (frame > 0) m_smoothed_ms = m_smoothed_ms == 0 ? frame_ms : 0.8 * m_smoothed_ms + 0.2 * frame_ms;
  const bool far_too_slow = frame > 1 && frame_ms > 2.0 * m_target_ms;
  if (far_too_slow) m_smoothed_ms = frame_ms;
  if ((frame % 8 != 0 && !far_too_slow) || m_smoothed_ms <= 0) return scale;
  // Aim 10% below the target time so that the dead band below never leaves the rate under it.
  const double wanted = scale * std::sqrt(m_target_ms / 1.1 / m_smoothed_ms);
  const double next = std::clamp(wanted, m_min_scale, 1.0);
  // A 5% dead band against dithering; the bounds are taken whatever the
  // step (scale 1 is solview's direct path; at 0.97 it would never be reached).
  const bool at_bound = next == m_min_scale || next == 1.0;
  return std::abs(next - scale) > 0.05 * scale || (at_bound && next != scale) ? next : scale;
}

}  // namespace sol::programs
