// Parallel transport: orthogonality, Q u(0) = u(t), composition, and an
// independent 50-digit reference written with the Christoffel symbols.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_access.hpp>
#include <glm/matrix.hpp>
#include <sol/sol.hpp>

#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"
#include "support/sweep.hpp"

namespace {

using glm::dmat3;
using glm::dvec3;

double max_abs(const dmat3& m) {
  double r = 0;
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 3; ++i) r = std::max(r, std::abs(m[c][i]));
  return r;
}

TEST(Transport, IsOrthogonalAndCarriesTheTangent) {
  std::vector<dvec3> dirs = sol::test::random_directions(300, 21);
  for (const dvec3& d : sol::test::stiff_directions()) dirs.push_back(d);
  double worst_orth = 0, worst_tangent = 0;
  for (const dvec3& d : dirs) {
    for (double t : {-7.0, 3.0, 50.0}) {
      const sol::GeodesicState s{{1.0, -2.0, 0.5}, d};
      const dmat3 q = sol::transport(s, t);
      worst_orth = std::max(worst_orth, max_abs(glm::transpose(q) * q - dmat3(1.0)));
      worst_tangent = std::max(worst_tangent, glm::length(q * d - sol::flow(s, t).direction));
      EXPECT_GT(glm::determinant(q), 0.0);  // a rotation: transport preserves orientation
    }
  }
  std::printf("transport (Auto: closed-form u(t), Dormand–Prince 1e-12, t<=50): |Q^T Q - I| <= %.2e, |Q u0 - u(t)| <= %.2e\n", worst_orth, worst_tangent);
  EXPECT_LT(worst_orth, 1e-9);
  EXPECT_LT(worst_tangent, 1e-9);
}

TEST(Transport, TwoSegmentsCompose) {
  const std::vector<dvec3> dirs = sol::test::random_directions(100, 22);
  for (const dvec3& d : dirs) {
    const sol::GeodesicState s{{0.3, 0.1, -0.2}, d};
    const sol::GeodesicState mid = sol::flow(s, 2.5);
    const dmat3 whole = sol::transport(s, 6.0);
    const dmat3 parts = sol::transport(mid, 3.5) * sol::transport(s, 2.5);
    EXPECT_LT(max_abs(whole - parts), 1e-9);
  }
}

TEST(Transport, MatchesChristoffelReference) {
  std::vector<dvec3> dirs = sol::test::random_directions(5, 23);
  const std::vector<dvec3> stiff = sol::test::stiff_directions();
  for (std::size_t i = 1; i < stiff.size(); i += 5) dirs.push_back(stiff[i]);
  double worst = 0;
  for (const dvec3& d : sol::test::sweep(dirs, 3)) {
    sol::test::ReferenceGeodesic<> reference(d, /*with_transport=*/true);
    for (double t : {1.0, 10.0, 30.0}) {
      const dmat3 expected = reference.at(t).transport;
      const dmat3 q = sol::transport({dvec3(0.0), d}, t);
      worst = std::max(worst, max_abs(q - expected));
    }
  }
  std::printf("transport against the 50-digit reference (t<=30): max |Q - Q_ref| = %.2e\n", worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(Transport, ExactCases) {
  // Along the vertical line u = (0,0,1), so B = 0 and Q = I.
  const dmat3 vertical = sol::transport({dvec3(0.0), {0, 0, 1}}, 12.0);
  EXPECT_LT(max_abs(vertical - dmat3(1.0)), 1e-14);
  // Along the straight line u = (s, s, 0) (s = 1/√2) B is constant. For
  // w(0) = e_z, with p = (w1 - w2)/√2: p' = w3 and w3' = -p, so e_z turns
  // towards n = (1,-1,0)/√2 at unit rate, and u itself is fixed.
  const double s = 1.0 / std::sqrt(2.0), t = 2.0;
  const dmat3 q = sol::transport({dvec3(0.0), {s, s, 0}}, t);
  const dvec3 expected_ez = std::cos(t) * dvec3(0, 0, 1) + std::sin(t) * dvec3(s, -s, 0);
  EXPECT_LT(glm::length(glm::column(q, 2) - expected_ez), 1e-12);
  EXPECT_LT(glm::length(q * dvec3(s, s, 0) - dvec3(s, s, 0)), 1e-12);
}

}  // namespace
