// Sol's logarithm's series at w, unchecked (libsol-internal): sol::log_series
// refuses a w beyond the series' reach; a solver's first guess takes it
// anywhere (it need only fall in Newton's basin).
#pragma once

#include <glm/vec3.hpp>

#include "sol/log_series.h"

namespace sol::detail {

/// (w_x f(w_x², w_y², w_z), w_y f(w_y², w_x², −w_z), h(w_x², w_y², w_z)), sol/log_series.h's series.
inline glm::dvec3 log_series_at(const glm::dvec3& w) {
  const double p = w.x * w.x, q = w.y * w.y;
  return {w.x * kernel::sol_log_series_f(p, q, w.z), w.y * kernel::sol_log_series_f(q, p, -w.z),
          kernel::sol_log_series_h(p, q, w.z)};
}

}  // namespace sol::detail
