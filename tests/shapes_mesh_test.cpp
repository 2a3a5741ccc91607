// No self-intersection: sol::geodesic_sphere's meshes checked by CGAL's
// Polygon Mesh Processing (exact predicates), an independent reference for
// what the closedness and orientation tests of shapes_test.cpp cannot see
// (two sheets crossing, as too coarse meshes near the cut locus do). A
// binary of its own: CGAL's headers are heavy and only this file needs them.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace pmp = CGAL::Polygon_mesh_processing;

SurfaceMesh to_cgal(const sol::Mesh& m) {
  SurfaceMesh out;
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const glm::dvec3& p : m.vertices) v.push_back(out.add_vertex(Kernel::Point_3(p.x, p.y, p.z)));
  for (const auto& t : m.triangles) {
    EXPECT_NE(out.add_face(v[t[0]], v[t[1]], v[t[2]]), SurfaceMesh::null_face()) << "not a manifold face";
  }
  return out;
}

// Radii up to 6 (the issue asks for up to 5): every 0.25 below the cut
// locus, every 0.05 from 4.45 (where the discs cut away are smaller than a
// triangle) on, at coarse and finer resolutions.
TEST(GeodesicSphereMesh, NeverCrossesItself) {
  std::vector<double> radii = {0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.25, 4.4};
  for (double r = 4.45; r <= 6.0 + 1e-9; r += 0.05) radii.push_back(r);
  for (const double r : radii) {
    for (const int n : {4, 8, 16, 24}) {
      if (r > sol::kCoarseSphereRadius && n < sol::kMinCoarseSubdivisions) continue;
      const SurfaceMesh mesh = to_cgal(sol::geodesic_sphere(glm::dvec3(0.3, -0.2, 0.1), r, n));
      ASSERT_TRUE(CGAL::is_closed(mesh)) << r << " " << n;
      std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> crossings;
      pmp::self_intersections(mesh, std::back_inserter(crossings));
      EXPECT_TRUE(crossings.empty()) << "radius " << r << ", " << n << " subdivisions: " << crossings.size()
                                     << " pairs of triangles cross";
      EXPECT_TRUE(pmp::is_outward_oriented(mesh)) << r << " " << n;
    }
  }
}

// The check can fail: one closed tetrahedron is clean; a second one
// through its faces makes triangles cross.
TEST(GeodesicSphereMesh, TheCheckSeesACrossing) {
  sol::Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> crossings;
  pmp::self_intersections(to_cgal(m), std::back_inserter(crossings));
  EXPECT_TRUE(crossings.empty());
  for (int i = 0; i < 4; ++i) m.vertices.push_back(m.vertices[static_cast<std::size_t>(i)] + glm::dvec3(0.3, 0.3, 0.3));
  for (int i = 0; i < 4; ++i) {
    const auto t = m.triangles[static_cast<std::size_t>(i)];
    m.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  }
  pmp::self_intersections(to_cgal(m), std::back_inserter(crossings));
  EXPECT_FALSE(crossings.empty());
}

}  // namespace
