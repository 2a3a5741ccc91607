#include "sol/objects.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "objects_internal.hpp"
#include "sol/clearance.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/group.hpp"
#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"

namespace sol {
namespace {

// Lattice words γ1^a γ2^b γ3^c with |a|, |b| up to this are searched for the
// images of balls and tubes in the quotient: see the proof at
// sol::quotient_images (march.cpp).
constexpr int kQuotientLatticeRange = 22;

// Two images are the same set when they agree to this.
constexpr double kSameSetTolerance = 1e-9;

// The normal of a distance bound at q: its gradient by central differences
// along the frame E1 = e^{z}∂x, E2 = e^{-z}∂y, E3 = ∂z (the kernel's step).
template <class Kind>
glm::dvec3 gradient_normal(const Kind& kind, const glm::dvec3& q) {
  const double h = kernel::kNormalStep, ez = std::exp(q.z);
  const glm::dvec3 e1(h * ez, 0.0, 0.0), e2(0.0, h / ez, 0.0), e3(0.0, 0.0, h);
  const glm::dvec3 g(kind.distance(q + e1) - kind.distance(q - e1), kind.distance(q + e2) - kind.distance(q - e2),
                     kind.distance(q + e3) - kind.distance(q - e3));
  return glm::length(g) > 0.0 ? glm::normalize(g) : glm::dvec3(0.0, 0.0, 1.0);
}

// The side of a plane {coordinate = c} the origin is on: the march stops
// within hit_epsilon of a plane, possibly just across it, so a plane's side
// comes from the ray's origin, not from the hit.
double origin_side(double c) { return 0.0 >= c ? 1.0 : -1.0; }

double gap(double v, double lo, double hi) { return v < lo ? lo - v : (v > hi ? v - hi : 0.0); }

// A lower bound, over every point q of the fundamental domain D, of the
// distance bound of a ball (or, `vertical_tube`, of a vertical tube) about
// `center`, or (`heading` non-zero) of a horizontal tube through `center`
// along `heading`, before the radius is taken off. D = {s γ1 + r γ2} × [0, h):
// its (x, y) lie in the parallelogram P with corners 0, γ1, γ2, γ1 + γ2. D
// is cut into slabs z in [z0, z1] and the bound is the least of the slabs':
//  - ball, vertical tube: the distance bound is at least the distance to the
//    plane x = c_x, asinh(|q_x - c_x| e^{-q_z}) >= asinh(gap_x e^{-z1}), and
//    to y = c_y, asinh(|q_y - c_y| e^{q_z}) >= asinh(gap_y e^{z0}) (gap_x,
//    gap_y: from c_x, c_y to P's x- and y-ranges); balls also >= |Δz|;
//  - horizontal tube: |h_y Δx - h_x Δy| is linear on P, so its least value
//    is 0 when the corners' values differ in sign and else the least corner
//    value; the denominator |h_x| e^{-z} + |h_y| e^{z} is convex in z, so at
//    most its larger value at z0 or z1; also >= |Δz|.
enum class Solid { Ball, VerticalTube, HorizontalTube };
double least_solid_bound(Solid solid, const glm::dvec3& c, const glm::dvec2& heading, const Lattice& lattice) {
  const double h = lattice.height();
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  const glm::dvec2 corners[4] = {{0.0, 0.0}, {g1.x, g1.y}, {g2.x, g2.y}, {g1.x + g2.x, g1.y + g2.y}};
  double xlo = 0.0, xhi = 0.0, ylo = 0.0, yhi = 0.0;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;  // h_y Δx - h_x Δy over P
  for (const glm::dvec2& k : corners) {
    xlo = std::min(xlo, k.x);
    xhi = std::max(xhi, k.x);
    ylo = std::min(ylo, k.y);
    yhi = std::max(yhi, k.y);
    const double v = heading.y * (k.x - c.x) - heading.x * (k.y - c.y);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const double least_across = lo <= 0.0 && hi >= 0.0 ? 0.0 : std::min(std::abs(lo), std::abs(hi));
  const double gx = gap(c.x, xlo, xhi), gy = gap(c.y, ylo, yhi);
  const double hx = std::abs(heading.x), hy = std::abs(heading.y);
  constexpr int kSlabs = 16;
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kSlabs; ++i) {
    const double z0 = h * i / kSlabs, z1 = h * (i + 1) / kSlabs;
    double b = 0.0;
    if (solid == Solid::HorizontalTube) {
      const double denominator = std::max(hx * std::exp(-z0) + hy * std::exp(z0), hx * std::exp(-z1) + hy * std::exp(z1));
      b = std::max(gap(c.z, z0, z1), std::asinh(least_across / denominator));
    } else {
      b = std::max(std::asinh(gx * std::exp(-z1)), std::asinh(gy * std::exp(z0)));
      if (solid == Solid::Ball) b = std::max(b, gap(c.z, z0, z1));
    }
    least = std::min(least, b);
  }
  return least;
}

}  // namespace

// ---- PlaneX --------------------------------------------------------------

double PlaneX::distance(const glm::dvec3& q) const { return sdf_plane_x(q, c); }

std::array<BoundTerm, 1> PlaneX::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return {slab_x_term(q, u, c, 0.0)};
}

