#include "sol/objects/planes.hpp"

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

CoordinateBox PlaneX::coordinate_box() const {
  CoordinateBox b = CoordinateBox::everywhere();
  b.lo.x = b.hi.x = c;
  return b;
}

KernelShape PlaneX::kernel_shape() const {
  return {.code = kernel::kObjectPlaneX, .geometry = {c, 0.0, 0.0, 0.0}, .bound = {c, 0.0, 0.0, 0.0}};
}

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

CoordinateBox PlaneY::coordinate_box() const {
  CoordinateBox b = CoordinateBox::everywhere();
  b.lo.y = b.hi.y = c;
  return b;
}

KernelShape PlaneY::kernel_shape() const {
  return {.code = kernel::kObjectPlaneY, .geometry = {c, 0.0, 0.0, 0.0}, .bound = {c, 0.0, 0.0, 0.0}};
}

// ---- PlaneZ --------------------------------------------------------------

double PlaneZ::distance(const glm::dvec3& q) const { return sdf_plane_z(q, c); }

std::array<BoundTerm, 1> PlaneZ::clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const {
  return {plane_z_term(q, u, c)};
}

glm::dvec3 PlaneZ::normal(const glm::dvec3&) const { return {0.0, 0.0, origin_side(c)}; }

PlaneZ PlaneZ::seen_from(const glm::dvec3& p) const { return {c - p.z}; }

CoordinateBox PlaneZ::coordinate_box() const {
  CoordinateBox b = CoordinateBox::everywhere();
  b.lo.z = b.hi.z = c;
  return b;
}

KernelShape PlaneZ::kernel_shape() const {
  return {.code = kernel::kObjectPlaneZ, .geometry = {c, 0.0, 0.0, 0.0}, .bound = {c, 0.0, 0.0, 0.0}};
}

PlaneZ PlaneZ::into_domain(const Lattice& lattice) const {
  if (lattice.loops() == Lattice::Loops::XY) return *this;  // γ1, γ2 fix it, and there is no γ3
  const double h = lattice.height();
  return {c - h * std::floor(c / h)};
}

double PlaneZ::least_distance_over_domain(const Lattice& lattice) const {
  return lattice.loops() == Lattice::Loops::XY ? 0.0 : gap(c, 0.0, lattice.height());  // xy loops: D has every height
}

bool PlaneZ::same_set(const PlaneZ& other) const { return std::abs(c - other.c) < kSameSetTolerance; }

// ---- Checks and scene-file keys

namespace detail {

template <class Plane>
void check_plane(const Plane& p, const std::string& at, const Lattice* quotient) {
  if (!std::isfinite(p.c) || std::abs(p.c) > kMaxCoordinate) field_error(at + ".c", at + ".c must be finite and within 1e15");
  if (std::is_same_v<Plane, PlaneZ> && !(std::abs(p.c) <= kMaxHeight)) {
    field_error(at + ".c", at + ".c is a height: it must be within [-80, 80] (e^{±z} must stay finite in float)");
  }
  if (quotient && !std::is_same_v<Plane, PlaneZ>) {
    field_error(at + ".type", quotient->compact() ? at + ".type: planes x, y = c are not supported in the quotient (Γ maps "
                                                         "them to planes of every slope, dense in M)"
                                                  : at + ".type: planes x, y = c are not supported in the quotient (its loops "
                                                         "map them to planes without end near the domain)");
  }
}

void check_kind(const PlaneX& p, const std::string& at, const Lattice* quotient) { check_plane(p, at, quotient); }
void check_kind(const PlaneY& p, const std::string& at, const Lattice* quotient) { check_plane(p, at, quotient); }
void check_kind(const PlaneZ& p, const std::string& at, const Lattice* quotient) { check_plane(p, at, quotient); }

void read_plane(const json& o, double& c, bool& cutout, const SceneFileReader& r, const std::string& at) {
  r.require_known_object_keys(o, {"type", "c", "cutout"}, at, at);
  if (o.contains("c")) c = r.number(o["c"], at + ".c");
  if (o.contains("cutout")) cutout = r.boolean(o["cutout"], at + ".cutout");
}
void read_kind(PlaneX& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at, const Lattice*) {
  read_plane(o, p.c, obj.cutout, r, at);
}
void read_kind(PlaneY& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at, const Lattice*) {
  read_plane(o, p.c, obj.cutout, r, at);
}
void read_kind(PlaneZ& p, SceneObject& obj, const json& o, const SceneFileReader& r, const std::string& at, const Lattice*) {
  read_plane(o, p.c, obj.cutout, r, at);
}

json write_kind(const PlaneX& p, const SceneObject& o, const Lattice*) { return {{"c", p.c}, {"cutout", o.cutout}}; }
json write_kind(const PlaneY& p, const SceneObject& o, const Lattice*) { return {{"c", p.c}, {"cutout", o.cutout}}; }
json write_kind(const PlaneZ& p, const SceneObject& o, const Lattice*) { return {{"c", p.c}, {"cutout", o.cutout}}; }

}  // namespace detail
}  // namespace sol
