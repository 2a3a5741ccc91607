#include "sol/objects/tube.hpp"
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

namespace sol {

using namespace detail;

// ---- Tube ----------------------------------------------------------------

glm::dvec3 tube_axis_direction(TubeAxis axis, const Lattice& lattice) {
  switch (axis) {
    case TubeAxis::X:
      return {1.0, 0.0, 0.0};
    case TubeAxis::Y:
      return {0.0, 1.0, 0.0};
    case TubeAxis::Z:
      return {0.0, 0.0, 1.0};
    case TubeAxis::Gamma1:
    case TubeAxis::Gamma2: {
      // A z loop has no γ1, γ2: the default's directions stand in.
      const Lattice& own = lattice.loops() == Lattice::Loops::Z ? Lattice::default_axes() : lattice;
      return glm::normalize(own.generators()[axis == TubeAxis::Gamma1 ? 0 : 1]);
    }
  }
  return {0.0, 0.0, 1.0};
}

namespace {
constexpr TubeAxis kTubeAxes[] = {TubeAxis::X, TubeAxis::Y, TubeAxis::Z, TubeAxis::Gamma1, TubeAxis::Gamma2};
}

std::optional<TubeAxis> tube_axis_of(const glm::dvec3& direction, const Lattice& lattice) {
  for (TubeAxis a : kTubeAxes) {
    if (tube_axis_direction(a, lattice) == direction) return a;
  }
  return std::nullopt;
}

std::string_view to_string(TubeAxis axis) {
  switch (axis) {
    case TubeAxis::X:
      return "x";
    case TubeAxis::Y:
      return "y";
    case TubeAxis::Z:
      return "z";
    case TubeAxis::Gamma1:
      return "gamma1";
    case TubeAxis::Gamma2:
      return "gamma2";
  }
  return "?";
}

double Tube::distance(const glm::dvec3& q) const {
  return vertical() ? sdf_tube(q, through, 2, radius) : sdf_tube_horizontal(q, through, {direction.x, direction.y}, radius);
}

std::array<BoundTerm, 2> Tube::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return tube_terms(q, u, through, vertical(), {direction.x, direction.y}, radius);
}

std::array<InsideTerm, 4> Tube::inside_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return tube_inside_terms(q, u, through, vertical(), {direction.x, direction.y}, radius);
}

glm::dvec3 Tube::normal(const glm::dvec3& q) const { return gradient_normal(*this, q); }

glm::dvec2 Tube::pattern_uv(const glm::dvec3& q) const {
  const glm::dvec3 w = multiply(inverse(through), q);
  if (vertical()) return kernel::sol_tube_pattern_uv(w, true, {}, radius);  // sol/patterns.h
  // The axis direction relative to the point `through` (see seen_from).
  const glm::dvec2 h =
      glm::normalize(glm::dvec2(std::exp(-through.z) * direction.x, std::exp(through.z) * direction.y));
  return kernel::sol_tube_pattern_uv(w, false, h, radius);
}

// Left-translation maps lines to lines and scales a horizontal direction
// (h_x, h_y) to (e^{-p_z} h_x, e^{p_z} h_y).
Tube Tube::seen_from(const glm::dvec3& p) const {
  Tube t{multiply(inverse(p), through), direction, radius};
  if (!vertical()) {
    const glm::dvec2 h = glm::normalize(glm::dvec2(std::exp(-p.z) * direction.x, std::exp(p.z) * direction.y));
    t.direction = {h.x, h.y, 0.0};
  }
  return t;
}

// Vertical: unbounded (its x and y widths grow as e^{±z}). Horizontal:
// |Δz| <= r; along x (h = (1, 0)) asinh(|Δy| e^{z}) <= r bounds |Δy| by
// sinh(r) e^{-z} <= sinh(r) e^{r - z0}, along y |Δx| by sinh(r) e^{z0 + r}
// (sol::sdf_tube_horizontal); along another direction x and y are unbounded.
CoordinateBox Tube::coordinate_box() const {
  CoordinateBox b = CoordinateBox::everywhere();
  if (vertical()) return b;
  const double r = radius * (1.0 + 1e-12), s = std::sinh(r) * (1.0 + 1e-12);
  b.lo.z = through.z - r;
  b.hi.z = through.z + r;
  if (direction.y == 0.0) {
    b.lo.y = through.y - s * std::exp(r - through.z);
    b.hi.y = through.y + s * std::exp(r - through.z);
  }
  if (direction.x == 0.0) {
    b.lo.x = through.x - s * std::exp(through.z + r);
    b.hi.x = through.x + s * std::exp(through.z + r);
  }
  return b;
}

