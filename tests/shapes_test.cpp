// sol::geodesic_sphere: vertices at the radius (exact distances), a closed
// outward-oriented 2-manifold, Sol's symmetries, left invariance, the
// Euclidean limit; beyond √2π its creases on the cut locus. sol::cut_time,
// sol::cut_locus_curves against the connection solver's minimisers,
// sol::geodesic_polylines against the integrated flow. (No self-
// intersection: tests/shapes_mesh_test.cpp, with CGAL.)
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using glm::dvec3;

// The signed volume the mesh encloses in coordinates (divergence theorem):
// positive when the triangles face outwards.
double signed_volume(const sol::Mesh& m, const dvec3& center) {
  double v = 0.0;
  for (const auto& t : m.triangles) {
    const dvec3 a = m.vertices[t[0]] - center, b = m.vertices[t[1]] - center, c = m.vertices[t[2]] - center;
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

TEST(GeodesicSphere, VerticesLieAtTheRadius) {
  const dvec3 center(0.3, -0.4, 0.2);
  for (double r : {0.5, 2.0, 4.0, 4.4, 4.5, 5.0, 6.0}) {
    const sol::Mesh m = sol::geodesic_sphere(center, r, r > sol::kCoarseSphereRadius ? 16 : 6);
    double worst = 0.0;
    for (const dvec3& p : m.vertices) worst = std::max(worst, std::abs(sol::distance(center, p) - r));
    // The closed form's vertices against the solver's distance: both ~1e-12
    // relative; 1e-9 leaves room for the solver's acceptance (1e-12 max(1, t)).
    EXPECT_LT(worst, 1e-9 * std::max(1.0, r)) << r;
  }
}

// Every edge in exactly two triangles, once each way (consistent
// orientation); the Euler characteristic V - E + F.
long long check_closed_oriented(const sol::Mesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  std::set<std::pair<int, int>> edges;
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << "edge " << e.first << "-" << e.second << " has one face";
    edges.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
  }
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.triangles) {
    for (int i : t) used[static_cast<std::size_t>(i)] = 1;
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](char u) { return u != 0; })) << "a vertex in no triangle";
  return static_cast<long long>(m.vertices.size()) - static_cast<long long>(edges.size()) +
         static_cast<long long>(m.triangles.size());
}

TEST(GeodesicSphere, ClosedOutwardTwoManifold) {
  const dvec3 c(0.1, 0.2, -0.3);
  for (const int n : {1, 3, 8}) {
    const sol::Mesh m = sol::geodesic_sphere(c, 3.0, n);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(4 * n * n + 2));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(8 * n * n));
    EXPECT_EQ(check_closed_oriented(m), 2);
    EXPECT_GT(signed_volume(m, c), 0.0);  // outward
    // No degenerate triangles.
    for (const auto& t : m.triangles) {
      EXPECT_GT(glm::length(glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]])), 1e-12);
    }
  }
  // Beyond √2π: clipped at the cut locus and zipped, still a closed
  // outward sphere without degenerate triangles, at radii where the discs
  // cut away are smaller than a triangle (4.45) up to the largest.
  for (const double r : {4.45, 4.5, 5.0, 5.5, 6.0}) {
    for (const int n : {3, 8, 16, 24}) {
      if (r > sol::kCoarseSphereRadius && n < sol::kMinCoarseSubdivisions) continue;
      const sol::Mesh m = sol::geodesic_sphere(c, r, n);
      EXPECT_EQ(check_closed_oriented(m), 2) << r << " " << n;
      EXPECT_GT(signed_volume(m, c), 0.0) << r << " " << n;
      for (const auto& t : m.triangles) {
        ASSERT_GT(glm::length(glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]])), 1e-12)
            << r << " " << n;
      }
    }
  }
}

