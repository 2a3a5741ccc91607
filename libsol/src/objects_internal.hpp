// What the kinds of object share beyond their public interface (not
// installed): helpers of their geometry, and the checks and scene-file keys
// of each kind (declared here for every kind of sol/object_kinds.h, defined
// with the kind's geometry in libsol/src/objects/<kind>.cpp).
#pragma once

#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene_reader.hpp"
#include "sol/objects.hpp"

namespace sol::detail {

// ---- Helpers of the kinds' geometry (objects.cpp)

// Two images are the same set when they agree to this.
inline constexpr double kSameSetTolerance = 1e-9;

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
inline double origin_side(double c) { return 0.0 >= c ? 1.0 : -1.0; }

inline double gap(double v, double lo, double hi) { return v < lo ? lo - v : (v > hi ? v - hi : 0.0); }

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
//
// The non-compact quotients (Lattice::Loops): a z loop's D = R² × [0, h) has
// no x-, y-range (gap_x = gap_y = 0, and a horizontal tube's least |h_y Δx -
// h_x Δy| is 0), so only |Δz| bounds; xy loops' D = P × R is unbounded in
// z, and the slabs cover only c_z ± kBeyond: above and below, |Δz| alone
// exceeds kBeyond (a vertical tube, which has no |Δz| term, gets 0 there).
enum class Solid { Ball, VerticalTube, HorizontalTube };
double least_solid_bound(Solid solid, const glm::dvec3& c, const glm::dvec2& heading, const Lattice& lattice);

// ---- Checks and scene-file keys

/// A radius finite and > 0, and in the quotient at most kMaxQuotientRadius
/// (FieldError at `at`.radius).
void check_radius(double radius, const std::string& at, const Lattice* quotient);

json to_json(const glm::dvec3& v);

// Each kind's checks of scene object `at` ("objects[2]"; with `quotient`,
// the world's lattice, those of its compact quotient; throws FieldError), its own keys read from
// the object's JSON `o` into `kind` (and the object), and written back (names
// of lattice directions are `quotient`'s, the golden lattice's without one).
#define SOL_KIND_FILE_FUNCTIONS(Type, code_name, code, prefix, feature, solid)                                 \
  void check_kind(const Type& kind, const std::string& at, const Lattice* quotient);                                   \
  void read_kind(Type& kind, SceneObject& object, const json& o, const SceneFileReader& reader, const std::string& at, \
                 const Lattice* quotient);                                                                             \
  json write_kind(const Type& kind, const SceneObject& object, const Lattice* quotient);
SOL_OBJECT_KINDS(SOL_KIND_FILE_FUNCTIONS)
SOL_KIND_FILE_FUNCTIONS(Composite, , , , , )
#undef SOL_KIND_FILE_FUNCTIONS

/// A composite's part at `at` ("objects[2].a"): a solid's "type" and its
/// kind's keys, no appearance (the composite's); and its JSON back.
Shape read_part(const json& value, const SceneFileReader& reader, const std::string& at, const Lattice* quotient);
json write_part(const Shape& part, const Lattice* quotient);

/// The checks of scene object `at` ("objects[2]"), and with `quotient` (the
/// world's lattice) those of its compact quotient; throws FieldError.
void check_object(const SceneObject& object, const std::string& at, const Lattice* quotient);

/// A scene object from its JSON at path `at`, in a world whose quotient's
/// lattice is `quotient` (null in Sol: names of axes such as gamma1 are the
/// lattice's).
SceneObject read_object(const json& value, const SceneFileReader& reader, const std::string& at, const Lattice* quotient);
/// The JSON of a scene object (read_object reads it back with the same lattice).
json write_object(const SceneObject& object, const Lattice* quotient);

}  // namespace sol::detail
