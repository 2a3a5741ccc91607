// Argument validation shared by libsol's public functions (not installed).
#pragma once

#include <cmath>
#include <string>

#include <glm/vec3.hpp>

#include "sol/error.hpp"

namespace sol::detail {

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

}  // namespace sol::detail
