// The CPU renderer's rows on a pool of threads (not installed).
#pragma once

#include <atomic>
#include <functional>

namespace sol::detail {

/// Runs row(j) for every j in [0, rows) on `threads` threads, the calling
/// thread among them, handing out rows one at a time. With `progress` the
/// calling thread reports the finished fraction (0 first, 1 last) every
/// 200 ms, also between its own rows (with one thread, only there). The
/// first exception a row or `progress` throws stops the hand-out and is
/// rethrown here once every thread has joined: a `progress` that throws is
/// how a caller stops a render. `row(j, stopping)` gets the flag set once
/// the work stops, to drop the rest of a long row rather than finish it.
void for_each_row(int rows, unsigned threads, const std::function<void(double)>& progress,
                  const std::function<void(int, const std::atomic<bool>&)>& row);

}  // namespace sol::detail
