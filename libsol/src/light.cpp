#include "sol/light.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <string>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/group.hpp"
#include "sol/lattice.hpp"
#include "sol/objects.hpp"
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

namespace {

// The light's terms along connections from p.
void append_connections(const Light& light, const std::vector<Connection>& cs, std::vector<LightAtPoint>& out) {
  const bool geodesic = falloff_of(light) == Falloff::Geodesic;
  for (const Connection& c : cs) {
    if (c.length == 0.0) continue;
    const glm::dvec3 l = glm::normalize(c.direction);
    out.push_back({l,
                   geodesic ? 1.0 / clamped_spreading(sphere_area_density(l, c.length)) : 1.0 / (1.0 + c.length * c.length),
                   c.length});
  }
}

}  // namespace

std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p) {
  if (light.type != LightType::Point || !light.exact) return {light_at(light, p)};
  std::vector<LightAtPoint> out;
  try {
    append_connections(light,
                       light.reach > 0.0 ? geodesics_between(p, light.position, distance(p, light.position) + light.reach)
                                         : minimising_geodesics(p, light.position),
                       out);
  } catch (const OutOfRange&) {
    return {light_at(light, p)};  // no connection found (extreme far points): the approximate direction
  }
  return out;
}

std::vector<glm::dvec3> quotient_light_images(const Light& light, const Lattice& lattice) {
  if (light.type != LightType::Point || !light.exact) return {};
  const glm::dvec3 l0 = lattice.teleport(light.position).point;
  // C: the largest over a 7³ grid of D of the least distance to the nearby
  // images (an upper bound of the least distance to all of them), plus the
  // longest path from a point of D to its nearest grid node: offsets up to
  // 1/12 of |γ1| + |γ2| along x and y at a height z in [0, h] (a path
  // e^{-z}|Δx| + e^{z}|Δy|, convex in z: largest at 0 or h) and h/12
  // vertically (for the golden lattice 0.74, taken as 0.87).
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  const double h = lattice.height();
  const double dx = (std::abs(g1.x) + std::abs(g2.x)) / 12.0, dy = (std::abs(g1.y) + std::abs(g2.y)) / 12.0;
  const double slack = std::max(0.87, std::max(dx + dy, std::exp(-h) * dx + std::exp(h) * dy) + h / 12.0);
  std::vector<glm::dvec3> nearby;
  for (int a = -2; a <= 2; ++a) {
    for (int b = -2; b <= 2; ++b) {
      for (int c = -1; c <= 1; ++c) nearby.push_back(lattice.apply({a, b, c}, l0));
    }
  }
  constexpr int n = 6;
  double cover = 0.0;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        const double s = static_cast<double>(i) / n, r = static_cast<double>(j) / n;
        const glm::dvec3 p(s * g1.x + r * g2.x, s * g1.y + r * g2.y, lattice.height() * k / n);
        double least = std::numeric_limits<double>::infinity();
        for (const glm::dvec3& q : nearby) {
          if (distance_lower_bound(p, q) >= least) continue;
          try {
            least = std::min(least, distance(p, q));
          } catch (const OutOfRange&) {
          }
        }
        cover = std::max(cover, least);
      }
    }
  }
  const double radius = cover + slack + light.reach;
  std::vector<glm::dvec3> images;
  const int layers = static_cast<int>(std::ceil(radius / lattice.height())) + 1;
  // The words γ1^a γ2^b γ3^c enumerated, |a|, |b| <= range: an image on the
  // edge of that square within R means others beyond it may be too, and
  // the list would be silently short. The nearest edge image bounds the
  // reach that keeps it whole.
  constexpr int range = 22;
  double nearest_edge = std::numeric_limits<double>::infinity();
  for (int c = -layers; c <= layers; ++c) {
    for (int a = -range; a <= range; ++a) {
      for (int b = -range; b <= range; ++b) {
        const glm::dvec3 q = lattice.apply({a, b, c}, l0);
        const double d = Ball{q, 0.0}.least_distance_over_domain(lattice);
        if (d <= radius) images.push_back(q);
        if (std::abs(a) == range || std::abs(b) == range) nearest_edge = std::min(nearest_edge, d);
      }
    }
  }
  if (nearest_edge <= radius) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "reach %g in the quotient needs the light's images beyond the %d x %d lattice words enumerated "
                  "(%zu images lie within %.2f of the domain, some on its edge, and each point of a surface would "
                  "look for connections to many of them); this light allows a reach of at most %.2f",
                  light.reach, 2 * range + 1, 2 * range + 1, images.size(), radius,
                  std::max(0.0, std::floor(100.0 * (nearest_edge - cover - slack)) / 100.0 - 0.01));
    throw InvalidArgument(text);
  }
  return images;
}

std::vector<LightAtPoint> lights_at(const Light& light, const glm::dvec3& p, const std::vector<glm::dvec3>& images) {
  if (light.type != LightType::Point || !light.exact || images.empty()) return lights_at(light, p);
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t i = 0; i < images.size(); ++i) order.emplace_back(distance_lower_bound(p, images[i]), i);
  std::sort(order.begin(), order.end());
  double best = std::numeric_limits<double>::infinity();
  std::vector<std::pair<std::size_t, double>> near;  // (image, its distance)
  for (const auto& [bound, i] : order) {
    if (bound > best + light.reach) break;
    try {
      const double d = distance(p, images[i]);
      best = std::min(best, d);
      near.emplace_back(i, d);
    } catch (const OutOfRange&) {
    }
  }
  std::vector<LightAtPoint> out;
  for (const auto& [i, d] : near) {
    if (d > best + light.reach + 1e-9) continue;
    try {
      append_connections(light,
                         light.reach > 0.0 ? geodesics_between(p, images[i], best + light.reach)
                                           : minimising_geodesics(p, images[i]),
                         out);
    } catch (const OutOfRange&) {
    }
  }
  if (out.empty()) return {light_at(light, p)};
  return out;
}

}  // namespace sol
