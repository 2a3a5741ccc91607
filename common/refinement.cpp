#include "refinement.hpp"

#include <sol/camera.hpp>

namespace sol::programs {

bool Refinement::update(const std::array<double, 16>& key, double dt, double scale) {
  bool kept = true;
  if (key != m_last_key) {
    m_last_key = key;
    m_still_for = 0.0;
    kept = m_refined < 0;
    m_refined = -1;
  } else {
    m_still_for += dt;
  }
  if (m_refined < 0 && m_samples > 0 && m_still_for >= kDelay && (scale < 1.0 || m_samples > 1)) {
    m_refined = 0;
    m_began = std::chrono::steady_clock::now();
  }
  return kept;
}

std::optional<Refinement::Sample> Refinement::sample() const {
  if (m_refined < 0 || m_refined >= m_samples) return std::nullopt;
  return Sample{sol::pixel_sample(m_refined), 1.0 / (m_refined + 1), m_refined};
}

std::optional<double> Refinement::shown(double* full_seconds) {
  if (m_refined < 0 || m_refined >= m_samples) return std::nullopt;
  ++m_refined;
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_began).count();
  if (m_refined == 1) m_full_s = since;
  if (m_refined < m_samples) return std::nullopt;
  if (full_seconds != nullptr) *full_seconds = m_full_s;
  return since;
}

}  // namespace sol::programs
