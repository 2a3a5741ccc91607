#include "sol/objects/ball.hpp"
#include "sol/patterns.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/geometric.hpp>

#include "../field_error.hpp"
#include "../objects_internal.hpp"
#include "sol/clearance.hpp"
#include "sol/distance.hpp"
#include "sol/group.hpp"
#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"
#include "sol/connection.hpp"

namespace sol {

using namespace detail;

// ---- Ball ----------------------------------------------------------------

double Ball::distance(const glm::dvec3& q) const {
  return exact ? sdf_ball_exact(q, center, radius) : sdf_ball(q, center, radius);
}

// The exact ball lies inside the bound's ball: its clearance serves both.
std::array<BoundTerm, 2> Ball::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return ball_terms(q, u, center, radius);
}

std::array<InsideTerm, 2> Ball::inside_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return ball_inside_terms(q, u, center, radius);
}

glm::dvec3 Ball::normal(const glm::dvec3& q) const {
  if (exact) {
    try {
      return sdf_ball_exact_gradient(q, center);  // the true sphere's normal
    } catch (const OutOfRange&) {
    }
  }
  return gradient_normal(*this, q);
}

glm::dvec2 Ball::pattern_uv(const glm::dvec3& q) const {
  return kernel::sol_ball_pattern_uv(multiply(inverse(center), q));  // sol/patterns.h
}

Ball Ball::seen_from(const glm::dvec3& p) const { return {multiply(inverse(p), center), radius, exact}; }

// The bound's ball (which holds the exact one): d_bound <= r needs
// sinh²(Δz/2) + ¼ Δx² e^{-(z + z0)} <= S², S = sinh(r/2)
// (sol::distance_lower_bound), so |Δz| <= r and, with s = Δz/2,
// |Δx| <= 2 e^{z0} f(s), f(s)² = e^{2s} (S² - sinh² s). f² is largest where
// S² - sinh² s = sinh s cosh s, that is where e^{2s} = 1 + 2S² = cosh r,
// and there f² = cosh r (cosh r - 1/cosh r)/4 = sinh² r / 4: |Δx| <=
// sinh(r) e^{z0}, reached. Likewise |Δy| <= sinh(r) e^{-z0} (s → -s).
// Widened by a few ulps against the rounding of the bound's own evaluation.
CoordinateBox Ball::coordinate_box() const {
  const double s = std::sinh(radius) * (1.0 + 1e-12);
  const glm::dvec3 extent(s * std::exp(center.z), s * std::exp(-center.z), radius * (1.0 + 1e-12));
  return {center - extent, center + extent};
}

KernelShape Ball::kernel_shape() const {
  return {.code = exact ? kernel::kObjectExactBall : kernel::kObjectBall,
          .geometry = {center, 0.0},
          .radius = radius,
          .bound = {center, radius}};
}

Ball Ball::into_domain(const Lattice& lattice) const { return {lattice.teleport(center).point, radius, exact}; }

double Ball::least_distance_over_domain(const Lattice& lattice) const {
  return least_solid_bound(Solid::Ball, center, {0.0, 0.0}, lattice) - radius;
}

Ball Ball::half_turned() const { return {half_turn(center), radius, exact}; }

ImageAnchor Ball::image_anchor() const { return {ImageAnchor::Along::Point, center, {0.0, 0.0}}; }

bool Ball::same_set(const Ball& other) const { return glm::length(center - other.center) < kSameSetTolerance; }

// ---- Checks and scene-file keys

namespace detail {

void check_kind(const Ball& b, const std::string& at, const Lattice* quotient) {
  check_position(b.center, at + ".center");
  check_radius(b.radius, at, quotient);
}

void read_kind(Ball& b, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at, const Lattice*) {
  const std::string what = at + " (a ball)";
  r.require_known_object_keys(o, {"type", "center", "radius", "exact", "glow_reach"}, what, at);
  r.require_key(o, "center", what, "a 'center'", at);
  r.require_key(o, "radius", what, "a 'radius'", at);
  b.center = r.vec3(o["center"], at + ".center");
  b.radius = r.number(o["radius"], at + ".radius");
  if (o.contains("exact")) b.exact = r.boolean(o["exact"], at + ".exact");
}

json write_kind(const Ball& b, const SceneObject&, const Lattice*) {
  return {{"center", to_json(b.center)}, {"radius", b.radius}, {"exact", b.exact}};
}

}  // namespace detail
}  // namespace sol
