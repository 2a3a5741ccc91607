#include "frame_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace sol::programs {
namespace {

double mean(const std::vector<double>& values) {
  return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

}  // namespace

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  // Nearest rank: the ceil(p/100 · n)-th smallest value (1-based).
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

void FrameStats::add(std::optional<double> interval_ms, double work_ms, double record_ms, double period_ms) {
  if (interval_ms) m_intervals.push_back(*interval_ms);
  m_work.push_back(work_ms);
  m_record_sum += record_ms;
  if (work_ms + record_ms > period_ms) ++m_missed;
}

double FrameStats::mean_interval_ms() const { return mean(m_intervals); }
double FrameStats::p99_interval_ms() const { return percentile(m_intervals, 99.0); }
double FrameStats::mean_work_ms() const { return mean(m_work); }
double FrameStats::p99_work_ms() const { return percentile(m_work, 99.0); }
double FrameStats::mean_record_ms() const {
  return m_work.empty() ? 0.0 : m_record_sum / static_cast<double>(m_work.size());
}

std::string FrameStats::summary(const std::string& what) const {
  char line[256];
  std::snprintf(line, sizeof line, "%s frames: %ld, mean %.3f ms, p99 %.3f ms, missed %ld", what.c_str(), frames(),
                mean_interval_ms(), p99_interval_ms(), missed());
  return line;
}

std::string FrameStats::details() const {
  char line[256];
  std::snprintf(line, sizeof line, "device work mean %.3f ms, p99 %.3f ms; host recording mean %.3f ms", mean_work_ms(),
                p99_work_ms(), mean_record_ms());
  return line;
}

}  // namespace sol::programs
