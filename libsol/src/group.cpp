#include "sol/group.hpp"

#include <cmath>

#include "check.hpp"

namespace sol {

glm::dvec3 multiply(const glm::dvec3& p, const glm::dvec3& q) {
  detail::require_finite(p, "sol::multiply", "p");
  detail::require_finite(q, "sol::multiply", "q");
  return detail::finite_result({std::exp(p.z) * q.x + p.x, std::exp(-p.z) * q.y + p.y, p.z + q.z}, "sol::multiply",
                               "the product");
}

glm::dvec3 inverse(const glm::dvec3& p) {
  detail::require_finite(p, "sol::inverse", "p");
  return detail::finite_result({-std::exp(-p.z) * p.x, -std::exp(p.z) * p.y, -p.z}, "sol::inverse", "the inverse");
}

glm::dvec3 velocity_from_frame(const glm::dvec3& point, const glm::dvec3& frame) {
  detail::require_finite(point, "sol::velocity_from_frame", "point");
  detail::require_finite(frame, "sol::velocity_from_frame", "frame");
  return detail::finite_result({std::exp(point.z) * frame.x, std::exp(-point.z) * frame.y, frame.z},
                               "sol::velocity_from_frame", "the velocity");
}

glm::dvec3 frame_from_velocity(const glm::dvec3& point, const glm::dvec3& velocity) {
  detail::require_finite(point, "sol::frame_from_velocity", "point");
  detail::require_finite(velocity, "sol::frame_from_velocity", "velocity");
  return detail::finite_result({std::exp(-point.z) * velocity.x, std::exp(point.z) * velocity.y, velocity.z},
                               "sol::frame_from_velocity", "the frame components");
}

}  // namespace sol
