// How much of a long numerical sweep a build runs.
//
// A sanitizer build instruments every load, store and arithmetic check: the
// tests' own references (50-digit Bulirsch-Stoer integrations, the quotient's
// brute-force image search) run five to ten times slower there, while what the
// sanitizers look for (an out-of-bounds read, an overflow, a leak) lies on code
// paths that a part of each sweep already takes. So a sanitizer build runs
// every k-th case of these sweeps (the stiff and extreme cases are spread over
// the list, and the first is always kept); the optimised build runs them all
// and holds the figures the tests quote.
#pragma once

#include <cstddef>
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

/// Every case in an optimised build; every `stride`-th (from the first) in a sanitizer build.
template <class T>
std::vector<T> sweep(const std::vector<T>& cases, std::size_t stride = 4) {
  if (!kSanitizedBuild || stride <= 1) return cases;
  std::vector<T> kept;
  for (std::size_t i = 0; i < cases.size(); i += stride) kept.push_back(cases[i]);
  return kept;
}

/// `count` in an optimised build; count / `divisor` (at least 1) in a sanitizer build.
inline int sweep_count(int count, int divisor = 4) {
  if (!kSanitizedBuild || divisor <= 1) return count;
  return count / divisor > 0 ? count / divisor : 1;
}

}  // namespace sol::test