// The creases: beyond √2π the mesh has vertices on the cut locus of the
// centre, in the horizontal plane through it (a whole z-period returns z),
// each reached by two minimising geodesics of length r, mirrors (a, b, ±c)
// of each other, by the connection solver (an independent Newton search).
TEST(GeodesicSphere, CreasesLieOnTheCutLocus) {
  const dvec3 c(0.4, -0.2, 0.3);
  for (const double r : {4.6, 5.2}) {
    const sol::Mesh m = sol::geodesic_sphere(c, r, 12);
    int creased = 0;
    for (const dvec3& p : m.vertices) {
      if (std::abs(p.z - c.z) > 1e-9) continue;
      ++creased;
      const std::vector<sol::Connection> ways = sol::minimising_geodesics(c, p);
      ASSERT_EQ(ways.size(), 2u) << p.x << ", " << p.y;
      for (const sol::Connection& w : ways) EXPECT_NEAR(w.length, r, 1e-8);
      EXPECT_NEAR(ways[0].direction.x, ways[1].direction.x, 1e-6);
      EXPECT_NEAR(ways[0].direction.y, ways[1].direction.y, 1e-6);
      EXPECT_NEAR(ways[0].direction.z, -ways[1].direction.z, 1e-6);
    }
    // Four arcs, each with several vertices.
    EXPECT_GE(creased, 4 * 4) << r;
  }
  // Below √2π nothing lies in that plane but where the sphere crosses it
  // smoothly, with one minimiser.
  const sol::Mesh smooth = sol::geodesic_sphere(c, 4.0, 12);
  for (const dvec3& p : smooth.vertices) {
    if (std::abs(p.z - c.z) < 1e-9) {
      EXPECT_EQ(sol::minimising_geodesics(c, p).size(), 1u);
    }
  }
}

// Sol's isometries fixing the origin map the sphere's mesh onto itself:
// (x, y, z) → (−x, y, z), (x, −y, z), (y, x, −z), vertex to vertex.
TEST(GeodesicSphere, SymmetricUnderSolsIsometries) {
  for (const double r : {3.5, 5.0}) {
    const sol::Mesh m = sol::geodesic_sphere(dvec3(0.0), r, 5);
    auto present = [&](const dvec3& q) {
      return std::any_of(m.vertices.begin(), m.vertices.end(),
                         [&](const dvec3& p) { return glm::length(p - q) < 1e-9 * (1.0 + glm::length(q)); });
    };
    for (const dvec3& p : m.vertices) {
      EXPECT_TRUE(present({-p.x, p.y, p.z})) << r;
      EXPECT_TRUE(present({p.x, -p.y, p.z})) << r;
      EXPECT_TRUE(present({p.y, p.x, -p.z})) << r;
    }
  }
}

// Left invariance: the sphere about c is c times the sphere about the origin.
TEST(GeodesicSphere, SphereAboutCIsCTimesTheSphereAboutTheOrigin) {
  const dvec3 c(1.5, -2.0, 0.7);
  for (const double r : {2.5, 5.0}) {
    const sol::Mesh at_c = sol::geodesic_sphere(c, r, 4), at_0 = sol::geodesic_sphere(dvec3(0.0), r, 4);
    ASSERT_EQ(at_c.vertices.size(), at_0.vertices.size());
    ASSERT_EQ(at_c.triangles, at_0.triangles);
    for (std::size_t i = 0; i < at_c.vertices.size(); ++i) {
      EXPECT_LT(glm::length(at_c.vertices[i] - sol::multiply(c, at_0.vertices[i])), 1e-11 * (1.0 + glm::length(at_c.vertices[i])));
    }
  }
}

// Small spheres: in frame coordinates at the centre the sphere is the
// Euclidean one up to O(r²) (the coordinates bend at second order).
TEST(GeodesicSphere, SmallSpheresAreEuclidean) {
  for (double r : {1e-2, 1e-3}) {
    const sol::Mesh m = sol::geodesic_sphere(dvec3(0.0), r, 4);
    for (const dvec3& p : m.vertices) EXPECT_NEAR(glm::length(p), r, r * r) << r;
  }
}

TEST(GeodesicSphere, BadInputIsRefused) {
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), 0.0, 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), -1.0, 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), std::nan(""), 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(std::nan(""), 0, 0), 1.0, 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), 1.0, 0), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), 6.01, 16), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), 5.5, 8), sol::InvalidArgument);  // too coarse there
  EXPECT_NO_THROW(sol::geodesic_sphere(dvec3(0.0), 5.5, 16));
  EXPECT_EQ(sol::kSmoothSphereRadius, std::sqrt(2.0) * std::numbers::pi);
  EXPECT_THROW(sol::cut_time(dvec3(0.0)), sol::InvalidArgument);
  EXPECT_THROW(sol::cut_time(dvec3(std::nan(""), 1, 0)), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_polylines(dvec3(0.0), {dvec3(0.0)}, 1.0, 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_polylines(dvec3(0.0), {dvec3(1, 0, 0)}, 0.0, 4), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesic_polylines(dvec3(0.0), {dvec3(1, 0, 0)}, 1.0, 0), sol::InvalidArgument);
  EXPECT_THROW(sol::cut_locus_curves(dvec3(0.0), {4.4}, 8), sol::InvalidArgument);  // no cut locus within 4.4
  EXPECT_THROW(sol::cut_locus_curves(dvec3(0.0), {5.0}, 1), sol::InvalidArgument);
}

