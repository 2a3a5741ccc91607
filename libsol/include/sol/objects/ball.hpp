// Balls, drawn with their distance bound or as the true geodesic sphere
// (sol/objects/kind.hpp says what a kind provides). Source:
// libsol/src/objects/ball.cpp.
#pragma once

#include "sol/objects/kind.hpp"

namespace sol {

/// The points within `radius` of `center`. Drawn with the distance bound
/// (sol::sdf_ball), or with `exact` as the true geodesic sphere
/// (sol::sdf_ball_exact). Pattern: with w = centre⁻¹·q, (4/π)·(longitude
/// atan2(w_y, w_x), latitude atan2(w_z, |w_xy|)): 8 cells around, 4 from pole to pole.
struct Ball {
  static constexpr std::string_view kName = "ball";
  static constexpr bool kSolid = true;
  glm::dvec3 center{0.0};
  double radius = 0.5;
  bool exact = false;

  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 2> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Seen from inside the bound's ball (sol/clearance.hpp): an exact ball
  /// lies inside it, so the march takes its own (exact_ball_inside_clearance).
  std::array<InsideTerm, 2> inside_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The true sphere's normal when exact, else the bound's gradient by
  /// central differences (kernel::kNormalStep along E1, E2, E3).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Ball seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  Ball into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  ImageAnchor image_anchor() const;
  Ball half_turned() const;
  bool same_set(const Ball& other) const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("centre", center);
    visit("radius", radius, FieldRange{0.005, 0.01, 5.0});
    visit("exact (the true geodesic sphere)", exact);
  }
  bool operator==(const Ball&) const = default;
};

}  // namespace sol