glm::dvec3 PlaneX::normal(const glm::dvec3& q) const {
  glm::dvec3 n = sdf_plane_x_gradient(q, c);
  n.x = origin_side(c) * std::abs(n.x);
  return n;
}

// p⁻¹ maps (x, y, z) to (e^{-p_z}(x - p_x), e^{p_z}(y - p_y), z - p_z).
PlaneX PlaneX::seen_from(const glm::dvec3& p) const { return {std::exp(-p.z) * (c - p.x)}; }

KernelShape PlaneX::kernel_shape() const { return {kernel::kObjectPlaneX, {c, 0.0, 0.0, 0.0}}; }

// ---- PlaneY --------------------------------------------------------------

double PlaneY::distance(const glm::dvec3& q) const { return sdf_plane_y(q, c); }

std::array<BoundTerm, 1> PlaneY::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return {slab_y_term(q, u, c, 0.0)};
}

glm::dvec3 PlaneY::normal(const glm::dvec3& q) const {
  glm::dvec3 n = sdf_plane_y_gradient(q, c);
  n.y = origin_side(c) * std::abs(n.y);
  return n;
}

PlaneY PlaneY::seen_from(const glm::dvec3& p) const { return {std::exp(p.z) * (c - p.y)}; }

KernelShape PlaneY::kernel_shape() const { return {kernel::kObjectPlaneY, {c, 0.0, 0.0, 0.0}}; }

// ---- PlaneZ --------------------------------------------------------------

double PlaneZ::distance(const glm::dvec3& q) const { return sdf_plane_z(q, c); }

std::array<BoundTerm, 1> PlaneZ::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return {plane_z_term(q, u, c)};
}

glm::dvec3 PlaneZ::normal(const glm::dvec3&) const { return {0.0, 0.0, origin_side(c)}; }

PlaneZ PlaneZ::seen_from(const glm::dvec3& p) const { return {c - p.z}; }

KernelShape PlaneZ::kernel_shape() const { return {kernel::kObjectPlaneZ, {c, 0.0, 0.0, 0.0}}; }

PlaneZ PlaneZ::into_domain(const Lattice& lattice) const {
  const double h = lattice.height();
  return {c - h * std::floor(c / h)};
}

double PlaneZ::least_distance_over_domain(const Lattice& lattice) const { return gap(c, 0.0, lattice.height()); }

bool PlaneZ::same_set(const PlaneZ& other) const { return std::abs(c - other.c) < kSameSetTolerance; }

// ---- Ball ----------------------------------------------------------------

double Ball::distance(const glm::dvec3& q) const {
  return exact ? sdf_ball_exact(q, center, radius) : sdf_ball(q, center, radius);
}

// The exact ball lies inside the bound's ball: its clearance serves both.
std::array<BoundTerm, 2> Ball::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return ball_terms(q, u, center, radius);
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
  constexpr double kCells = kernel::kPatternCellsPerRadian;  // 8 cells per turn
  const glm::dvec3 w = multiply(inverse(center), q);
  return {kCells * std::atan2(w.y, w.x), kCells * std::atan2(w.z, std::hypot(w.x, w.y))};
}