// The cut time is where a geodesic and its mirror (a, b, -c) meet again
// (both integrated by Dormand–Prince, not the closed form): at T their ends
// coincide, before it they differ; the straight lines' limit √2π; the
// planes' and the vertical's geodesics never come back (∞); the symmetries.
TEST(CutTime, IsWhereAGeodesicMeetsItsMirror) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  int tested = 0;
  while (tested < 40) {
    dvec3 v = glm::normalize(dvec3(g(rng), g(rng), g(rng)));
    const double T = sol::cut_time(v);
    if (!(T < 12.0)) continue;
    ++tested;
    const dvec3 mirror(v.x, v.y, -v.z);
    const dvec3 p = sol::flow({dvec3(0.0), v}, T, sol::Method::DormandPrince).position;
    const dvec3 q = sol::flow({dvec3(0.0), mirror}, T, sol::Method::DormandPrince).position;
    EXPECT_LT(glm::length(p - q), 1e-7 * (1.0 + glm::length(p))) << v.x << " " << v.y << " " << v.z;
    EXPECT_NEAR(p.z, 0.0, 1e-7);
    if (std::abs(v.z) > 0.05) {
      const dvec3 p2 = sol::flow({dvec3(0.0), v}, 0.9 * T, sol::Method::DormandPrince).position;
      const dvec3 q2 = sol::flow({dvec3(0.0), mirror}, 0.9 * T, sol::Method::DormandPrince).position;
      EXPECT_GT(glm::length(p2 - q2), 1e-3);
    }
    EXPECT_EQ(T, sol::cut_time({-v.x, v.y, v.z}));
    EXPECT_EQ(T, sol::cut_time({v.x, -v.y, -v.z}));
    EXPECT_EQ(T, sol::cut_time({v.y, v.x, v.z}));
  }
  EXPECT_EQ(sol::cut_time(dvec3(1.0, 1.0, 0.0)), sol::kSmoothSphereRadius);
  EXPECT_NEAR(sol::cut_time(dvec3(1.0, 1.0, 1e-6)), sol::kSmoothSphereRadius, 1e-9);
  EXPECT_TRUE(std::isinf(sol::cut_time(dvec3(1.0, 0.0, 0.3))));
  EXPECT_TRUE(std::isinf(sol::cut_time(dvec3(0.0, 0.0, 1.0))));
  // The least cut time over a grid of directions is the straight lines'.
  double least = 1e300;
  for (int i = 0; i <= 60; ++i) {
    for (int j = 0; j <= 60; ++j) {
      const double th = std::numbers::pi * i / 60.0, ph = std::numbers::pi / 2.0 * j / 60.0;
      least = std::min(least, sol::cut_time({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)}));
    }
  }
  EXPECT_GE(least, sol::kSmoothSphereRadius * (1.0 - 1e-12));
}

// The cut locus curves: four arcs per radius in the plane through the
// centre, every point with two minimising geodesics of length r (the
// connection solver), the arcs' ends on the equator of directions.
TEST(CutLocus, PointsHaveTwoMinimisersOfEqualLength) {
  const dvec3 c(-0.3, 0.5, 0.2);
  const std::vector<double> radii = {4.6, 5.5};
  const auto curves = sol::cut_locus_curves(c, radii, 9);
  ASSERT_EQ(curves.size(), 8u);
  for (std::size_t k = 0; k < curves.size(); ++k) {
    ASSERT_EQ(curves[k].size(), 9u);
    const double r = radii[k / 4];
    for (const dvec3& p : curves[k]) {
      EXPECT_NEAR(p.z, c.z, 1e-9);
      const std::vector<sol::Connection> ways = sol::minimising_geodesics(c, p);
      ASSERT_FALSE(ways.empty());
      EXPECT_NEAR(ways[0].length, r, 1e-8);
      // At the arc's ends (c = 0) the two directions coincide.
      if (&p != &curves[k].front() && &p != &curves[k].back()) {
        ASSERT_EQ(ways.size(), 2u) << k;
        EXPECT_NEAR(ways[1].length, r, 1e-8);
      }
    }
  }
  // The arcs for a larger radius reach farther from the centre.
  EXPECT_GT(glm::length(curves[4][4] - c), glm::length(curves[0][4] - c));
}

