#include "sol/light.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/spreading.hpp"

namespace sol {
namespace detail {

// The checks of one light, `at` its path ("lights[0]").
void check_light(const Light& l, const std::string& at) {
  if (!(l.reach >= 0.0 && l.reach <= 10.0)) field_error(at + ".reach", at + ".reach must be in [0, 10]");
  if (l.type == LightType::Directional) check_direction(l.direction, at + ".direction");
  if (l.type == LightType::Point) check_position(l.position, at + ".position");
  if (!unit_interval3(l.color)) field_error(at + ".color", at + ".color components must be in [0, 1]");
  // Up to 1e9: colours stay far inside float (3.4e38) whatever the scene sums.
  if (!(l.intensity >= 0.0) || !std::isfinite(l.intensity)) {
    field_error(at + ".intensity", at + ".intensity must be finite and >= 0");
  }
  if (!(l.intensity <= 1e9)) field_error(at + ".intensity", at + ".intensity must be at most 1e9");
  if (l.falloff != Falloff::Auto && l.type != LightType::Point) {
    field_error(at + ".falloff", at + ".falloff is for point lights");
  }
  if (l.shadows && (l.type != LightType::Point || !l.exact)) {
    field_error(at + ".shadows", at + ".shadows needs an exact point light (\"exact\": true: the geodesics to the light)");
  }
  if (l.falloff == Falloff::Geodesic && !l.exact) {
    field_error(at + ".falloff", at + ".falloff geodesic needs \"exact\": true (the light's geodesics)");
  }
}

}  // namespace detail

Falloff falloff_of(const Light& light) {
  if (light.falloff != Falloff::Auto) return light.falloff;
  return light.type == LightType::Point && light.exact ? Falloff::Geodesic : Falloff::InverseSquare;
}

LightAtPoint light_at(const Light& light, const glm::dvec3& p) {
  if (light.type == LightType::Directional) return {glm::normalize(light.direction), 1.0};
  const glm::dvec3 d = light.position - p;
  // The coordinate difference in frame components at p (left-invariant, like
  // everything here), and the inverse-square law on the distance bound.
  const glm::dvec3 v(std::exp(-p.z) * d.x, std::exp(p.z) * d.y, d.z);
  const double r = distance_lower_bound(p, light.position);
  const double len = glm::length(v);
  return {len > 0.0 ? v / len : glm::dvec3(0.0, 0.0, 1.0), 1.0 / (1.0 + r * r)};
}

std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p) {
  if (light.type != LightType::Point || !light.exact) return {light_at(light, p)};
  std::vector<LightAtPoint> out;
  try {
    const std::vector<Connection> cs = light.reach > 0.0
                                           ? geodesics_between(p, light.position, distance(p, light.position) + light.reach)
                                           : minimising_geodesics(p, light.position);
    const bool geodesic = falloff_of(light) == Falloff::Geodesic;
    for (const Connection& c : cs) {
      if (c.length == 0.0) continue;
      const glm::dvec3 l = glm::normalize(c.direction);
      out.push_back({l,
                     geodesic ? 1.0 / clamped_spreading(sphere_area_density(l, c.length)) : 1.0 / (1.0 + c.length * c.length),
                     c.length});
    }
  } catch (const OutOfRange&) {
    return {light_at(light, p)};  // no connection found (extreme far points): the approximate direction
  }
  return out;
}

}  // namespace sol
