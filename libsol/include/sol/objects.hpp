// The kinds of object a scene holds, each a type with its own geometry.
//
// A kind is a struct: its data (in Sol coordinates, directions as
// coordinate directions), and what the march needs of it, in whatever
// coordinates the object and the point are both given in:
//   distance(q)      a signed distance: exact for planes, a lower bound for
//                    balls and tubes (sol/distance.hpp), so sphere tracing
//                    never passes through the surface;
//   clearance_terms(q, u)
//                    the terms of its bound at q along the geodesic with
//                    unit tangent u (sol/clearance.hpp), from which
//                    sol::shape_clearance and sol::shape_clearances take how
//                    far that geodesic goes before it can reach the object:
//                    at least the bound's distance, longer beside it (exact
//                    balls: the bound's ball's, which holds them, so a
//                    march steps by the larger of it and distance(q));
//   normal(q)        the unit surface normal at a hit q (frame components);
//   pattern_uv(q)    the coordinates its pattern is drawn in;
//   seen_from(p)     the same object left-translated by p⁻¹ (relative to p);
//   kernel_shape()   what the GLSL kernels read of it (sol/kernel_constants.h codes);
// and for kinds that close up in the compact quotient (planes z = c, balls,
// tubes along γ1, γ2, γ3): into_domain, least_distance_over_domain,
// lattice_range and same_set (sol::quotient_images). A scene object is a
// kind (`Shape`, a std::variant) with a colour and a pattern. Adding a kind:
// its struct here, its functions in objects.cpp (geometry, checks, scene-
// file keys), its distance and clearance in compute/shaders/march/objects.glsl, and
// its tests.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sol/clearance.hpp"

namespace sol {

class Lattice;

/// What the kernels read of an object (compute/shaders/march/objects.glsl).
struct KernelShape {
  int code = 0;                   ///< kernel::kObject*
  glm::dvec4 geometry{0.0};       ///< planes (c, 0, 0, 0); balls (centre, 0); tubes (point of the axis, axis code)
  glm::dvec2 heading{0.0};        ///< horizontal tubes: the axis's unit coordinate direction
  double radius = 0.0;            ///< balls, tubes
};

/// The plane x = c, a totally geodesic hyperbolic plane. Pattern in its own
/// coordinates (y, z).
struct PlaneX {
  static constexpr std::string_view kName = "plane_x";
  double c = 0.0;

  /// asinh(|x - c| e^{-z}).
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Facing the side of the origin (the march's point of view).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.y, world.z}; }
  PlaneX seen_from(const glm::dvec3& p) const;
  KernelShape kernel_shape() const;
  bool operator==(const PlaneX&) const = default;
};

/// The plane y = c, a totally geodesic hyperbolic plane. Pattern in (x, z).
struct PlaneY {
  static constexpr std::string_view kName = "plane_y";
  double c = 0.0;

  /// asinh(|y - c| e^{z}).
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.x, world.z}; }
  PlaneY seen_from(const glm::dvec3& p) const;
  KernelShape kernel_shape() const;
  bool operator==(const PlaneY&) const = default;
};

/// The plane z = c, flat (a Euclidean plane in its own metric). Pattern in (x, y).
struct PlaneZ {
  static constexpr std::string_view kName = "plane_z";
  double c = 0.0;

  /// |z - c|.
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.x, world.y}; }
  PlaneZ seen_from(const glm::dvec3& p) const;
  KernelShape kernel_shape() const;
  // The quotient: γ3 moves it by the lattice height; γ1, γ2 fix it.
  PlaneZ into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  int lattice_range() const { return 0; }
  bool same_set(const PlaneZ& other) const;
  bool operator==(const PlaneZ&) const = default;
};

/// The points within `radius` of `center`. Drawn with the distance bound
/// (sol::sdf_ball), or with `exact` as the true geodesic sphere
/// (sol::sdf_ball_exact). Pattern: with w = centre⁻¹·q, (4/π)·(longitude
/// atan2(w_y, w_x), latitude atan2(w_z, |w_xy|)): 8 cells around, 4 from pole to pole.
struct Ball {
  static constexpr std::string_view kName = "ball";
  glm::dvec3 center{0.0};
  double radius = 0.5;
  bool exact = false;

  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 2> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The true sphere's normal when exact, else the bound's gradient by
  /// central differences (kernel::kNormalStep along E1, E2, E3).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Ball seen_from(const glm::dvec3& p) const;
  KernelShape kernel_shape() const;
  Ball into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  int lattice_range() const;
  bool same_set(const Ball& other) const;
  bool operator==(const Ball&) const = default;
};