Ball Ball::seen_from(const glm::dvec3& p) const { return {multiply(inverse(p), center), radius, exact}; }

KernelShape Ball::kernel_shape() const {
  return {exact ? kernel::kObjectExactBall : kernel::kObjectBall, {center, 0.0}, {0.0, 0.0}, radius};
}

Ball Ball::into_domain(const Lattice& lattice) const { return {lattice.teleport(center).point, radius, exact}; }

double Ball::least_distance_over_domain(const Lattice& lattice) const {
  return least_solid_bound(Solid::Ball, center, {0.0, 0.0}, lattice) - radius;
}

int Ball::lattice_range() const { return kQuotientLatticeRange; }

bool Ball::same_set(const Ball& other) const { return glm::length(center - other.center) < kSameSetTolerance; }

// ---- Tube ----------------------------------------------------------------

glm::dvec3 tube_axis_direction(TubeAxis axis) {
  constexpr double phi = kernel::kPhi;
  switch (axis) {
    case TubeAxis::X:
      return {1.0, 0.0, 0.0};
    case TubeAxis::Y:
      return {0.0, 1.0, 0.0};
    case TubeAxis::Z:
      return {0.0, 0.0, 1.0};
    case TubeAxis::Gamma1:
      return glm::normalize(glm::dvec3(phi, -1.0, 0.0));
    case TubeAxis::Gamma2:
      return glm::normalize(glm::dvec3(1.0, phi, 0.0));
  }
  return {0.0, 0.0, 1.0};
}

namespace {
constexpr TubeAxis kTubeAxes[] = {TubeAxis::X, TubeAxis::Y, TubeAxis::Z, TubeAxis::Gamma1, TubeAxis::Gamma2};
}

