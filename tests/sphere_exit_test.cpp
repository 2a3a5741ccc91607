// Where a ray from a small geodesic sphere's inner wall leaves it
// (detail::sphere_exit, the CPU renderer's exit search), checked against the
// general distance solver and the sphere's exact normal, not against itself.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sol/closed_form.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/group.hpp"
#include "sphere_exit.hpp"  // libsol/src

namespace {

glm::dvec3 unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  for (;;) {
    const glm::dvec3 v(n(rng), n(rng), n(rng));
    if (glm::length(v) > 1e-3) return glm::normalize(v);
  }
}

// For spheres of radius 0.3, 1 and 1.45 about random centres, rays from a
// point of the sphere into it at every angle (the hit band's level r − 1e-5,
// as the renderer's search: sphere_exit aims at it): the exit lies at
// distance `level` from the centre (sol::distance, to 1e-9), heads out (the
// exact normal sdf_ball_exact_gradient against the ray's tangent, which
// sphere_exit's normal equals to 1e-8), and no point of the ray before it is
// outside (the first crossing). Every ray but grazing ones is solved.
TEST(SphereExit, IsWhereTheDistanceFromTheCentreFirstReachesTheLevel) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int solved = 0, rays = 0;
  double worst_level = 0.0, worst_normal = 0.0;
  for (const double r : {0.3, 1.0, 1.45}) {
    for (int k = 0; k < 60; ++k) {
      const glm::dvec3 centre(4.0 * u(rng) - 2.0, 4.0 * u(rng) - 2.0, 2.0 * u(rng) - 1.0);
      // A point h of the sphere and its outward normal there.
      const sol::ClosedFormGeodesic<double>::State radial = sol::ClosedFormGeodesic<double>(unit(rng)).at(r);
      const glm::dvec3 h = sol::multiply(centre, radial.position), outward = radial.direction;
      // A direction into the sphere: cos θ against the inward normal in (0.02, 1).
      glm::dvec3 d = unit(rng);
      d -= glm::dot(d, outward) * outward;
      d = glm::normalize(d);
      const double c = 0.02 + 0.98 * u(rng);
      d = glm::normalize(-c * outward + std::sqrt(1.0 - c * c) * d);
      const double level = r - 1e-5;
      const sol::ClosedFormGeodesic<double> ray(d);
      ++rays;
      const auto exit = sol::detail::sphere_exit(centre, level, h, ray, 2.0 * r * c, 10.0);
      if (!exit) continue;
      ++solved;
      const glm::dvec3 q = sol::multiply(h, ray.at(exit->s).position);
      worst_level = std::max(worst_level, std::abs(sol::distance(centre, q) - level));
      const glm::dvec3 normal = sol::sdf_ball_exact_gradient(q, centre);
      worst_normal = std::max(worst_normal, glm::length(normal - exit->outward));
      EXPECT_GT(glm::dot(normal, ray.at(exit->s).direction), 0.0) << "heads out";
      EXPECT_LT(glm::length(exit->direction - ray.at(exit->s).direction), 1e-12);
      // The first crossing: inside from just past the start up to it.
      for (int i = 1; i < 16; ++i) {
        const double s = exit->s * (0.05 + 0.9 * i / 16.0);
        EXPECT_LT(sol::distance(centre, sol::multiply(h, ray.at(s).position)), level) << "r " << r << " at " << s;
      }
    }
  }
  std::printf("sphere exits: %d of %d rays solved; worst |distance - level| %.2e, normal %.2e\n", solved, rays,
              worst_level, worst_normal);
  EXPECT_LT(worst_level, 1e-9);
  EXPECT_LT(worst_normal, 1e-8);
  EXPECT_GE(solved, rays * 95 / 100);
}

// A ray that leaves no sphere within the limit, or a start past it, gets
// no exit: nothing rather than a wrong crossing.
TEST(SphereExit, NoneBeyondTheLimit) {
  const glm::dvec3 centre(0.3, -0.2, 0.1);
  const sol::ClosedFormGeodesic<double>::State radial = sol::ClosedFormGeodesic<double>(glm::dvec3(1.0, 0.0, 0.0)).at(1.0);
  const glm::dvec3 h = sol::multiply(centre, radial.position);
  const sol::ClosedFormGeodesic<double> ray(-radial.direction);  // straight through the centre
  const auto full = sol::detail::sphere_exit(centre, 1.0 - 1e-5, h, ray, 2.0, 10.0);
  ASSERT_TRUE(full.has_value());
  EXPECT_NEAR(full->s, 2.0 - 1e-5, 1e-9);  // a diameter: through the centre, r − 1e-5 beyond it
  EXPECT_FALSE(sol::detail::sphere_exit(centre, 1.0 - 1e-5, h, ray, 2.0, 1.5).has_value());
}

}  // namespace