// The bound's record (kernel::Image::bound): a vertical tube (-radius, x0,
// y0, 0); a horizontal one along h through (x0, y0, z0) (k h_x, k h_y,
// k (h_y x0 - h_x y0), z0), k = ±radius / (|h_x| + |h_y|) with the sign
// that makes k h_x >= 0 (tube_record_clearances in compute/shaders/kinds/tube.glsl).
KernelShape Tube::kernel_shape() const {
  KernelShape s{.code = kernel::kObjectTube,
                .geometry = {through, vertical() ? kernel::kTubeVertical : 0},
                .heading = {direction.x, direction.y},
                .radius = radius};
  if (vertical()) {
    s.bound = {-radius, through.x, through.y, 0.0};
  } else {
    const double k = (direction.x < 0.0 ? -radius : radius) / (std::abs(direction.x) + std::abs(direction.y));
    const glm::dvec2 h = k * glm::dvec2(direction.x, direction.y);
    s.bound = {h.x, h.y, h.y * through.x - h.x * through.y, through.z};
  }
  return s;
}

// The axis point is moved into D by the element g of Γ that teleports it, and
// the axis with it (left-translation by g = seen from g⁻¹).
Tube Tube::into_domain(const Lattice& lattice) const {
  const Teleport t = lattice.teleport(through);
  Tube moved = (t.turned ? half_turned() : *this).seen_from(inverse(t.element));
  moved.through = t.point;
  return moved;
}

double Tube::least_distance_over_domain(const Lattice& lattice) const {
  const Solid solid = vertical() ? Solid::VerticalTube : Solid::HorizontalTube;
  return least_solid_bound(solid, through, vertical() ? glm::dvec2(0.0) : glm::dvec2(direction.x, direction.y), lattice) -
         radius;
}

// The line through half_turn(through) along the turned direction (a
// vertical one is its own); the pattern follows (along and across keep their signs).
Tube Tube::half_turned() const { return {half_turn(through), half_turn(direction), radius}; }

ImageAnchor Tube::image_anchor() const {
  if (vertical()) return {ImageAnchor::Along::VerticalLine, through, {0.0, 0.0}};
  return {ImageAnchor::Along::HorizontalLine, through, {direction.x, direction.y}};
}

bool Tube::same_set(const Tube& other) const {
  constexpr double tol = kSameSetTolerance;
  if (vertical() != other.vertical()) return false;
  if (vertical()) return std::abs(through.x - other.through.x) < tol && std::abs(through.y - other.through.y) < tol;
  const glm::dvec2 d(other.through.x - through.x, other.through.y - through.y);
  return std::abs(through.z - other.through.z) < tol &&
         std::abs(direction.x * other.direction.y - direction.y * other.direction.x) < tol &&
         std::abs(direction.x * d.y - direction.y * d.x) < tol;
}

// ---- Checks and scene-file keys

