// What a presenter's frames cost, as the display gets them: solview --stats
// and solxr --stats print it at exit.
//
// A frame is counted with three figures: its interval (the time from the
// previous frame's end to its own end on the device: what the display gets
// one new frame per; none for the first frame, or one after a pause), its
// work (the device's time from the frame's first command to its last) and
// its host recording time. A frame is missed when its work plus its
// recording exceed the display period: it could not have been shown in time
// however well it was paced.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace sol::programs {

class FrameStats {
 public:
  /// A frame: its interval in milliseconds (none for a first frame, or one
  /// after frames that were not rendered), the device's work and the host's
  /// recording in milliseconds, and the display period it had to fit.
  void add(std::optional<double> interval_ms, double work_ms, double record_ms, double period_ms);

  /// Frames counted.
  long frames() const { return static_cast<long>(m_work.size()); }
  /// Frames with an interval.
  long intervals() const { return static_cast<long>(m_intervals.size()); }
  /// The mean and the 99th percentile (nearest rank: the smallest value at
  /// or above 99 % of them) of the intervals; 0 without any.
  double mean_interval_ms() const;
  double p99_interval_ms() const;
  double mean_work_ms() const;
  double p99_work_ms() const;
  double mean_record_ms() const;
  /// Frames whose work plus recording exceeded their display period.
  long missed() const { return m_missed; }

  /// "stereo frames: N, mean X ms, p99 Y ms, missed Z" (with `what` for
  /// "stereo"): N frames, X and Y of their intervals.
  std::string summary(const std::string& what) const;
  /// The work and recording line: "device work mean A ms, p99 B ms; host
  /// recording mean C ms".
  std::string details() const;

 private:
  std::vector<double> m_intervals, m_work;
  double m_record_sum = 0.0;
  long m_missed = 0;
};

/// The nearest-rank p-th percentile (0 < p <= 100) of `values`; 0 when empty.
double percentile(std::vector<double> values, double p);

}  // namespace sol::programs
