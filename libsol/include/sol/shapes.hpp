// Shapes seen from outside, in the R³ model: meshes of geodesic spheres
// (docs/shapes.md).
//
// The geodesic sphere S(c, r) = {p : d(c, p) = r}. A geodesic from the
// origin with direction v minimises exactly up to its z-period T(v)
// (Coiculescu–Schwartz; ClosedFormGeodesic::period), and the least period
// over all directions is √2π, on the straight lines (1, ±1, 0)/√2 (their
// first conjugate point; sol/spreading.hpp). So for r < √2π no geodesic
// of length r from c is past its cut point: S(c, r) = c · exp(r S²), the
// exponential map is an embedding of the sphere of radius r, and a mesh of
// the direction sphere maps to a mesh of S(c, r) whose vertices lie on it
// exactly (to the closed form's rounding). Beyond √2π the sphere has
// creases where the cut locus meets it (not yet built: such radii throw
// sol::NotImplemented).
#pragma once

#include <array>
#include <vector>

#include <glm/vec3.hpp>

namespace sol {

/// A triangle mesh in Sol coordinates: outward-oriented triangles
/// (counter-clockwise seen from outside), closed.
struct Mesh {
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// The least radius at which a geodesic sphere meets the cut locus of its
/// centre: √2π, the period of the straight lines (1, ±1, 0)/√2.
inline constexpr double kSmoothSphereRadius = 4.44288293815836624702;

/// The geodesic sphere S(center, radius): the octahedron's faces divided
/// into subdivisions² triangles each, projected to the unit sphere of
/// directions (frame components at the centre) and mapped by
/// center · exp(radius v). The direction mesh is symmetric under every
/// permutation and sign change of (a, b, c), so the sphere's mesh maps to
/// itself under Sol's isometries fixing the centre ((x, y, z) → (±x, ±y, z),
/// (±y, ±x, −z) about it). 8 subdivisions² triangles, 4 subdivisions² + 2
/// vertices. Throws InvalidArgument for a non-finite centre, a radius not in
/// (0, kSmoothSphereRadius) (NotImplemented beyond it: creases) or
/// subdivisions outside [1, 512].
Mesh geodesic_sphere(const glm::dvec3& center, double radius, int subdivisions);

}  // namespace sol
