#include "sol/objects/box.hpp"
#include "sol/patterns.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../field_error.hpp"
#include "../objects_internal.hpp"
#include "sol/clearance.hpp"
#include "sol/group.hpp"
#include "sol/kernel_constants.h"
#include "sol/lattice.hpp"

namespace sol {

using namespace detail;

namespace {

// The signed exact distance to the slab {|x - x0| <= A} along x, asinh(s e^{-z})
// with s = |x - x0| - A (negative inside: minus the distance to its nearer
// face's plane), as a bound term: its rate along u (x' = e^{z} u1, z' = u3)
// is (±u1 - w u3)/√(1 + w²), w = s e^{-z}; where it is positive it is the
// distance to the plane x = x0 ± A, whose bend is at most 1 (sol/clearance.hpp).
BoundTerm slab_term_x(double dx, double half_width, double z, const glm::dvec3& u) {
  const double w = (std::abs(dx) - half_width) * std::exp(-z);
  return {std::asinh(w), ((dx >= 0.0 ? 1.0 : -1.0) * u.x - w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

// The same along y: asinh(s e^{z}), s = |y - y0| - B; rate (±u2 + w u3)/√(1 + w²).
BoundTerm slab_term_y(double dy, double half_width, double z, const glm::dvec3& u) {
  const double w = (std::abs(dy) - half_width) * std::exp(z);
  return {std::asinh(w), ((dy >= 0.0 ? 1.0 : -1.0) * u.y + w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

// How far apart two intervals are (0 where they meet).
double interval_gap(double lo_a, double hi_a, double lo_b, double hi_b) { return std::max({0.0, lo_b - hi_a, lo_a - hi_b}); }

}  // namespace

glm::dvec2 Box::coordinate_half_widths() const {
  return {half_size.x * std::exp(center.z), half_size.y * std::exp(-center.z)};
}

double Box::distance(const glm::dvec3& q) const {
  const glm::dvec2 w = coordinate_half_widths();
  return std::max({std::asinh((std::abs(q.x - center.x) - w.x) * std::exp(-q.z)),
                   std::asinh((std::abs(q.y - center.y) - w.y) * std::exp(q.z)), std::abs(q.z - center.z) - half_size.z});
}

std::array<BoundTerm, 3> Box::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  const glm::dvec2 w = coordinate_half_widths();
  const double dz = q.z - center.z;
  return {slab_term_x(q.x - center.x, w.x, q.z, u), slab_term_y(q.y - center.y, w.y, q.z, u),
          BoundTerm{std::abs(dz) - half_size.z, dz >= 0.0 ? u.z : -u.z, 1.0}};
}

std::array<InsideTerm, 6> Box::inside_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  const glm::dvec2 w = coordinate_half_widths();
  return {face_x(q, u, center.x + w.x, -1.0), face_x(q, u, center.x - w.x, 1.0),
          face_y(q, u, center.y + w.y, -1.0), face_y(q, u, center.y - w.y, 1.0),
          face_z(q, u, center.z + half_size.z, -1.0), face_z(q, u, center.z - half_size.z, 1.0)};
}

glm::dvec3 Box::normal(const glm::dvec3& q) const { return gradient_normal(*this, q); }

// The face nearest q is the slab whose term is largest (left-invariant: in
// the coordinates w of the box's own frame the half widths are a, b, c).
glm::dvec2 Box::pattern_uv(const glm::dvec3& q) const {
  return kernel::sol_box_pattern_uv(multiply(inverse(center), q), half_size);  // sol/patterns.h
}

// p⁻¹·(center·B) = (p⁻¹·center)·B.
Box Box::seen_from(const glm::dvec3& p) const { return {multiply(inverse(p), center), half_size}; }

// Its bound is <= 0 exactly on the coordinate box of its half widths.
CoordinateBox Box::coordinate_box() const {
  const glm::dvec2 w = coordinate_half_widths();
  const glm::dvec3 extent = glm::dvec3(w, half_size.z) * (1.0 + 1e-12);
  return {center - extent, center + extent};
}

// The kernels' record (compute/shaders/kinds/box.glsl): geometry (centre, c),
// heading the coordinate half widths (a e^{z0}, b e^{-z0}), computed here in
// double; in the quotient its image's bound (centre, c), its heading word
// the half widths.
KernelShape Box::kernel_shape() const {
  return {.code = kernel::kObjectBox,
          .geometry = {center, half_size.z},
          .heading = coordinate_half_widths(),
          .bound = {center, half_size.z}};
}

// g·(center·B) = (g·center)·B: the element that teleports the centre moves the box.
Box Box::into_domain(const Lattice& lattice) const { return {lattice.teleport(center).point, half_size}; }

// A lower bound of max(0, bound) over D = {s γ1 + r γ2} × [0, h), cut into
// slabs z in [z0, z1]: there the x-slab's term is at least asinh(g_x e^{-z1})
// (g_x the gap between the box's x-range and that of D's parallelogram P),
// the y-slab's asinh(g_y e^{z0}), the z-slab's the gap between [z0, z1] and
// the box's z-range.
double Box::least_distance_over_domain(const Lattice& lattice) const {
  const DomainExtent e = lattice.domain_extent(center.z);  // the non-compact quotients: sol/lattice.hpp
  const glm::dvec2 w = coordinate_half_widths();
  const double gx = interval_gap(e.xlo, e.xhi, center.x - w.x, center.x + w.x);
  const double gy = interval_gap(e.ylo, e.yhi, center.y - w.y, center.y + w.y);
  double least = e.beyond - half_size.z;  // beyond the slabs, the z-slab's term alone
  for (int i = 0; i < e.slabs; ++i) {
    const double z0 = e.zlo + (e.zhi - e.zlo) * i / e.slabs, z1 = e.zlo + (e.zhi - e.zlo) * (i + 1) / e.slabs;
    least = std::min(least, std::max({std::asinh(gx * std::exp(-z1)), std::asinh(gy * std::exp(z0)),
                                      interval_gap(z0, z1, center.z - half_size.z, center.z + half_size.z)}));
  }
  return least;
}

// Every point of the box is within a + b + c of its centre (along x, then
// y, then z from the centre's frame: lengths a, b, c at most), which the
// quotient's check keeps within kMaxQuotientRadius: the images' search of
// sol::quotient_images holds for it as for a ball of that radius.
// The half-turn is an automorphism and B is symmetric: half_turn(center·B) = half_turn(center)·B.
Box Box::half_turned() const { return {half_turn(center), half_size}; }

ImageAnchor Box::image_anchor() const { return {ImageAnchor::Along::Point, center, {0.0, 0.0}}; }

bool Box::same_set(const Box& other) const {
  return glm::length(center - other.center) < kSameSetTolerance &&
         glm::length(half_size - other.half_size) < kSameSetTolerance;
}

// ---- Checks and scene-file keys

namespace detail {

void check_kind(const Box& b, const std::string& at, const Lattice* quotient) {
  check_position(b.center, at + ".center");
  const glm::dvec3& s = b.half_size;
  if (!finite3(s) || !(s.x > 0.0 && s.y > 0.0 && s.z > 0.0)) {
    field_error(at + ".half_size", at + ".half_size must be finite and > 0 in each component");
  }
  if (!(std::max({s.x, s.y, s.z}) <= kMaxHeight)) {
    field_error(at + ".half_size", at + ".half_size must be at most 80 in each component (e^{±z} must stay finite in float)");
  }
  if (quotient && !(s.x + s.y + s.z <= kMaxQuotientRadius)) {
    field_error(at + ".half_size", at + ".half_size: its components must add up to at most 0.45 in the quotient (every "
                                       "point of the box is then within 0.45 of its centre, which the listing of the "
                                       "objects' images around the domain assumes)");
  }
}

void read_kind(Box& b, SceneObject&, const json& o, const SceneFileReader& r, const std::string& at, const Lattice*) {
  const std::string what = at + " (a box)";
  r.require_known_object_keys(o, {"type", "center", "half_size"}, what, at);
  r.require_key(o, "center", what, "a 'center'", at);
  r.require_key(o, "half_size", what, "a 'half_size'", at);
  b.center = r.vec3(o["center"], at + ".center");
  b.half_size = r.vec3(o["half_size"], at + ".half_size");
}

json write_kind(const Box& b, const SceneObject&, const Lattice*) { return {{"center", to_json(b.center)}, {"half_size", to_json(b.half_size)}}; }

}  // namespace detail
}  // namespace sol
