// Boxes: left translates of coordinate boxes (sol/objects/kind.hpp says what
// a kind provides). Source: libsol/src/objects/box.cpp.
#pragma once

#include "sol/objects/kind.hpp"

namespace sol {

/// The solid center · ([-a, a] × [-b, b] × [-c, c]), (a, b, c) = half_size:
/// the left translate of a coordinate box, which is again a coordinate box,
/// [x0 - a e^{z0}, x0 + a e^{z0}] × [y0 - b e^{-z0}, y0 + b e^{-z0}] ×
/// [z0 - c, z0 + c] for center (x0, y0, z0). Its faces lie on planes
/// x = const and y = const (totally geodesic) and z = const, so it is the
/// intersection of three slabs, and the largest of the exact (signed)
/// distances to them, max(asinh(s_x e^{-z}), asinh(s_y e^{z}), s_z) with
/// s_x = |x - x0| - a e^{z0}, s_y = |y - y0| - b e^{-z0}, s_z = |z - z0| - c,
/// is a lower bound of the distance to the box, exact near each face.
/// Pattern: on the face nearest a point, the two coordinates of w =
/// center⁻¹·q along it, in cells of half the smallest half size.
struct Box {
  static constexpr std::string_view kName = "box";
  static constexpr bool kSolid = true;
  glm::dvec3 center{0.0};
  glm::dvec3 half_size{0.25, 0.25, 0.25};

  /// The half-widths of the box in x and y coordinates: a e^{z0}, b e^{-z0}.
  glm::dvec2 coordinate_half_widths() const;
  double distance(const glm::dvec3& q) const;
  /// The three slabs' terms (sol/clearance.hpp: each a distance to a plane,
  /// bend 1).
  std::array<BoundTerm, 3> clearance_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Seen from inside: its six faces (sol/clearance.hpp, bend 1).
  std::array<InsideTerm, 6> inside_terms(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The bound's gradient by central differences (kernel::kNormalStep along E1, E2, E3).
  glm::dvec3 normal(const glm::dvec3& q) const;
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Box seen_from(const glm::dvec3& p) const;
  /// A coordinate box that holds every point where distance(q) <= 0
  /// (sol/coordinate_box.hpp; infinite where the object is unbounded).
  CoordinateBox coordinate_box() const;
  KernelShape kernel_shape() const;
  Box into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  ImageAnchor image_anchor() const;
  Box half_turned() const;
  bool same_set(const Box& other) const;
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit("centre", center);
    visit("half size", half_size);
  }
  bool operator==(const Box&) const = default;
};

}  // namespace sol