// Polylines are the flow's points, evenly spaced in arc length: against
// Dormand–Prince integration of the geodesic equations.
TEST(GeodesicPolylines, MatchTheIntegratedFlow) {
  const dvec3 from(0.2, -0.1, 0.4);
  const std::vector<dvec3> dirs = {{1, 0, 0}, {0.3, 0.5, 0.8}, {-1, 2, -0.5}, {0, 0, -1}};
  const auto lines = sol::geodesic_polylines(from, dirs, 3.0, 6);
  ASSERT_EQ(lines.size(), dirs.size());
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    ASSERT_EQ(lines[k].size(), 7u);
    EXPECT_EQ(lines[k][0], from);
    for (int i = 0; i <= 6; ++i) {
      const dvec3 ref = sol::flow({from, glm::normalize(dirs[k])}, 0.5 * i, sol::Method::DormandPrince).position;
      EXPECT_LT(glm::length(lines[k][static_cast<std::size_t>(i)] - ref), 1e-8) << k << " " << i;
    }
  }
}

// Calls whose points exceed the bounds are refused before any work, with
// the figure; one just inside is made.
TEST(Shapes, WorkBeyondThePointBoundsIsRefused) {
  const std::vector<dvec3> many(100000, dvec3(1, 0, 0));
  try {
    (void)sol::geodesic_polylines(dvec3(0.0), many, 3.0, 100000);
    ADD_FAILURE() << "10^10 points accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("100000 directions x 100001 points = 1e+10 points"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sol::geodesic_polylines(dvec3(0.0), std::vector<dvec3>(2, dvec3(1, 0, 0)), 3.0, 1000000).size(), 2u);
  try {
    (void)sol::cut_locus_curves(dvec3(0.0), std::vector<double>(1000, 5.0), 64);
    ADD_FAILURE() << "256000 cut locus points accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("1000 radii x 4 arcs x 64 samples = 2.56e+05 points"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sol::cut_locus_curves(dvec3(0.0), std::vector<double>(2, 5.0), 16).size(), 8u);
}

// vertex_thickness against shapes of known thickness: a box 10 x 2 x 6
// with faces of 4 x 4 squares (a vertex inside a big face has that face's
// normal, so the ray crosses the 2 exactly; a corner's diagonal ray meets
// a face at 2 sqrt(3)); a UV sphere of radius 1.5, every vertex's ray
// through the centre to the far side: 3 less the chord's sag, at most
// r (1 - cos(pi / 24)) = 0.013 here.
sol::Mesh box_mesh(const dvec3& size, int n) {
  sol::Mesh m;
  // Each face: an (n + 1)^2 grid of vertices, 2 n^2 triangles, outward (counter-clockwise seen from outside).
  auto face = [&](const dvec3& origin, const dvec3& u, const dvec3& v) {
    const int base = static_cast<int>(m.vertices.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) m.vertices.push_back(origin + u * (double(i) / n) + v * (double(j) / n));
    }
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({a, d, c});
      }
    }
  };
  const dvec3 x(size.x, 0, 0), y(0, size.y, 0), z(0, 0, size.z), o(0.0);
  face(o, y, x);          // z = 0, normal -z
  face(o + z, x, y);      // z = top, +z
  face(o, x, z);          // y = 0, -y
  face(o + y, z, x);      // y = top, +y
  face(o, z, y);          // x = 0, -x
  face(o + x, y, z);      // x = top, +x
  return m;
}

