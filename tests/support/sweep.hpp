// How much of a long numerical sweep a build runs.
//
// A sanitizer build instruments every load, store and arithmetic check: the
// tests' own references (50-digit Bulirsch-Stoer integrations, the quotient's
// brute-force image search) run five to ten times slower there, while what the
// sanitizers look for (an out-of-bounds read, an overflow, a leak) lies on code
// paths that a part of each sweep already takes. So a sanitizer build runs
// every k-th case of these sweeps (the stiff and extreme cases are spread over
// the list, and the first is always kept), and the optimised build every
// second, which keeps the test command within its time; SOL_FULL_SWEEPS=1
// runs them all, and holds the figures the tests quote.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace sol::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

/// Whether every case of every sweep runs (SOL_FULL_SWEEPS=1): the figures
/// the docs quote. Otherwise an optimised build runs every second case, so
/// that the test command stays within its time.
inline bool full_sweeps() {
  const char* full = std::getenv("SOL_FULL_SWEEPS");
  return full != nullptr && std::string_view(full) == "1";
}

/// How many cases a sweep steps over: 1 in a full sweep, 2 in an optimised
/// build, `sanitized` in a sanitizer build.
inline std::size_t sweep_stride(std::size_t sanitized) {
  if (full_sweeps()) return 1;
  return kSanitizedBuild ? sanitized : 2;
}

/// Every sweep_stride(stride)-th case, from the first.
template <class T>
std::vector<T> sweep(const std::vector<T>& cases, std::size_t stride = 8) {
  const std::size_t step = sweep_stride(stride);
  if (step <= 1) return cases;
  std::vector<T> kept;
  for (std::size_t i = 0; i < cases.size(); i += step) kept.push_back(cases[i]);
  return kept;
}

/// `count` in an optimised build; count / `divisor` (at least 1) in a sanitizer build.
inline int sweep_count(int count, int divisor = 4) {
  const int step = static_cast<int>(sweep_stride(static_cast<std::size_t>(divisor > 1 ? divisor : 1)));
  if (step <= 1) return count;
  return count / step > 0 ? count / step : 1;
}

}  // namespace sol::test
