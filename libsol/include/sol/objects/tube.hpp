// Tubes about vertical and horizontal lines (sol/objects/kind.hpp says what a
// kind provides). Source: libsol/src/objects/tube.cpp.
#pragma once

#include <optional>
#include <string_view>

#include "sol/lattice.hpp"
#include "sol/objects/kind.hpp"

namespace sol {

/// The named axes of a tube: the coordinate lines, and the horizontal lines
/// along a lattice's γ1 and γ2 (for the golden lattice (φ, -1, 0) and
/// (1, φ, 0); the one-parameter subgroups t·γ1, t·γ2 of the plane z = 0,
/// translated): through a point of Γ·o these are the closed curves of γ1,
/// γ2 in M = Γ\Sol, and the z-line is the closed curve of γ3.
enum class TubeAxis { X, Y, Z, Gamma1, Gamma2 };

/// Unit coordinate direction of a named axis: (1,0,0), (0,1,0), (0,0,1),
/// γ1/|γ1|, γ2/|γ2| of `lattice` (the world's quotient's, or
/// Lattice::default_axes(); a z loop's are the default's).
glm::dvec3 tube_axis_direction(TubeAxis axis, const Lattice& lattice);
/// The name of a direction when it is one of the named axes' (exactly).
std::optional<TubeAxis> tube_axis_of(const glm::dvec3& direction, const Lattice& lattice);
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
  static constexpr bool kSolid = true;
  glm::dvec3 through{0.0};
  glm::dvec3 direction{0.0, 0.0, 1.0};
  double radius = 0.5;

  bool vertical() const { return direction.x == 0.0 && direction.y == 0.0; }
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 2> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Seen from inside: its faces (sol::tube_inside_terms).
  std::array<InsideTerm, 4> inside_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The bound's gradient by central differences (as Ball's).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Tube seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  Tube into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  ImageAnchor image_anchor() const;
  Tube half_turned() const;
  bool same_set(const Tube& other) const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("through", through);
    visit("radius", radius, FieldRange{0.005, 0.01, 5.0});
  }
  bool operator==(const Tube&) const = default;
};

/// A tube along a named axis (of `lattice`: gamma1 and gamma2 are its generators').
inline Tube make_tube(TubeAxis axis, const glm::dvec3& through, double radius, const Lattice& lattice) {
  return {through, tube_axis_direction(axis, lattice), radius};
}

}  // namespace sol