TEST(Shapes, VertexThicknessOfShapesOfKnownThickness) {
  const sol::Mesh box = box_mesh({10, 2, 6}, 4);
  // (The faces' grids share no vertices, so each vertex's normal is its own face's, corners included: every
  // vertex of a y face sees the other y face at 2, of an x face at 10 (beyond up_to: infinite), z faces at 6.)
  const std::vector<double> t = sol::vertex_thickness(box, 8.0);
  ASSERT_EQ(t.size(), box.vertices.size());
  int twos = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const dvec3 v = box.vertices[k];
    const bool y_face = k >= 2 * 25 && k < 4 * 25, z_face = k < 2 * 25;
    if (y_face) {
      EXPECT_NEAR(t[k], 2.0, 1e-12) << v.x << " " << v.y << " " << v.z;
      ++twos;
    } else if (z_face) {
      EXPECT_NEAR(t[k], 6.0, 1e-12);
    } else {
      EXPECT_TRUE(std::isinf(t[k])) << t[k];  // 10 across: beyond up_to
    }
  }
  EXPECT_EQ(twos, 50);
  // The sphere.
  sol::Mesh sphere;
  const int rings = 24, segments = 48;
  const double r = 1.5;
  sphere.vertices.push_back({0, 0, r});
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      sphere.vertices.push_back({r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
    }
  }
  sphere.vertices.push_back({0, 0, -r});
  const int south = static_cast<int>(sphere.vertices.size()) - 1;
  auto at = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    sphere.triangles.push_back({0, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      sphere.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      sphere.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
    sphere.triangles.push_back({south, at(rings - 1, j + 1), at(rings - 1, j)});
  }
  const std::vector<double> ts = sol::vertex_thickness(sphere, 4.0);
  for (std::size_t k = 0; k < ts.size(); ++k) EXPECT_NEAR(ts[k], 2.0 * r, 0.015) << k;
  // Nothing within a smaller reach: infinite.
  for (const double v : sol::vertex_thickness(sphere, 2.0)) EXPECT_TRUE(std::isinf(v));
  EXPECT_THROW(sol::vertex_thickness(sphere, 0.0), sol::InvalidArgument);
}

// The search through the hierarchy finds what trying every triangle finds,
// on a geodesic sphere past its creases (radius 5: triangles from long
// slivers to specks, the case a uniform grid made quadratic): every vertex's
// first non-incident triangle along its inward normal, brute force here
// (the ray-plane intersection solved by Cramer's rule, barycentric
// coordinates within 1e-9 as the library's). Progress is reported from 0 to 1.
TEST(Shapes, ThicknessSearchFindsWhatEveryTriangleFinds) {
  const sol::Mesh mesh = sol::geodesic_sphere(dvec3(0.0), 5.0, 12);
  std::vector<double> reported;
  const double reach = 3.0;
  const std::vector<double> got = sol::vertex_thickness(mesh, reach, [&](double f) { reported.push_back(f); });
  ASSERT_EQ(got.size(), mesh.vertices.size());
  std::vector<dvec3> normals(mesh.vertices.size(), dvec3(0.0));
  for (const auto& t : mesh.triangles) {
    const dvec3 a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    for (int k : t) normals[static_cast<std::size_t>(k)] += glm::cross(b - a, c - a);
  }
  int finite = 0;
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    const dvec3 o = mesh.vertices[k], d = -glm::normalize(normals[k]);
    double least = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles) {
      if (static_cast<std::size_t>(t[0]) == k || static_cast<std::size_t>(t[1]) == k || static_cast<std::size_t>(t[2]) == k) continue;
      const dvec3 a = mesh.vertices[t[0]], e1 = mesh.vertices[t[1]] - a, e2 = mesh.vertices[t[2]] - a, s = o - a;
      // o + t d = a + u e1 + v e2: [e1 e2 -d] (u, v, t) = s.
      const double det = glm::dot(e1, glm::cross(e2, -d));
      if (std::abs(det) < 1e-300) continue;
      const double u = glm::dot(s, glm::cross(e2, -d)) / det, v = glm::dot(e1, glm::cross(s, -d)) / det;
      const double h = glm::dot(e1, glm::cross(e2, s)) / det;
      if (u >= -1e-9 && v >= -1e-9 && u + v <= 1.0 + 1e-9 && h > 0.0) least = std::min(least, h);
    }
    if (least > reach) least = std::numeric_limits<double>::infinity();
    if (std::isinf(least)) {
      EXPECT_TRUE(std::isinf(got[k])) << k << ": " << got[k];
    } else {
      ++finite;
      EXPECT_NEAR(got[k], least, 1e-9 * (1.0 + least)) << k;
    }
  }
  EXPECT_GT(finite, 0);  // the creases' thin parts are within reach
  ASSERT_GE(reported.size(), 2u);
  EXPECT_EQ(reported.front(), 0.0);
  EXPECT_EQ(reported.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(reported.begin(), reported.end()));
}

}  // namespace
