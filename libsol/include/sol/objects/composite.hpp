// Composite solids: the union, intersection or difference of two solids
// (sol/objects/kind.hpp says what a kind provides). Source:
// libsol/src/objects/composite.cpp.
#pragma once

#include <memory>
#include <optional>

#include "sol/objects/kind.hpp"

namespace sol {

/// The two parts of a composite (defined with sol::Shape, which they are).
struct CompositeParts;

/// How a composite combines its parts A and B.
enum class CompositeOp {
  Union = kernel::kCompositeUnion,                ///< A ∪ B: min(d_A, d_B)
  Intersection = kernel::kCompositeIntersection,  ///< A ∩ B: max(d_A, d_B)
  Difference = kernel::kCompositeDifference,      ///< A \ B: max(d_A, −d_B)
};
/// The scene file's "type" of a composite: "union", "intersection", "difference".
std::string_view to_string(CompositeOp op);
/// The operation a scene file's "type" names; none for any other type.
std::optional<CompositeOp> composite_op_named(std::string_view name);

/// The union, intersection or difference of two solids (balls, tubes,
/// boxes or composites). Every solid's distance is 1-Lipschitz with the
/// solid its sublevel set {d <= 0} (a lower bound outside, the depth's
/// lower bound inside), and minima, maxima and negations of 1-Lipschitz
/// functions are 1-Lipschitz with the set's union, intersection and
/// complement as sublevel sets: so the composite's distance, the min or
/// max of its parts' (−d_B for the part taken away), is again a step the
/// march may take on either side, and zero exactly on the composite's
/// boundary (on an exact ball's own sphere where that part is exact). The
/// normal, pattern and clearances are those of the part whose term is the
/// distance at the point (the active part; B's normal turned for a
/// difference). In a quotient: intersections and differences (which lie
/// inside their first part, whose images they follow).
struct Composite {
  static constexpr std::string_view kName = "composite";
  static constexpr bool kSolid = true;
  CompositeOp op = CompositeOp::Union;
  /// Never null (a default composite is the union of two default balls).
  std::shared_ptr<const CompositeParts> parts;

  Composite();
  Composite(CompositeOp op, const struct CompositeParts& parts);

  /// The scene file's "type": to_string(op).
  std::string_view name() const { return to_string(op); }
  double distance(const glm::dvec3& q) const;
  /// How far the geodesic from q goes along u (and back along −u) before
  /// it can reach the composite, q outside it: a union's least part's, an
  /// intersection's largest over the parts q is outside of, a difference's
  /// largest of A's (q outside A) and of the inside clearances of B (q
  /// inside B); each at least the distance.
  Clearances clearances(const glm::dvec3& q, const glm::dvec3& u) const;
  /// Seen from inside (distance < 0): how far before the ray can leave
  /// it, and the rate of the active part's nearest face.
  InsideClearances inside_clearances(const glm::dvec3& q, const glm::dvec3& u) const;
  /// The active part's normal (B's turned in a difference): the gradient
  /// of the distance, outward.
  glm::dvec3 normal(const glm::dvec3& q) const;
  /// The active part's pattern coordinates (each part's own).
  glm::dvec2 pattern_uv(const glm::dvec3& q) const;
  Composite seen_from(const glm::dvec3& p) const;
  /// A union's hull of its parts' boxes, an intersection's overlap, a difference's A's.
  CoordinateBox coordinate_box() const;
  /// kernel::kObjectComposite with geometry (0, the number of parts of
  /// its chain, 0, 0): the kernel's host puts the chain in the parts'
  /// buffer and its first part's index in x.
  KernelShape kernel_shape() const;
  Composite into_domain(const Lattice& lattice) const;
  double least_distance_over_domain(const Lattice& lattice) const;
  ImageAnchor image_anchor() const;
  Composite half_turned() const;
  bool same_set(const Composite& other) const;
  /// Its parts' fields, named "a: ..." and "b: ..." (nested composites'
  /// "a: b: ..."); an edit replaces the shared parts by an edited copy, so
  /// that another composite holding them is not changed
  /// (visit_composite_fields, sol/objects.hpp).
  template <class Visitor>
  void visit_fields(Visitor&& visit) {
    visit_composite_fields(*this, visit);
  }
  bool operator==(const Composite& other) const;
};

}  // namespace sol
