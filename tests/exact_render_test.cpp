// Exact balls and exact point lights in the CPU renderer: the drawn surface
// is the geodesic sphere, the light arrives along true geodesics, and the
// scene keys are validated.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/error.hpp"
#include "sol/geodesic.hpp"
#include "sol/group.hpp"
#include "sol/render.hpp"
#include "sol/scene.hpp"
#include "sol/scene_file.hpp"
#include "sol/spreading.hpp"
#include "support/directions.hpp"

namespace {

sol::Scene one_ball(bool exact) {
  sol::Scene s;
  s.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 60.0};
  // Off z = 0: the bound is far from the sphere there.
  s.objects = {{sol::Ball{{1.3, 1.1, 0.6}, 0.5, exact}}};
  return s;
}

// Largest | d(hit, centre) - r | over the hit pixels (AOV hit points, float).
double sphere_error(const sol::RenderResult& r, const sol::SceneObject& object, int& hits) {
  const sol::Ball& ball = std::get<sol::Ball>(object.shape);
  double worst = 0.0;
  hits = 0;
  for (std::size_t i = 0; i < r.object.size(); ++i) {
    if (r.object[i] != 1.0f) continue;
    ++hits;
    const glm::dvec3 p(r.px[i], r.py[i], r.pz[i]);
    worst = std::max(worst, std::abs(sol::distance(p, ball.center) - ball.radius));
  }
  return worst;
}

TEST(ExactBall, HitPointsLieOnTheGeodesicSphere) {
  sol::RenderOptions settings;
  settings.width = 20;
  settings.height = 16;
  const sol::Scene exact = one_ball(true);
  int hits = 0;
  const double error = sphere_error(sol::render_cpu(exact, settings), exact.objects[0], hits);
  EXPECT_GT(hits, 20);
  // hit_epsilon 5e-5 plus the float rounding of the AOV coordinates.
  EXPECT_LT(error, 1e-4);
  // The bound-based ball draws another surface (outside the sphere, where
  // the bound is below the distance).
  const sol::Scene bound = one_ball(false);
  int bound_hits = 0;
  EXPECT_GT(sphere_error(sol::render_cpu(bound, settings), bound.objects[0], bound_hits), 1e-2);
}

TEST(ExactBall, DistanceIsTheBoundFarAndExactNear) {
  const glm::dvec3 c(0.3, -0.2, 0.4);
  for (const glm::dvec3& q : {glm::dvec3(3.0, 2.0, 0.1), glm::dvec3(0.9, 0.1, 0.5), glm::dvec3(0.5, -0.1, 0.9)}) {
    const double bound = sol::distance_lower_bound(q, c) - 0.5;
    const double d = sol::sdf_ball_exact(q, c, 0.5);
    if (bound > sol::kExactBallBand) {
      EXPECT_EQ(d, bound);
    } else {
      EXPECT_NEAR(d, sol::distance(q, c) - 0.5, 1e-12);
    }
    EXPECT_LE(d, sol::distance(q, c) - 0.5 + 1e-12);  // never above the true signed distance
  }
  // The normal is the unit tangent at q of the geodesic from the centre.
  const glm::dvec3 q(0.9, 0.1, 0.5);
  const glm::dvec3 n = sol::sdf_ball_exact_gradient(q, c);
  const double h = 1e-5, ez = std::exp(q.z);
  const glm::dvec3 fd((sol::distance(q + glm::dvec3(h * ez, 0, 0), c) - sol::distance(q - glm::dvec3(h * ez, 0, 0), c)) / (2 * h),
                      (sol::distance(q + glm::dvec3(0, h / ez, 0), c) - sol::distance(q - glm::dvec3(0, h / ez, 0), c)) / (2 * h),
                      (sol::distance(q + glm::dvec3(0, 0, h), c) - sol::distance(q - glm::dvec3(0, 0, h), c)) / (2 * h));
  EXPECT_NEAR(glm::length(n - fd), 0.0, 1e-5);
}