std::optional<TubeAxis> tube_axis_of(const glm::dvec3& direction) {
  for (TubeAxis a : kTubeAxes) {
    if (tube_axis_direction(a) == direction) return a;
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

glm::dvec3 Tube::normal(const glm::dvec3& q) const { return gradient_normal(*this, q); }

glm::dvec2 Tube::pattern_uv(const glm::dvec3& q) const {
  constexpr double kCells = kernel::kPatternCellsPerRadian;
  const glm::dvec3 w = multiply(inverse(through), q);
  if (vertical()) return {kCells * std::atan2(w.y, w.x), kCells * w.z / radius};
  // The axis direction relative to the point `through` (see seen_from).
  const glm::dvec2 h =
      glm::normalize(glm::dvec2(std::exp(-through.z) * direction.x, std::exp(through.z) * direction.y));
  const double along = w.x * h.x + w.y * h.y, across = w.y * h.x - w.x * h.y;
  return {kCells * std::atan2(w.z, across), kCells * along / radius};
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

KernelShape Tube::kernel_shape() const {
  return {kernel::kObjectTube, {through, vertical() ? kernel::kTubeVertical : 0}, {direction.x, direction.y}, radius};
}

// The axis point is moved into D by the element g of Γ that teleports it, and
// the axis with it (left-translation by g = seen from g⁻¹).
Tube Tube::into_domain(const Lattice& lattice) const {
  const Teleport t = lattice.teleport(through);
  Tube moved = seen_from(inverse(t.element));
  moved.through = t.point;
  return moved;
}

double Tube::least_distance_over_domain(const Lattice& lattice) const {
  const Solid solid = vertical() ? Solid::VerticalTube : Solid::HorizontalTube;
  return least_solid_bound(solid, through, vertical() ? glm::dvec2(0.0) : glm::dvec2(direction.x, direction.y), lattice) -
         radius;
}

int Tube::lattice_range() const { return kQuotientLatticeRange; }

bool Tube::same_set(const Tube& other) const {
  constexpr double tol = kSameSetTolerance;
  if (vertical() != other.vertical()) return false;
  if (vertical()) return std::abs(through.x - other.through.x) < tol && std::abs(through.y - other.through.y) < tol;
  const glm::dvec2 d(other.through.x - through.x, other.through.y - through.y);
  return std::abs(through.z - other.through.z) < tol &&
         std::abs(direction.x * other.direction.y - direction.y * other.direction.x) < tol &&
         std::abs(direction.x * d.y - direction.y * d.x) < tol;
}

// ---- Visiting shapes -------------------------------------------------------

std::string_view kind_name(const Shape& shape) {
  return std::visit([](const auto& k) { return std::decay_t<decltype(k)>::kName; }, shape);
}

double shape_distance(const Shape& shape, const glm::dvec3& q) {
  return std::visit([&](const auto& k) { return k.distance(q); }, shape);
}

double shape_clearance(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  return std::visit([&](const auto& k) { return clearance(k.clearance_terms(q, u)); }, shape);
}

Clearances shape_clearances(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u) {
  return std::visit([&](const auto& k) { return clearances(k.clearance_terms(q, u)); }, shape);
}

glm::dvec3 shape_normal(const Shape& shape, const glm::dvec3& q) {
  return std::visit([&](const auto& k) { return k.normal(q); }, shape);
}

Shape shape_seen_from(const Shape& shape, const glm::dvec3& p) {
  return std::visit([&](const auto& k) { return Shape(k.seen_from(p)); }, shape);
}

KernelShape kernel_shape(const Shape& shape) {
  return std::visit([](const auto& k) { return k.kernel_shape(); }, shape);
}

glm::dvec2 shape_pattern_uv(const Shape& shape, const glm::dvec3& q, const glm::dvec3& world) {
  return std::visit(
      [&](const auto& k) {
        using Kind = std::decay_t<decltype(k)>;
        if constexpr (std::is_same_v<Kind, Ball> || std::is_same_v<Kind, Tube>) {
          return k.pattern_uv(q);
        } else {
          return k.pattern_uv(world);
        }
      },
      shape);
}

// ---- Patterns --------------------------------------------------------------

std::string_view to_string(Pattern p) {
  switch (p) {
    case Pattern::None:
      return "none";
    case Pattern::Circles:
      return "circles";
    case Pattern::Checker:
      return "checker";
  }
  return "?";
}

double pattern_factor(Pattern pattern, double u, double v) {
  switch (pattern) {
    case Pattern::None:
      return 1.0;
    case Pattern::Circles: {
      const double du = u - std::floor(u) - 0.5, dv = v - std::floor(v) - 0.5;
      return du * du + dv * dv < kernel::kCircleRadius * kernel::kCircleRadius ? 1.0 : kernel::kCircleDark;
    }
    case Pattern::Checker:
      return std::fmod(std::floor(u) + std::floor(v), 2.0) == 0.0 ? 1.0 : kernel::kCheckerDark;
  }
  return 1.0;
}

// ---- Checks and scene-file keys, kind by kind -----------------------------

namespace detail {
namespace {

using nlohmann::json;

void check_radius(double radius, const std::string& at, bool quotient) {
  if (!(radius > 0.0) || !std::isfinite(radius)) field_error(at + ".radius", at + ".radius must be finite and > 0");
  if (quotient && radius > kMaxQuotientRadius) {
    field_error(at + ".radius",
                at + ".radius must be <= 0.45 in the quotient (the listing of the objects' images around the domain assumes it)");
  }
}

template <class Plane>
void check_plane(const Plane& p, const std::string& at, bool quotient) {
  if (!std::isfinite(p.c) || std::abs(p.c) > kMaxCoordinate) field_error(at + ".c", at + ".c must be finite and within 1e15");
  if (std::is_same_v<Plane, PlaneZ> && !(std::abs(p.c) <= kMaxHeight)) {
    field_error(at + ".c", at + ".c is a height: it must be within [-80, 80] (e^{±z} must stay finite in float)");
  }
  if (quotient && !std::is_same_v<Plane, PlaneZ>) {
    field_error(at + ".type", at + ".type: planes x, y = c are not supported in the quotient (Γ maps them to planes of "
                                   "every slope, dense in M)");
  }
}

void check_kind(const PlaneX& p, const std::string& at, bool quotient) { check_plane(p, at, quotient); }
void check_kind(const PlaneY& p, const std::string& at, bool quotient) { check_plane(p, at, quotient); }
void check_kind(const PlaneZ& p, const std::string& at, bool quotient) { check_plane(p, at, quotient); }

void check_kind(const Ball& b, const std::string& at, bool quotient) {
  check_position(b.center, at + ".center");
  check_radius(b.radius, at, quotient);
}

bool parallel(const glm::dvec3& a, const glm::dvec3& b) { return glm::length(glm::cross(a, b)) < 1e-12; }

void check_kind(const Tube& t, const std::string& at, bool quotient) {
  check_position(t.through, at + ".through");
  const glm::dvec3& d = t.direction;
  if (!finite3(d) || std::abs(glm::length(d) - 1.0) > 1e-12 || (d.z != 0.0 && !t.vertical())) {
    field_error(at + ".axis", at + ".axis must be a unit vertical or horizontal direction");
  }
  check_radius(t.radius, at, quotient);
  if (!quotient) return;
  if (t.vertical()) {
    // A vertical line closes up (as the curve of γ3) when it passes through
    // a lattice point of ⟨γ1, γ2⟩, which γ3 maps into the lattice.
    const glm::dvec2 st = Lattice::golden().lattice_coordinates(t.through.x, t.through.y);
    if (std::abs(st.x - std::round(st.x)) > 1e-9 || std::abs(st.y - std::round(st.y)) > 1e-9) {
      field_error(at + ".through", at + ".through: a tube along z in the quotient must pass through a point (x, y) of the "
                                        "lattice ⟨γ1, γ2⟩ (then it is the closed curve of γ3)");
    }
  } else if (parallel(d, tube_axis_direction(TubeAxis::X)) || parallel(d, tube_axis_direction(TubeAxis::Y))) {
    field_error(at + ".axis", at + ".axis: tubes along x or y do not close up in the quotient (their images are dense); "
                                   "use gamma1, gamma2 or z");
  } else if (!parallel(d, tube_axis_direction(TubeAxis::Gamma1)) && !parallel(d, tube_axis_direction(TubeAxis::Gamma2))) {
    field_error(at + ".axis", at + ".axis: a horizontal tube closes up in the quotient only along gamma1 or gamma2");
  }
}

// A kind's own keys, read into `kind`; `o` is the object's JSON.
void read_plane(const json& o, double& c, bool& cutout, const SceneFileReader& r, const std::string& at) {
  r.require_known_keys(o, {"type", "c", "color", "pattern", "cutout"}, at, at);
  if (o.contains("c")) c = r.number(o["c"], at + ".c");
  if (o.contains("cutout")) cutout = r.boolean(o["cutout"], at + ".cutout");
}
void read_kind(PlaneX& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at) {
  read_plane(o, p.c, obj.cutout, r, at);
}
void read_kind(PlaneY& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at) {
  read_plane(o, p.c, obj.cutout, r, at);
}
void read_kind(PlaneZ& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at) {
  read_plane(o, p.c, obj.cutout, r, at);
}

void read_kind(Ball& b, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at) {
  const std::string what = at + " (a ball)";
  r.require_known_keys(o, {"type", "center", "radius", "color", "pattern", "exact"}, what, at);
  r.require_key(o, "center", what, "a 'center'", at);
  r.require_key(o, "radius", what, "a 'radius'", at);
  b.center = r.vec3(o["center"], at + ".center");
  b.radius = r.number(o["radius"], at + ".radius");
  if (o.contains("exact")) b.exact = r.boolean(o["exact"], at + ".exact");
}

void read_kind(Tube& t, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at) {
  const std::string what = at + " (a tube)";
  r.require_known_keys(o, {"type", "axis", "through", "radius", "color", "pattern"}, what, at);
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
      t.direction = tube_axis_direction(TubeAxis::Z);  // the closed curve of γ3 is the vertical line
    } else if (known != std::end(kTubeAxes)) {
      t.direction = tube_axis_direction(*known);
    } else {
      r.fail(at + ".axis", "'" + at + ".axis' must be x, y, z, gamma1, gamma2 or gamma3, got " + name +
                               " (or a vertical or horizontal direction [a, b, c])");
    }
  }
  t.through = r.vec3(o["through"], at + ".through");
  t.radius = r.number(o["radius"], at + ".radius");
}

json to_json(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

json write_kind(const PlaneX& p, const SceneObject& o) { return {{"c", p.c}, {"cutout", o.cutout}}; }
json write_kind(const PlaneY& p, const SceneObject& o) { return {{"c", p.c}, {"cutout", o.cutout}}; }
json write_kind(const PlaneZ& p, const SceneObject& o) { return {{"c", p.c}, {"cutout", o.cutout}}; }
json write_kind(const Ball& b, const SceneObject&) {
  return {{"center", to_json(b.center)}, {"radius", b.radius}, {"exact", b.exact}};
}
json write_kind(const Tube& t, const SceneObject&) {
  const std::optional<TubeAxis> name = tube_axis_of(t.direction);
  return {{"axis", name ? json(std::string(to_string(*name))) : to_json(t.direction)},
          {"through", to_json(t.through)},
          {"radius", t.radius}};
}

// The kind named `name`, default-constructed; nullopt if there is none.
template <std::size_t I = 0>
std::optional<Shape> shape_named(std::string_view name) {
  if constexpr (I < std::variant_size_v<Shape>) {
    using Kind = std::variant_alternative_t<I, Shape>;
    if (Kind::kName == name) return Shape(Kind{});
    return shape_named<I + 1>(name);
  } else {
    return std::nullopt;
  }
}

template <std::size_t... I>
std::string kind_names(std::index_sequence<I...>) {
  std::string list;
  ((list += std::string(I == 0 ? "" : ", ") + std::string(std::variant_alternative_t<I, Shape>::kName)), ...);
  return list;
}

Pattern read_pattern(const json& value, const SceneFileReader& r, const std::string& path) {
  return r.choice<Pattern>(value, path,
                           {{to_string(Pattern::None), Pattern::None},
                            {to_string(Pattern::Circles), Pattern::Circles},
                            {to_string(Pattern::Checker), Pattern::Checker}});
}

}  // namespace

void check_object(const SceneObject& o, const std::string& at, bool quotient) {
  std::visit([&](const auto& kind) { check_kind(kind, at, quotient); }, o.shape);
  const bool plane = std::holds_alternative<PlaneX>(o.shape) || std::holds_alternative<PlaneY>(o.shape) ||
                     std::holds_alternative<PlaneZ>(o.shape);
  if (o.cutout && (!plane || o.pattern == Pattern::None)) {
    field_error(at + ".cutout", at + ".cutout needs a plane with a pattern (circles or checker)");
  }
  if (!unit_interval3(o.color)) field_error(at + ".color", at + ".color components must be in [0, 1]");
}

SceneObject read_object(const json& o, const SceneFileReader& r, const std::string& at) {
  if (!o.is_object()) r.fail(at, at + " must be an object");
  if (!o.contains("type")) r.fail(at, at + " needs a 'type'");
  const std::string type = SceneFileReader::text(o["type"]);
  const std::optional<Shape> shape = shape_named(type);
  if (!shape) {
    r.fail(at + ".type", "'" + at + ".type' must be one of " +
                             kind_names(std::make_index_sequence<std::variant_size_v<Shape>>()) + ", got " + type);
  }
  SceneObject obj;
  obj.shape = *shape;
  std::visit([&](auto& kind) { read_kind(kind, obj, o, r, at); }, obj.shape);
  if (o.contains("color")) obj.color = r.vec3(o["color"], at + ".color");
  if (o.contains("pattern")) obj.pattern = read_pattern(o["pattern"], r, at + ".pattern");
  return obj;
}

json write_object(const SceneObject& o) {
  json j = std::visit([&](const auto& kind) { return write_kind(kind, o); }, o.shape);
  j["type"] = std::string(kind_name(o.shape));
  j["color"] = to_json(o.color);
  j["pattern"] = std::string(to_string(o.pattern));
  return j;
}

}  // namespace detail
}  // namespace sol
