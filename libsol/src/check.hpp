// Argument validation shared by libsol's public functions (not installed).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include <glm/vec3.hpp>

#include "sol/error.hpp"

namespace sol::detail {

/// A number as a message shows it: %g's six significant digits, so that
/// 1e-300 reads "1e-300" (std::to_string's fixed "0.000000") and 1e300
/// "1e+300" (not 300 digits).
inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

inline void require_finite(double value, const char* function, const char* argument) {
  if (!std::isfinite(value)) {
    throw InvalidArgument(std::string(function) + ": argument '" + argument + "' is " +
                          (std::isnan(value) ? "NaN" : "infinite"));
  }
}

inline void require_finite(const glm::dvec3& v, const char* function, const char* argument) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i])) {
      throw InvalidArgument(std::string(function) + ": argument '" + argument + "' has a " +
                            (std::isnan(v[i]) ? "NaN" : "infinite") + " component " +
                            std::to_string(i));
    }
  }
}

/// `v`, when every component is finite; otherwise OutOfRange naming
/// `function`: finite arguments whose result overflows double (a height
/// beyond ±709, where e^{±z} does, or coordinates near the largest double)
/// are refused rather than answered with inf or NaN.
inline glm::dvec3 finite_result(const glm::dvec3& v, const char* function, const char* what) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i])) {
      throw OutOfRange(std::string(function) + ": " + what +
                       " overflows double (the arguments are too far from the origin)");
    }
  }
  return v;
}

}  // namespace sol::detail