TEST(ExactLight, DirectionsAreGeodesicsReachingTheLight) {
  sol::Light light;
  light.type = sol::LightType::Point;
  light.position = {0.4, -0.3, 0.7};
  light.exact = true;
  const glm::dvec3 p(-0.5, 0.8, 0.1);
  const std::vector<sol::LightAtPoint> ls = sol::lights_at(light, p);
  ASSERT_EQ(ls.size(), 1u);
  const std::vector<sol::Connection> cs = sol::minimising_geodesics(p, light.position);
  const double length = cs.front().length;
  const sol::GeodesicState end = sol::flow({p, ls[0].direction}, length);
  EXPECT_LT(glm::length(sol::multiply(sol::inverse(light.position), end.position)), 1e-10);
  // The geodesic falloff (the default of exact lights): 1 / J of the
  // geodesic as the light sends it out (from the light along −u at the
  // end), which reciprocity makes J as seen from p.
  EXPECT_EQ(sol::falloff_of(light), sol::Falloff::Geodesic);
  EXPECT_NEAR(ls[0].attenuation * sol::sphere_area_density(-end.direction, length), 1.0, 1e-8);
  light.falloff = sol::Falloff::InverseSquare;
  EXPECT_NEAR(sol::lights_at(light, p)[0].attenuation, 1.0 / (1.0 + length * length), 1e-12);
  // On the cut locus of p two geodesics of the same length bring the light.
  light.position = sol::multiply(p, glm::dvec3(5.0, 5.0, 0.0));
  EXPECT_EQ(sol::lights_at(light, p).size(), 2u);
  // With a reach, the longer connections too (the straight line, 5√2).
  light.reach = 1.0;
  EXPECT_GE(sol::lights_at(light, p).size(), 3u);
  // Not exact: the single approximate direction.
  light.exact = false;
  EXPECT_EQ(sol::lights_at(light, p).size(), 1u);
}

// In the quotient the reach is bounded by the images enumerated: a reach
// that needs images beyond them (an incomplete list, and seconds a lit
// point) is refused when the world is prepared, naming the field and the
// largest reach the light allows; that largest is accepted.
TEST(ExactLight, QuotientReachBeyondTheEnumeratedImagesIsRefused) {
  sol::Scene scene = sol::preset_scene("lattice-balls");
  sol::Light light;
  light.type = sol::LightType::Point;
  light.exact = true;
  light.position = {0.3, 0.2, 0.4};
  light.reach = 10.0;
  scene.lights = {light};
  sol::CpuRenderer renderer;
  double allowed = 0.0;
  try {
    renderer.set_world(scene);
    ADD_FAILURE() << "reach 10 accepted in the quotient";
  } catch (const sol::InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("lights[0].reach: reach 10 in the quotient", 0), 0u) << what;
    const std::size_t at = what.find("at most ");
    ASSERT_NE(at, std::string::npos) << what;
    allowed = std::stod(what.substr(at + 8));
  }
  // The edge of |a|, |b| <= 22 lies about 3.3 from D, C about 2.1 (docs/lighting.md).
  EXPECT_GT(allowed, 1.0);
  EXPECT_LT(allowed, 1.4);
  scene.lights[0].reach = allowed;
  EXPECT_NO_THROW(renderer.set_world(scene));
  // The figure is the bound rounded down by 0.01 to 0.02: 0.02 more is beyond it.
  scene.lights[0].reach = allowed + 0.02;
  EXPECT_THROW(renderer.set_world(scene), sol::InvalidArgument);
}

void expect_rejected(const std::string& json, const std::string& words) {
  try {
    (void)sol::parse_scene(json, "bad.json");
    ADD_FAILURE() << "accepted: " << json;
  } catch (const sol::InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(words), std::string::npos) << "message '" << what << "' lacks '" << words << "'";
  }
}

