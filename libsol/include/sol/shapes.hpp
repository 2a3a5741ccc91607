// Shapes seen from outside, in the R³ model: meshes of geodesic spheres
// (docs/shapes.md).
//
// The geodesic sphere S(c, r) = {p : d(c, p) = r}. A geodesic from the
// origin with direction v minimises exactly up to its z-period T(v), its cut
// time (Coiculescu–Schwartz; ClosedFormGeodesic::period), and the least
// period over all directions is √2π, on the straight lines (1, ±1, 0)/√2
// (their first conjugate point; sol/spreading.hpp). So for r < √2π no
// geodesic of length r from c is past its cut point: S(c, r) = c · exp(r S²),
// the exponential map is an embedding of the sphere of radius r, and a mesh
// of the direction sphere maps to a mesh of S(c, r) whose vertices lie on it
// exactly (to the closed form's rounding).
//
// From √2π on, the directions with T(v) < r (four discs, one around each
// straight direction) end inside the ball and are cut away; on the rim of
// each disc (T(v) = r) v and its mirror (a, b, −c) reach the same point of
// the plane z = c_z at the same length (a whole z-period shifts x and y by
// amounts that depend on a and b alone), a point of the cut locus of c with
// two minimising geodesics. The rim zipped to itself by the mirror is the
// sphere's crease: an arc of the cut locus in the plane through the centre.
#pragma once

#include <array>
#include <functional>
#include <cstddef>
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

/// The largest radius geodesic_sphere meshes: beyond it the directions
/// that still minimise become bands around the planes a = 0 and b = 0 too
/// thin for the octahedron's divisions.
inline constexpr double kMaxMeshedSphereRadius = 6.0;
/// Above this radius geodesic_sphere needs kMinCoarseSubdivisions: with
/// fewer, the thin bands of directions left make the mesh cross itself
/// (checked with CGAL from 4.45 to 6 in steps of 0.05: 4 subdivisions are
/// clean up to 5.35, 16 and more everywhere; tests/shapes_mesh_test.cpp).
inline constexpr double kCoarseSphereRadius = 5.3;
inline constexpr int kMinCoarseSubdivisions = 16;

/// The cut time of the geodesic from the origin with initial direction
/// `direction` (frame components, normalised here): its z-period
/// 4K(m)/λ, √2π for the straight lines (1, ±1, 0)/√2, infinite for the
/// geodesics in the planes x = 0, y = 0 and the vertical ones. Symmetric
/// under (a, b, c) → (±a, ±b, ±c), (b, a, c) bit for bit.
double cut_time(const glm::dvec3& direction);

/// The geodesic sphere S(center, radius): the octahedron's faces divided
/// into subdivisions² triangles each, projected to the unit sphere of
/// directions (frame components at the centre) and mapped by
/// center · exp(radius v). The direction mesh is symmetric under every
/// permutation and sign change of (a, b, c), so the sphere's mesh maps to
/// itself under Sol's isometries fixing the centre ((x, y, z) → (±x, ±y, z),
/// (±y, ±x, −z) about it). Below kSmoothSphereRadius: 8 subdivisions²
/// triangles, 4 subdivisions² + 2 vertices. From it on, the directions with
/// cut_time < radius are clipped away (the rim's points by bisection of
/// cut_time, vertices within a quarter edge of the rim moved onto it along
/// the great circle from the disc's centre, so no sliver remains) and the
/// rim is zipped to its mirror (a, b, −c): the creases, on the cut locus.
/// Closed, outward, symmetric as above in either case. Throws
/// InvalidArgument for a non-finite centre, a radius not in (0,
/// kMaxMeshedSphereRadius], subdivisions outside [1, 512] or below
/// kMinCoarseSubdivisions above kCoarseSphereRadius.
Mesh geodesic_sphere(const glm::dvec3& center, double radius, int subdivisions);


/// The most points geodesic_polylines makes in one call: directions ×
/// (segments + 1) up to 10⁷, 240 MB of points and about 6 s on one core.
inline constexpr double kMaxPolylinePoints = 1e7;
/// The most points cut_locus_curves makes in one call: radii × 4 arcs ×
/// samples up to 10⁵, each found by bisection (about 7 s on one core).
inline constexpr double kMaxCutLocusPoints = 1e5;

/// The bounds above, before any work: InvalidArgument naming `who` with the
/// figure ("N directions x S points = P points; at most 1e+07 in one
/// call") where a call would make more points. geodesic_polylines and
/// cut_locus_curves check with them; a caller that splits the work (the
/// Python module, between interrupts) checks the whole first.
void check_polyline_points(std::size_t directions, long long segments, const char* who);
void check_cut_locus_points(std::size_t radii, long long samples, const char* who);

/// Geodesics from `from` along each of `directions` (frame components,
/// normalised here) to arc length `length`, each as segments + 1 points
/// evenly spaced in arc length (sol::flow: the closed form). Throws
/// InvalidArgument for non-finite input, a zero direction, length <= 0,
/// segments outside [1, 10⁶] or more than kMaxPolylinePoints points in all;
/// OutOfRange where a point overflows double (as sol::flow).
std::vector<std::vector<glm::dvec3>> geodesic_polylines(const glm::dvec3& from, const std::vector<glm::dvec3>& directions,
                                                        double length, int segments);

/// The cut locus of `center` as curves: for each radius r in `radii`
/// (in (√2π, kMaxMeshedSphereRadius]) the four arcs where it meets the
/// sphere S(center, r), the creases of geodesic_sphere, each as `samples`
/// points: for θ from 0 to π the direction at angle θ around the straight
/// direction s = (±1, ±1, 0)/√2 (from (s_x, −s_y, 0) towards (0, 0, 1)) on
/// the rim cut_time = r, mapped by exp. Every point has two minimising
/// geodesics from the centre, of length r (the direction and its mirror).
/// The arcs lie in the horizontal plane through the centre; radii fill the
/// cut locus out to the largest. Throws InvalidArgument for bad input and
/// for more than kMaxCutLocusPoints points in all.
std::vector<std::vector<glm::dvec3>> cut_locus_curves(const glm::dvec3& center, const std::vector<double>& radii,
                                                      int samples);

/// How thick a closed mesh is at each vertex, for printing: the distance
/// from the vertex along its inward normal (the area-weighted mean of its
/// triangles' normals, reversed) to the first triangle not incident to it,
/// or +infinity where none is within `up_to` (only thin parts matter). In
/// the mesh's units. The rays search a bounding volume hierarchy over the
/// triangles, so the work grows as n log n with the mesh's size, whatever
/// its triangles' sizes. `progress`, when given, is called now and then
/// with the finished fraction (0 first, 1 last). Throws InvalidArgument for
/// `up_to` not finite and > 0 or an index outside the vertices.
std::vector<double> vertex_thickness(const Mesh& mesh, double up_to, const std::function<void(double)>& progress = {});

}  // namespace sol