namespace detail {

bool parallel(const glm::dvec3& a, const glm::dvec3& b) { return glm::length(glm::cross(a, b)) < 1e-12; }

void check_kind(const Tube& t, const std::string& at, const Lattice* quotient) {
  check_position(t.through, at + ".through");
  const glm::dvec3& d = t.direction;
  if (!finite3(d) || std::abs(glm::length(d) - 1.0) > 1e-12 || (d.z != 0.0 && !t.vertical())) {
    field_error(at + ".axis", at + ".axis must be a unit vertical or horizontal direction");
  }
  check_radius(t.radius, at, quotient);
  if (!quotient) return;
  if (quotient->loops() == Lattice::Loops::Z) {
    // γ3 maps a horizontal line at height z to one at z + h (finitely many
    // near D), the axis x = y = 0 to itself, every other vertical line to
    // others without end (all of them near D's unbounded x, y).
    if (t.vertical() && (t.through.x != 0.0 || t.through.y != 0.0)) {
      field_error(at + ".through", at + ".through: a tube along z in a z loop must be the axis x = y = 0 (γ3 maps every "
                                        "other vertical line to new ones without end)");
    }
    return;
  }
  if (t.vertical()) {
    if (quotient->loops() == Lattice::Loops::XY) {
      field_error(at + ".axis", at + ".axis: a tube along z does not fit xy loops (its images crowd together without end "
                                     "far above or below); use a horizontal tube along gamma1 or gamma2");
    }
    // A vertical line closes up (as the curve of γ3) when it passes through
    // a lattice point of ⟨γ1, γ2⟩, which γ3 maps into the lattice.
    const glm::dvec2 st = quotient->lattice_coordinates(t.through.x, t.through.y);
    if (std::abs(st.x - std::round(st.x)) > 1e-9 || std::abs(st.y - std::round(st.y)) > 1e-9) {
      field_error(at + ".through", at + ".through: a tube along z in the quotient must pass through a point (x, y) of the "
                                        "lattice ⟨γ1, γ2⟩ (then it is the closed curve of γ3)");
    }
  } else if (parallel(d, tube_axis_direction(TubeAxis::Gamma1, *quotient)) ||
             parallel(d, tube_axis_direction(TubeAxis::Gamma2, *quotient))) {
    return;  // the closed curve of γ1 or γ2 (its period: sol::quotient_images)
  } else if (parallel(d, tube_axis_direction(TubeAxis::X, *quotient)) || parallel(d, tube_axis_direction(TubeAxis::Y, *quotient))) {
    field_error(at + ".axis", at + ".axis: tubes along x or y do not close up in the quotient (their images are dense); "
                                   "use gamma1, gamma2 or z");
  } else {
    field_error(at + ".axis", at + ".axis: a horizontal tube closes up in the quotient only along its lattice's gamma1 "
                                   "or gamma2 (" + to_json(tube_axis_direction(TubeAxis::Gamma1, *quotient)).dump() + " or " +
                                   to_json(tube_axis_direction(TubeAxis::Gamma2, *quotient)).dump() + ")");
  }
}

void read_kind(Tube& t, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at,
               const Lattice* quotient) {
  const std::string what = at + " (a tube)";
  r.require_known_object_keys(o, {"type", "axis", "through", "radius"}, what, at);
  for (const char* key : {"axis", "through", "radius"}) r.require_key(o, key, what, std::string("'") + key + "'", at);
  const json& axis = o["axis"];
  if (axis.is_array()) {
    // Any coordinate direction, vertical or horizontal (check_kind checks it),
    // normalised unless already unit (so that to_json's output reads back as it was).
    const glm::dvec3 d = r.vec3(axis, at + ".axis");
    const double length = glm::length(d);
    t.direction = length > 0.0 && std::abs(length - 1.0) > 1e-15 ? d / length : d;
  } else {
    const std::string name = SceneFileReader::text(axis);
    const auto known = std::find_if(std::begin(kTubeAxes), std::end(kTubeAxes), [&](TubeAxis a) { return to_string(a) == name; });
    if (name == "gamma3") {
      t.direction = {0.0, 0.0, 1.0};  // the closed curve of γ3 is the vertical line
    } else if (known != std::end(kTubeAxes)) {
      t.direction = tube_axis_direction(*known, quotient ? *quotient : Lattice::default_axes());
    } else {
      r.fail(at + ".axis", "'" + at + ".axis' must be x, y, z, gamma1, gamma2 or gamma3, got " + SceneFileReader::json_text(axis) +
                               " (or a vertical or horizontal direction [a, b, c])");
    }
  }
  t.through = r.vec3(o["through"], at + ".through");
  t.radius = r.number(o["radius"], at + ".radius");
}

json write_kind(const Tube& t, const SceneObject&, const Lattice* quotient) {
  const std::optional<TubeAxis> name = tube_axis_of(t.direction, quotient ? *quotient : Lattice::default_axes());
  return {{"axis", name ? json(std::string(to_string(*name))) : to_json(t.direction)},
          {"through", to_json(t.through)},
          {"radius", t.radius}};
}

}  // namespace detail
}  // namespace sol
