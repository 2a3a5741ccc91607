// The objects of a scene: the kinds (one header each under sol/objects/,
// listed once in sol/object_kinds.h), the shape variant over them, and a
// scene object (a shape with a colour and a pattern). sol/objects/kind.hpp
// says what a kind provides; docs/renderer.md "Adding a kind of object"
// what a new one touches.
#pragma once

#include <concepts>
#include <memory>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "sol/material_kinds.h"
#include "sol/texture.hpp"
#include "sol/object_kinds.h"
#include "sol/objects/ball.hpp"
#include "sol/objects/box.hpp"
#include "sol/objects/composite.hpp"
#include "sol/objects/kind.hpp"
#include "sol/objects/planes.hpp"
#include "sol/objects/tube.hpp"
#include "sol/materials/lobes.h"

namespace sol {

namespace detail {
// std::variant of the distinct types of a list that ends with EndOfKinds, in
// their first order (SOL_OBJECT_KINDS may draw one type as several kinds).
struct EndOfKinds;
template <class Done, class... Rest>
struct DistinctKinds;
template <class... Done>
struct DistinctKinds<std::variant<Done...>, EndOfKinds> {
  using type = std::variant<Done...>;
};
template <class... Done, class Next, class... Rest>
struct DistinctKinds<std::variant<Done...>, Next, Rest...> {
  using type = typename DistinctKinds<std::conditional_t<(std::is_same_v<Next, Done> || ...), std::variant<Done...>,
                                                         std::variant<Done..., Next>>,
                                      Rest...>::type;
};
}  // namespace detail

#define SOL_KIND_TYPE(Type, code_name, code, prefix, feature, solid) Type,
/// Every kind of object: the types of SOL_OBJECT_KINDS, and composites of
/// them (sol/objects/composite.hpp; no kernel kind of their own).
using Shape =
    typename detail::DistinctKinds<std::variant<>, SOL_OBJECT_KINDS(SOL_KIND_TYPE) Composite, detail::EndOfKinds>::type;
#undef SOL_KIND_TYPE

/// A composite's parts: A, and B (united with, intersected with or taken from A).
struct CompositeParts {
  Shape a;
  Shape b;
  bool operator==(const CompositeParts&) const = default;
};

/// Composite::visit_fields: each part's fields through a visitor, their
/// names prefixed by the part's ("a: ", "b: "; a nested composite's by both,
/// through the same visitor type, so that the templates do not nest), on a
/// copy of the parts that replaces the shared ones where a field changed.
template <class Visitor>
struct PrefixedFields {
  Visitor& visit;
  std::string prefix;
  template <class... Rest>
  void operator()(const char* name, Rest&&... rest) {
    const std::string full = prefix + name;
    visit(full.c_str(), std::forward<Rest>(rest)...);
  }
};

template <class Visitor>
void visit_composite_parts(Composite& composite, Visitor& visit, const std::string& prefix) {
  CompositeParts edited = *composite.parts;
  PrefixedFields<Visitor> a{visit, prefix + "a: "}, b{visit, prefix + "b: "};
  std::visit([&](auto& kind) { kind.visit_fields(a); }, edited.a);
  std::visit([&](auto& kind) { kind.visit_fields(b); }, edited.b);
  if (!(edited == *composite.parts)) composite.parts = std::make_shared<const CompositeParts>(std::move(edited));
}

template <class Visitor>
void visit_composite_fields(Composite& composite, Visitor& visit) {
  visit_composite_parts(composite, visit, "");
}

template <class Visitor>
void visit_composite_fields(Composite& composite, PrefixedFields<Visitor>& visit) {
  visit_composite_parts(composite, visit.visit, visit.prefix);
}

/// The composite as a chain ((P0 op1 P1) op2 P2) ... of parts that are not
/// composites, each with the operation joining it to the chain before it
/// (P0's unused): nested composites as parts a unfold into it (the
/// kernel's form), and so does a part b that is a chain of unions under a
/// union or a difference (of intersections under an intersection), with
/// the same distance. Empty where a part b is any other composite.
std::vector<std::pair<const Shape*, CompositeOp>> composite_chain(const Composite& composite);

#define SOL_KIND_SOLID(Type, code_name, code, prefix, feature, solid) \
  static_assert(Type::kSolid == solid, "sol/object_kinds.h: " #Type "::kSolid disagrees with the list");
SOL_OBJECT_KINDS(SOL_KIND_SOLID)
#undef SOL_KIND_SOLID

#define SOL_MATERIAL_ENUM(Enum, code_name, code, prefix, name) Enum = code,
/// How an object's surface scatters light: one per line of SOL_MATERIALS
/// (sol/material_kinds.h), its value the kernels' code.
enum class Material { SOL_MATERIALS(SOL_MATERIAL_ENUM) };
#undef SOL_MATERIAL_ENUM
/// The scene file's name of a material ("diffuse", "mirror", ...).
std::string_view to_string(Material material);
/// Every material, in the list's order.
std::span<const Material> materials();

/// The scene file's name of the shape's kind ("plane_z", "ball", ...).
std::string_view kind_name(const Shape& shape);

enum class Pattern {
  None,     ///< plain base colour
  Circles,  ///< discs of radius 0.3 centred on the unit grid of the pattern's coordinates
  Checker,  ///< unit checkerboard in the pattern's coordinates
};
std::string_view to_string(Pattern pattern);

/// The pattern's code in the kernels' records and sol/patterns.h (kernel::kPattern*).
int pattern_code(Pattern pattern);
/// The brightness factor of a pattern at pattern coordinates (u, v): 1 on
/// the discs and light squares, kernel::kCircleDark and kernel::kCheckerDark
/// elsewhere (kernel::sol_pattern_factor, sol/patterns.h).
double pattern_factor(Pattern pattern, double u, double v);

struct SceneObject {
  Shape shape = PlaneZ{};
  glm::dvec3 color{0.8, 0.8, 0.8};  ///< linear RGB in [0, 1]
  Pattern pattern = Pattern::None;
  /// Planes: only the pattern's bright cells (discs, light squares) are solid.
  bool cutout = false;
  /// How the surface scatters light (sol/materials/<name>.h): diffuse
  /// (Lambertian, with `mirror` on top), a mirror coloured by `color`,
  /// glossy (a rough mirror of `roughness`) or glass (a dielectric of
  /// index `ior`; solids only).
  Material material = Material::Diffuse;
  /// Emitted radiance, linear RGB (>= 0): a glowing object shows it on top
  /// of the light it reflects (every material).
  glm::dvec3 emission{0.0, 0.0, 0.0};
  /// The diffuse material's specular reflectance in [0, 1]: the share of
  /// the light that comes along the geodesic reflected in the surface (the
  /// rest is diffuse, with albedo `color`); up to World::max_bounces
  /// reflections.
  double mirror = 0.0;
  /// The glossy material's roughness in [0, 1] (sol/materials/glossy.h):
  /// 0 reflects as a mirror, 1 in a broad sheen. A scene file's glossy
  /// object without "roughness" takes kDefaultRoughness.
  double roughness = 0.0;
  static constexpr double kDefaultRoughness = 0.3;
  /// The glass material's index of refraction in [1, 3] (sol/materials/glass.h;
  /// 1: as air, the object unseen). A scene file's glass object without
  /// "ior" takes kDefaultIor (crown glass).
  double ior = 0.0;
  static constexpr double kDefaultIor = 1.5;
  /// A glowing exact ball's reach for the path tracer's next-event
  /// estimation, in [0, 10]: a diffuse point is connected to a sampled
  /// point of its sphere along every geodesic up to their distance plus
  /// this (0: the minimising ones alone). Sol only (in a quotient paths
  /// reach glowing balls by reflection sampling).
  double glow_reach = 0.0;
  /// An image over the surface (sol/texture.hpp): the albedo is the colour
  /// times the pattern times the image's colour at the pattern
  /// coordinates, one copy of the image over `texture_cells` pattern cells
  /// (sol/texture.h). Null: none.
  std::shared_ptr<const Texture> texture;
  glm::dvec2 texture_cells{1.0, 1.0};
};

/// How the object's material scatters light at a point of albedo `albedo`
/// (its colour times its pattern there): sol_material_lobes, the kernels'
/// own function, in double.
kernel::SolLobes material_lobes(const SceneObject& object, const glm::dvec3& albedo);
/// The parameters sol_material_lobes takes for the object's material (x:
/// the diffuse material's mirror share, the glossy one's roughness): the
/// kernel's record holds them (sol::vk::kernel::Object::params).
glm::dvec4 material_params(const SceneObject& object);
/// Whether the object's material may reflect specularly (its lobes under a
/// white albedo have a specular weight): a world with one marches
/// reflected rays (MarchFeatures::mirrors).
bool material_reflects(const SceneObject& object);

/// The kinds that close up in the compact quotient (planes z = c, balls,
/// tubes along γ1, γ2, γ3, boxes): those sol::quotient_images moves by Γ.
template <class Kind>
concept ClosesInQuotient = requires(const Kind& kind, const Lattice& lattice) {
  { kind.into_domain(lattice) } -> std::same_as<Kind>;
  { kind.least_distance_over_domain(lattice) } -> std::convertible_to<double>;
  { kind.image_anchor() } -> std::same_as<ImageAnchor>;
  { kind.half_turned() } -> std::same_as<Kind>;
  { kind.same_set(kind) } -> std::convertible_to<bool>;
};

/// Largest radius of a solid in a quotient scene (boxes: the sum of their
/// half sizes, which bounds the distance from the centre to every point): the proof that
/// sol::quotient_images lists every image a step can reach assumes it
/// (its search covers the anchors within the longest step and this radius of D).
constexpr double kMaxQuotientRadius = 0.45;

// Visiting a shape: the distance, normal, pattern coordinates and
// left-translation of whichever kind it holds.
double shape_distance(const Shape& shape, const glm::dvec3& q);
/// How far the geodesic from q along u goes before it can reach the shape
/// (sol::clearance of its clearance_terms).
double shape_clearance(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u);
/// The same ahead along u and back along -u, from one evaluation of the
/// terms (sol::clearances).
Clearances shape_clearances(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u);
/// Seen from a point q inside a solid (its distance below 0): how far the
/// geodesic from q goes along u, and back along −u, before it can reach
/// the solid's surface (sol::inside_clearances of the kind's inside_terms;
/// an exact ball's are its bound's, which is larger: the march takes the
/// exact ball's own), and the rate of its nearest face. Not a solid, or no
/// inside terms: −distance both ways.
InsideClearances shape_inside_clearances(const Shape& shape, const glm::dvec3& q, const glm::dvec3& u);
glm::dvec3 shape_normal(const Shape& shape, const glm::dvec3& q);
/// Whether the shape is a solid (its kind's kSolid).
bool is_solid(const Shape& shape);
/// Whether the shape is a ball drawn as the true geodesic sphere (Ball::exact).
bool is_exact_ball(const Shape& shape);
Shape shape_seen_from(const Shape& shape, const glm::dvec3& p);
/// The kind's coordinate_box(): every point of the shape (distance <= 0) lies in it.
CoordinateBox shape_coordinate_box(const Shape& shape);
KernelShape kernel_shape(const Shape& shape);
/// Planes: their own coordinates of the world point; solids: of the point
/// relative to their centre (axis point), left-invariant, so any
/// coordinates in which the shape and q are both given will do.
glm::dvec2 shape_pattern_uv(const Shape& shape, const glm::dvec3& q, const glm::dvec3& world);

}  // namespace sol
