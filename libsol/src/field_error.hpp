// A problem with one field of a scene, found by the checks of the scene
// model (camera.cpp, objects.cpp, light.cpp, scene.cpp). Each check throws it
// with the field's path ("camera.fov", "objects[2].radius") and a message
// that names the field; sol::validate and the scene file reader catch it and
// rethrow an InvalidArgument with their source and, for files, the field's
// line and column. Not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <glm/vec3.hpp>

#include "sol/error.hpp"

namespace sol::detail {

class FieldError : public InvalidArgument {
 public:
  FieldError(std::string path, const std::string& message) : InvalidArgument(message), m_path(std::move(path)) {}
  /// The field's path in the scene file's terms, e.g. "objects[2].radius".
  const std::string& path() const { return m_path; }

 private:
  std::string m_path;
};

[[noreturn]] inline void field_error(const std::string& path, const std::string& message) {
  throw FieldError(path, message);
}

/// Beyond 1e15 double cannot resolve unit-size features (ulp 0.125) and the
/// float AOVs cannot hold the coordinates: such input is refused.
constexpr double kMaxCoordinate = 1e15;

inline bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool bounded3(const glm::dvec3& v) {
  return finite3(v) && std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate &&
         std::abs(v.z) <= kMaxCoordinate;
}
/// Heights: |z| <= 80 keeps e^{±z} (the metric's scale) finite in the
/// kernel's float (e^{88.7} is its largest) with room for the products it
/// meets, and every double path (flows, teleports) far from overflow.
constexpr double kMaxHeight = 80.0;

/// A position: finite, within kMaxCoordinate, and at a height within
/// kMaxHeight; `field` names it in the message.
inline void check_position(const glm::dvec3& p, const std::string& field) {
  if (!bounded3(p)) field_error(field, field + " must be finite and within 1e15 of the origin");
  if (!(std::abs(p.z) <= kMaxHeight)) {
    field_error(field, field + " must have its height z within [-80, 80] (e^{±z} must stay finite in float)");
  }
}

/// A direction given by a vector of any length: finite, non-zero, and of a
/// length that normalising keeps exact (no overflow or underflow).
inline void check_direction(const glm::dvec3& d, const std::string& field) {
  if (!finite3(d) || (d.x == 0.0 && d.y == 0.0 && d.z == 0.0)) field_error(field, field + " must be finite and non-zero");
  const double m = std::max(std::abs(d.x), std::max(std::abs(d.y), std::abs(d.z)));
  if (!(m >= 1e-100 && m <= 1e100)) field_error(field, field + " must have components of at most 1e100 and not all below 1e-100");
}

inline bool unit_interval3(const glm::dvec3& v) {
  for (int k = 0; k < 3; ++k) {
    if (!(v[k] >= 0.0 && v[k] <= 1.0)) return false;
  }
  return true;
}

/// Turns a FieldError thrown by `check` into an InvalidArgument prefixed with `source`.
template <class Check>
void validate_as(const char* source, Check&& check) {
  try {
    check();
  } catch (const FieldError& e) {
    throw InvalidArgument(std::string(source) + ": " + e.what());
  }
}

}  // namespace sol::detail