TEST(ExactScene, KeysAreValidatedAndRoundTrip) {
  const std::string ball = R"({"type": "ball", "center": [0, 0, 0], "radius": 0.5)";
  expect_rejected(R"({"objects": [)" + ball + R"(, "exact": 1}]})", "'objects[0].exact' must be true or false");
  expect_rejected(R"({"objects": [{"type": "plane_z", "exact": true}]})", "exact");
  expect_rejected(R"({"objects": [)" + ball + R"(}], "lights": [{"type": "point", "position": [0, 0, 1], "exact": "yes"}]})",
                  "'lights[0].exact' must be true or false");
  expect_rejected(R"({"objects": [)" + ball + R"(}], "lights": [{"type": "point", "position": [0, 0, 1], "reach": -1}]})",
                  "lights[0].reach must be in [0, 10]");
  expect_rejected(R"({"objects": [)" + ball + R"(}], "lights": [{"type": "directional", "exact": true}]})", "exact");
  const sol::Scene s = sol::parse_scene(
      R"({"objects": [)" + ball + R"(, "exact": true}], "lights": [{"type": "point", "position": [0, 0, 1], "exact": true, "reach": 2}]})");
  EXPECT_TRUE(std::get<sol::Ball>(s.objects[0].shape).exact);
  EXPECT_TRUE(s.lights[0].exact);
  EXPECT_EQ(s.lights[0].reach, 2.0);
  EXPECT_TRUE(sol::uses_exact(s));
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  EXPECT_TRUE(std::get<sol::Ball>(back.objects[0].shape).exact);
  EXPECT_TRUE(back.lights[0].exact);
  EXPECT_EQ(back.lights[0].reach, 2.0);
  // Falloff and power: checked, named, round-tripped.
  const std::string light = R"(}], "lights": [{"type": "point", "position": [0, 0, 1])";
  expect_rejected(R"({"objects": [)" + ball + light + R"(, "falloff": "geodesic"}]})",
                  "lights[0].falloff geodesic needs \"exact\": true");
  expect_rejected(R"({"objects": [)" + ball + light + R"(, "exact": true, "falloff": "cubic"}]})",
                  "'lights[0].falloff' must be geodesic or inverse-square, got \"cubic\"");
  expect_rejected(R"({"objects": [)" + ball + light + R"(, "power": 1, "intensity": 2}]})", "takes 'power' or 'intensity', not both");
  expect_rejected(R"({"objects": [)" + ball + light + R"(, "power": -1}]})", "lights[0].power must be in");
  expect_rejected(R"({"objects": [)" + ball + R"(}], "lights": [{"type": "directional", "falloff": "geodesic"}]})", "falloff");
  const sol::Scene lit = sol::parse_scene(R"({"objects": [)" + ball + light +
                                          R"(, "exact": true, "falloff": "inverse-square", "power": 12.566370614359172}]})");
  EXPECT_EQ(lit.lights[0].falloff, sol::Falloff::InverseSquare);
  EXPECT_NEAR(lit.lights[0].intensity, 1.0, 1e-15);  // Φ / 4π
  EXPECT_EQ(sol::parse_scene(sol::to_json(lit)).lights[0].falloff, sol::Falloff::InverseSquare);
  EXPECT_EQ(sol::falloff_of(back.lights[0]), sol::Falloff::Geodesic);  // exact lights' default
  const sol::Scene spheres = sol::preset_scene("spheres");
  EXPECT_TRUE(sol::uses_exact(spheres));
  EXPECT_FALSE(sol::uses_exact(sol::preset_scene("plane")));
}

}  // namespace

namespace {

TEST(ConnectionTable, EverySeedIsAConnectionToACornerOfItsCell) {
  // The kernels' seeds (sol::ConnectionTable, minimisers): in every cell,
  // each seed is a unit direction with x, y >= 0, seeds come shortest
  // first, and each flows (double closed form) onto one of the cell's eight
  // corners.
  using T = sol::ConnectionTable;
  const T& table = T::shared(false);
  ASSERT_EQ(table.seeds.size(), static_cast<std::size_t>(T::kCellsXY * T::kCellsXY * T::kCellsZ * T::kSlots * 4));
  EXPECT_EQ(table.failed_nodes, 0);
  EXPECT_EQ(table.overflow_cells, 0);
  auto corner = [](int i, int j, int k) {
    return glm::dvec3(std::sinh(i * T::kStep), std::sinh(j * T::kStep), -T::kHeight + k * T::kStep);
  };
  double worst_landing = 0.0;
  int seeds = 0;
  for (int k = 0; k < T::kCellsZ; ++k) {
    for (int j = 0; j < T::kCellsXY; ++j) {
      for (int i = 0; i < T::kCellsXY; ++i) {
        const std::size_t base = static_cast<std::size_t>(((k * T::kCellsXY + j) * T::kCellsXY + i) * T::kSlots) * 4;
        double previous = 0.0;
        for (int s = 0; s < T::kSlots; ++s) {
          const float* seed = &table.seeds[base + 4 * static_cast<std::size_t>(s)];
          if (seed[3] == 0.0f) break;
          ++seeds;
          EXPECT_GE(seed[3], previous);  // shortest first
          previous = seed[3];
          const glm::dvec3 d(seed[0], seed[1], seed[2]);
          EXPECT_NEAR(glm::length(d), 1.0, 1e-6);
          EXPECT_GE(std::min(d.x, d.y), -1e-7);  // the quadrant x, y >= 0
          const glm::dvec3 end = sol::flow({glm::dvec3(0.0), glm::normalize(d)}, seed[3]).position;
          double nearest = 1e30;
          for (int c = 0; c < 8; ++c) {
            const glm::dvec3 w = corner(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
            nearest = std::min(nearest, sol::test::scaled_error(end, w));
          }
          worst_landing = std::max(worst_landing, nearest);
        }
      }
    }
  }
  std::printf("connection seeds: %d, worst landing on a corner %.2e (relative, float seeds)\n", seeds, worst_landing);
  EXPECT_GT(seeds, T::kCellsXY * T::kCellsXY * T::kCellsZ);
  // Float direction and length of a connection up to length ~17: ~1e-7
  // relative each, amplified by the flow's sensitivity (measured 7.5e-7); a
  // seed of another cell or a wrong sign lands O(1) away.
  EXPECT_LT(worst_landing, 1e-3);
}

}  // namespace
