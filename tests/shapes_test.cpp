// sol::geodesic_sphere: vertices at the radius (exact distances), a closed
// outward-oriented 2-manifold, Sol's symmetries, left invariance, the
// Euclidean limit.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
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
  for (double r : {0.5, 2.0, 4.0, 4.4}) {
    const sol::Mesh m = sol::geodesic_sphere(center, r, 6);
    double worst = 0.0;
    for (const dvec3& p : m.vertices) worst = std::max(worst, std::abs(sol::distance(center, p) - r));
    // The closed form's vertices against the solver's distance: both ~1e-12
    // relative; 1e-9 leaves room for the solver's acceptance (1e-12 max(1, t)).
    EXPECT_LT(worst, 1e-9 * std::max(1.0, r)) << r;
  }
}

TEST(GeodesicSphere, ClosedOutwardTwoManifold) {
  for (const int n : {1, 3, 8}) {
    const sol::Mesh m = sol::geodesic_sphere(dvec3(0.1, 0.2, -0.3), 3.0, n);
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(4 * n * n + 2));
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(8 * n * n));
    // Every edge in exactly two triangles, once each way (consistent orientation).
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
    const long long euler = static_cast<long long>(m.vertices.size()) - static_cast<long long>(edges.size()) +
                            static_cast<long long>(m.triangles.size());
    EXPECT_EQ(euler, 2);
    EXPECT_GT(signed_volume(m, dvec3(0.1, 0.2, -0.3)), 0.0);  // outward
    // No degenerate triangles.
    for (const auto& t : m.triangles) {
      EXPECT_GT(glm::length(glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]])), 1e-12);
    }
  }
}

// Sol's isometries fixing the origin map the sphere's mesh onto itself:
// (x, y, z) → (−x, y, z), (x, −y, z), (y, x, −z), vertex to vertex.
TEST(GeodesicSphere, SymmetricUnderSolsIsometries) {
  const sol::Mesh m = sol::geodesic_sphere(dvec3(0.0), 3.5, 5);
  auto present = [&](const dvec3& q) {
    return std::any_of(m.vertices.begin(), m.vertices.end(), [&](const dvec3& p) { return glm::length(p - q) < 1e-9 * (1.0 + glm::length(q)); });
  };
  for (const dvec3& p : m.vertices) {
    EXPECT_TRUE(present({-p.x, p.y, p.z}));
    EXPECT_TRUE(present({p.x, -p.y, p.z}));
    EXPECT_TRUE(present({p.y, p.x, -p.z}));
  }
}

// Left invariance: the sphere about c is c times the sphere about the origin.
TEST(GeodesicSphere, SphereAboutCIsCTimesTheSphereAboutTheOrigin) {
  const dvec3 c(1.5, -2.0, 0.7);
  const sol::Mesh at_c = sol::geodesic_sphere(c, 2.5, 4), at_0 = sol::geodesic_sphere(dvec3(0.0), 2.5, 4);
  ASSERT_EQ(at_c.vertices.size(), at_0.vertices.size());
  for (std::size_t i = 0; i < at_c.vertices.size(); ++i) {
    EXPECT_LT(glm::length(at_c.vertices[i] - sol::multiply(c, at_0.vertices[i])), 1e-12);
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
  EXPECT_THROW(sol::geodesic_sphere(dvec3(0.0), 4.5, 4), sol::NotImplemented);
  EXPECT_EQ(sol::kSmoothSphereRadius, std::sqrt(2.0) * std::numbers::pi);
}

}  // namespace
