// The planes x = c, y = c and z = c (sol/objects/kind.hpp says what a kind
// provides). Sources: libsol/src/objects/planes.cpp.
#pragma once

#include "sol/objects/kind.hpp"

namespace sol {

/// The plane x = c, a totally geodesic hyperbolic plane. Pattern in its own
/// coordinates (y, z).
struct PlaneX {
  static constexpr std::string_view kName = "plane_x";
  static constexpr bool kSolid = false;
  double c = 0.0;

  /// asinh(|x - c| e^{-z}).
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Facing the side of the origin (the march's point of view).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.y, world.z}; }
  PlaneX seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("c", c, FieldRange{0.01, -80.0, 80.0});
  }
  bool operator==(const PlaneX&) const = default;
};

/// The plane y = c, a totally geodesic hyperbolic plane. Pattern in (x, z).
struct PlaneY {
  static constexpr std::string_view kName = "plane_y";
  static constexpr bool kSolid = false;
  double c = 0.0;

  /// asinh(|y - c| e^{z}).
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.x, world.z}; }
  PlaneY seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("c", c, FieldRange{0.01, -80.0, 80.0});
  }
  bool operator==(const PlaneY&) const = default;
};

/// The plane z = c, flat (a Euclidean plane in its own metric). Pattern in (x, y).
struct PlaneZ {
  static constexpr std::string_view kName = "plane_z";
  static constexpr bool kSolid = false;
  double c = 0.0;

  /// |z - c|.
  double distance(const glm::dvec3& q) const;
  std::array<BoundTerm, 1> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& world) const { return {world.x, world.y}; }
  PlaneZ seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  // The quotient: γ3 moves it by the lattice height; γ1, γ2 fix it.
  PlaneZ into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  ImageAnchor image_anchor() const { return {ImageAnchor::Along::Height, {0.0, 0.0, c}, {0.0, 0.0}}; }
  PlaneZ half_turned() const { return *this; }
  bool same_set(const PlaneZ& other) const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("c", c, FieldRange{0.01, -80.0, 80.0});
  }
  bool operator==(const PlaneZ&) const = default;
};

}  // namespace sol