/// The named axes of a tube: the coordinate lines, and the horizontal lines
/// along γ1 = (φ, -1, 0) and γ2 = (1, φ, 0) (the one-parameter subgroups
/// t·γ1, t·γ2 of the plane z = 0, translated): through a point of Γ·o these
/// are the closed curves of γ1, γ2 in M = Γ\Sol, and the z-line is the
/// closed curve of γ3.
enum class TubeAxis { X, Y, Z, Gamma1, Gamma2 };

/// Unit coordinate direction of a named axis: (1,0,0), (0,1,0), (0,0,1),
/// (φ,-1,0)/|.|, (1,φ,0)/|.|.
glm::dvec3 tube_axis_direction(TubeAxis axis);
/// The name of a direction when it is one of the named axes' (exactly).
std::optional<TubeAxis> tube_axis_of(const glm::dvec3& direction);
/// The scene file's name of an axis: "x", "y", "z", "gamma1", "gamma2".
std::string_view to_string(TubeAxis axis);

/// The points within `radius` of the line through `through` along
/// `direction`, a unit coordinate direction, vertical (0, 0, ±1) or
/// horizontal (h_x, h_y, 0): a left translation maps such a line to one of
/// the same kind. Drawn with the bound of sol::sdf_tube (vertical) or
/// sol::sdf_tube_horizontal. Pattern: with w = through⁻¹·q, (4/π)·the angle
/// around the axis and 4/(π r)·the coordinate along it (square cells of side
/// πr/4 on the surface).
struct Tube {
  static constexpr std::string_view kName = "tube";
  glm::dvec3 through{0.0};
  glm::dvec3 direction{0.0, 0.0, 1.0};
  double radius = 0.5;

  bool vertical() const { return direction.x == 0.0 && direction.y == 0.0; }
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 2> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The bound's gradient by central differences (as Ball's).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Tube seen_from(const glm::dvec3& p) const;
  KernelShape kernel_shape() const;
  Tube into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  int lattice_range() const;
  bool same_set(const Tube& other) const;
  bool operator==(const Tube&) const = default;
};

/// A tube along a named axis.
inline Tube make_tube(TubeAxis axis, const glm::dvec3& through, double radius) {
  return {through, tube_axis_direction(axis), radius};
}

using Shape = std::variant<PlaneX, PlaneY, PlaneZ, Ball, Tube>;

/// The scene file's name of the shape's kind ("plane_z", "ball", ...).
std::string_view kind_name(const Shape& shape);

enum class Pattern {
  None,     ///< plain base colour
  Circles,  ///< discs of radius 0.3 centred on the unit grid of the pattern's coordinates
  Checker,  ///< unit checkerboard in the pattern's coordinates
};
std::string_view to_string(Pattern pattern);

/// The brightness factor of a pattern at pattern coordinates (u, v): 1 on
/// the discs and light squares, kernel::kCircleDark and kernel::kCheckerDark elsewhere.
double pattern_factor(Pattern pattern, double u, double v);

struct SceneObject {
  Shape shape = PlaneZ{};
  glm::dvec3 color{0.8, 0.8, 0.8};  ///< linear RGB in [0, 1]
  Pattern pattern = Pattern::None;
  /// Planes: only the pattern's bright cells (discs, light squares) are solid.
  bool cutout = false;
};

/// Largest radius of a ball or tube in a quotient scene: the proof that
/// sol::quotient_images lists every image a step can reach assumes it
/// (lattice words γ3^c with |c| <= 2 only, which holds while 2h - radius
/// exceeds the longest quotient step, 0.9; and the widths of its search).
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
glm::dvec3 shape_normal(const Shape& shape, const glm::dvec3& q);
Shape shape_seen_from(const Shape& shape, const glm::dvec3& p);
KernelShape kernel_shape(const Shape& shape);
/// Planes: their own coordinates of the world point; balls, tubes: of the
/// point relative to their centre (axis point), left-invariant, so any
/// coordinates in which the shape and q are both given will do.
glm::dvec2 shape_pattern_uv(const Shape& shape, const glm::dvec3& q, const glm::dvec3& world);

}  // namespace sol
