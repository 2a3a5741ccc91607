// The CPU renderer's rows on a pool of threads (not installed).
#pragma once

#include <functional>

namespace sol::detail {

/// Runs row(j) for every j in [0, rows) on `threads` threads, the calling
/// thread among them, handing out rows one at a time; with `progress` the
/// calling thread first reports the finished fraction every 200 ms while the
/// others work. The first exception a row (or `progress`) throws stops the
/// hand-out and is rethrown here once every thread has joined.
void for_each_row(int rows, unsigned threads, const std::function<void(double)>& progress,
                  const std::function<void(int)>& row);

}  // namespace sol::detail
