// Time left for long work reported as a finished fraction (a render's
// progress callback), for the programs' progress lines.
#pragma once

#include <chrono>
#include <optional>

namespace sol::programs {

/// Estimates the time left from reports (seconds since the start, finished
/// fraction). The rate is measured from the first report that shows work
/// done, not from the start: what comes before it (a kernel compiled on a
/// cold cache, a world prepared) is no guide to the rest, and counting it
/// made a 12.5 s render say 306 s left at 4 %. Until a second such report,
/// the time since the last report of no work done (a renderer reports 0
/// again once its kernel is built and the work begins) over the fraction
/// done. No estimate before any work is done.
class ProgressEstimate {
 public:
  /// Records a report; returns the estimated seconds left, or none yet.
  std::optional<double> report(double seconds, double fraction) {
    if (!(fraction > 0.0)) {
      if (!m_first) m_begun = seconds;  // the work begins (as far as is known) now
      return std::nullopt;
    }
    if (fraction >= 1.0) return 0.0;
    if (!m_first) {
      m_first_seconds = seconds;
      m_first_fraction = fraction;
      m_first = true;
    }
    if (fraction > m_first_fraction && seconds > m_first_seconds) {
      return (seconds - m_first_seconds) / (fraction - m_first_fraction) * (1.0 - fraction);
    }
    return (seconds - m_begun) / fraction * (1.0 - fraction);
  }

 private:
  bool m_first = false;
  double m_begun = 0.0;
  double m_first_seconds = 0.0, m_first_fraction = 0.0;
};

/// A ProgressEstimate with its own clock, started when it is made: the
/// seconds since, and the time left after a report of the finished fraction.
class ProgressTimer {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_started).count();
  }
  std::optional<double> report(double fraction) { return m_estimate.report(seconds(), fraction); }

 private:
  std::chrono::steady_clock::time_point m_started = std::chrono::steady_clock::now();
  ProgressEstimate m_estimate;
};

}  // namespace sol::programs
