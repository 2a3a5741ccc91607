// Shadows (Light::shadows) on the CPU reference renderer, against an
// independent occlusion test: the geodesics the light arrives along,
// sampled densely with sol::flow in double and checked against the objects'
// own distance functions.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <variant>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/shadow_scene.hpp"

namespace {

using glm::dvec3;

// The floor, the ball and the light (support/shadow_scene.hpp), the march
// limited to arc length 6.
sol::Scene shadow_scene() {
  sol::Scene scene = sol::test::shadow_scene();
  scene.max_distance = 6.0;
  return scene;
}

// The least value of the scene's signed distances over points sampled
// every `spacing` along the geodesic from p along `direction` up to
// `length`: balls by their own distance function (sol::object_distance,
// negative inside), planes z = c by (z − c) on the side the geodesic
// starts from (negative once it has crossed). The surface the geodesic
// starts on (object `start`, 0-based, left along its normal `normal`)
// counts only once its distance stops growing: leaving it is not meeting
// it (a light low over the floor keeps the geodesic within 2e-3 of it for a
// while).
double least_distance_along(const sol::Scene& scene, const dvec3& p, const dvec3& normal, const dvec3& direction,
                            double length, std::size_t start, double spacing) {
  std::vector<double> side(scene.objects.size(), 1.0);
  for (std::size_t k = 0; k < scene.objects.size(); ++k) {
    if (const auto* plane = std::get_if<sol::PlaneZ>(&scene.objects[k].shape)) {
      side[k] = (k == start ? normal.z : p.z - plane->c) >= 0.0 ? 1.0 : -1.0;
    }
  }
  auto signed_distance = [&](std::size_t k, const dvec3& q) {
    if (const auto* plane = std::get_if<sol::PlaneZ>(&scene.objects[k].shape)) return side[k] * (q.z - plane->c);
    return sol::object_distance({scene.objects[k].shape, 0}, q);
  };
  double least = std::numeric_limits<double>::infinity(), previous = -std::numeric_limits<double>::infinity();
  bool leaving = true;
  for (double s = spacing; s <= length; s += spacing) {
    const dvec3 q = sol::flow({p, direction}, s).position;
    for (std::size_t k = 0; k < scene.objects.size(); ++k) {
      const double d = signed_distance(k, q);
      if (k == start) {
        leaving = leaving && d > previous;
        previous = d;
        if (leaving) continue;
      }
      least = std::min(least, d);
    }
  }
  return least;
}

// Each floor pixel's share of the light that arrives unblocked, from the
// renders (shadowed - dark) / (unshadowed - dark) and from sampling every
// connection the light arrives along: they agree, except where a sampled
// geodesic passes within 2e-3 of an object (the sampling's and the march's
// resolution; those pixels are skipped). The sampling: every 2e-3 of arc
// length, so a geodesic that enters an object deeper than about 2e-6 (a
// chord of 2e-3 in a ball of radius 0.25) is seen.
void expect_shadows_match_sampling(const sol::Scene& scene, int width, int height, int stride) {
  sol::Scene unshadowed = scene, dark = scene;
  unshadowed.lights[0].shadows = false;
  dark.lights[0].intensity = 0.0;
  sol::RenderOptions settings;
  settings.width = width;
  settings.height = height;
  const sol::RenderResult with = sol::render_cpu(scene, settings), without = sol::render_cpu(unshadowed, settings),
                          none = sol::render_cpu(dark, settings);
  const sol::CpuRenderer renderer(scene);
  int compared = 0, shadowed = 0, lit = 0, skipped = 0;
  for (int j = 0; j < height; j += stride) {
    for (int i = 0; i < width; i += stride) {
      const std::size_t k = static_cast<std::size_t>(j * width + i);
      if (with.object[k] != 1.0f) continue;  // the floor
      const double full = without.rgba[4 * k] - none.rgba[4 * k];
      if (full < 1e-4) continue;  // the light does not reach it even unblocked
      const double share = (with.rgba[4 * k] - none.rgba[4 * k]) / full;
      // The reference: the same hit in double, the light's ways to it, each sampled.
      const sol::MarchHit hit = renderer.march(scene.camera, sol::camera_ray(scene.camera, i, j, width, height));
      EXPECT_EQ(hit.object, 1);
      double total = 0.0, open = 0.0;
      bool borderline = false;
      for (const sol::LightAtPoint& at : sol::lights_at(scene.lights[0], hit.point)) {
        const double cosine = glm::dot(hit.normal, at.direction);
        if (cosine <= 0.0) continue;
        const double length = std::min(at.length, scene.max_distance);
        const double least = least_distance_along(scene, hit.point, hit.normal, at.direction, length, 0, 2e-3);
        borderline = borderline || std::abs(least) < 2e-3;
        total += at.attenuation * cosine;
        if (least > 0.0) open += at.attenuation * cosine;
      }
      if (borderline) {
        ++skipped;
        continue;
      }
      const double expected = open / total;
      EXPECT_NEAR(share, expected, 1e-4) << "pixel " << i << ", " << j;
      ++compared;
      shadowed += expected < 0.5;
      lit += expected > 0.5;
    }
  }
  std::printf("shadows against sampling: %d floor pixels compared (%d in shadow, %d lit), %d borderline skipped\n",
              compared, shadowed, lit, skipped);
  EXPECT_GT(shadowed, 10);  // the test needs both kinds
  EXPECT_GT(lit, 10);
  EXPECT_LT(skipped, compared / 5);
}

TEST(Shadows, ABallDarkensThePointsWhoseGeodesicsToTheLightMeetIt) { expect_shadows_match_sampling(shadow_scene(), 48, 36, 1); }

// Without the ball nothing is in shadow: the shadowed image is the
// unshadowed one, bit for bit (the floor does not shadow itself).
TEST(Shadows, RemovingTheBallRemovesTheShadow) {
  {
    sol::Scene scene = shadow_scene();
    sol::Scene unshadowed = scene;
    unshadowed.lights[0].shadows = false;
    sol::RenderOptions settings;
    settings.width = 32;
    settings.height = 24;
    int darker = 0;
    {
      const sol::RenderResult with = sol::render_cpu(scene, settings), without = sol::render_cpu(unshadowed, settings);
      for (std::size_t k = 0; k < with.object.size(); ++k) darker += with.rgba[4 * k] < without.rgba[4 * k];
    }
    EXPECT_GT(darker, 20);
    scene.objects.pop_back();
    unshadowed.objects.pop_back();
    const sol::RenderResult with = sol::render_cpu(scene, settings), without = sol::render_cpu(unshadowed, settings);
    EXPECT_EQ(with.rgba, without.rgba);
  }
}

// No shadow acne: a lone ball, lit, shadows itself only where the light's
// geodesic really runs back into it: every pixel the shadows darken is
// checked by sampling, and there are none where the light is well above
// the horizon (cos θ > 0.2), for the ball drawn with its bound and exact.
TEST(Shadows, NoShadowAcneOnALoneBall) {
  for (bool exact_ball : {false, true}) {
    sol::Scene scene;
    scene.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 50.0};
    scene.objects = {{sol::Ball{{1.0, 1.0, 0.0}, 0.4, exact_ball}, {0.9, 0.5, 0.3}}};
    const sol::Light light = sol::test::shadowing_light({0.2, 0.9, 0.4});
    scene.lights = {light};
    sol::Scene unshadowed = scene;
    unshadowed.lights[0].shadows = false;
    sol::RenderOptions settings;
    settings.width = 24;
    settings.height = 24;
    const sol::RenderResult with = sol::render_cpu(scene, settings), without = sol::render_cpu(unshadowed, settings);
    const sol::CpuRenderer renderer(scene);
    int lit = 0, darker = 0;
    for (int j = 0; j < 24; ++j) {
      for (int i = 0; i < 24; ++i) {
        const std::size_t k = static_cast<std::size_t>(j * 24 + i);
        if (with.object[k] != 1.0f) continue;
        const sol::MarchHit hit = renderer.march(scene.camera, sol::camera_ray(scene.camera, i, j, 24, 24));
        for (const sol::LightAtPoint& at : sol::lights_at(light, hit.point)) {
          const double cosine = glm::dot(hit.normal, at.direction);
          lit += cosine > 0.2;
          if (with.rgba[4 * k] < without.rgba[4 * k]) {
            ++darker;
            EXPECT_LT(cosine, 0.2) << "acne at pixel " << i << ", " << j;
            EXPECT_LT(least_distance_along(scene, hit.point, hit.normal, at.direction, at.length, 0, 2e-3), 2e-3) << i << ", " << j;
          }
        }
      }
    }
    std::printf("lone %s ball: %d lit pixels, %d darkened by its own shadow\n", exact_ball ? "exact" : "bound", lit, darker);
    EXPECT_GT(lit, 30);
  }
}

TEST(Shadows, KeysAreCheckedAndRoundTrip) {
  const char* ball = R"({"objects": [{"type": "ball", "center": [0, 0, 0], "radius": 0.5}], "lights": )";
  try {
    (void)sol::parse_scene(std::string(ball) + R"([{"type": "point", "position": [0, 0, 1], "shadows": true}]})", "bad.json");
    ADD_FAILURE() << "a point light's shadows without exact accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("lights[0].shadows needs an exact point light"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)sol::parse_scene(std::string(ball) + R"([{"type": "directional", "shadows": true}]})"), sol::InvalidArgument);
  EXPECT_THROW((void)sol::parse_scene(std::string(ball) + R"([{"type": "point", "position": [0, 0, 1], "exact": true, "shadows": 1}]})"),
               sol::InvalidArgument);
  const sol::Scene s = sol::parse_scene(std::string(ball) + R"([{"type": "point", "position": [0, 0, 1], "exact": true, "shadows": true}]})");
  EXPECT_TRUE(s.lights[0].shadows);
  EXPECT_TRUE(sol::parse_scene(sol::to_json(s)).lights[0].shadows);
}

}  // namespace

namespace {

// The quotient: an exact light is seen along the geodesics to every image
// γ·L within d + reach. Against brute force over a larger box of images
// (|a|, |b| <= 6, |c| <= 3, exact distances): sol::quotient_light_images
// holds every image that matters for random points of D, and lights_at
// finds the same ways (directions and lengths); the light moved by an
// element of Γ lights every point the same.
TEST(QuotientLight, EveryImageWithinReachAndNoOther) {
  const sol::Lattice lattice = sol::Lattice::golden();
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const glm::dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
  auto point_in_domain = [&] {
    const double s = unit(rng), r = unit(rng);
    return dvec3(s * g1.x + r * g2.x, s * g1.y + r * g2.y, lattice.height() * unit(rng));
  };
  for (const double reach : {0.0, 0.5}) {
    sol::Light light;
    light.type = sol::LightType::Point;
    light.exact = true;
    light.reach = reach;
    light.position = point_in_domain();
    const std::vector<dvec3> images = sol::quotient_light_images(light, lattice);
    sol::Light moved = light;
    moved.position = sol::multiply(lattice.element(2, -1, 1), light.position);
    const std::vector<dvec3> moved_images = sol::quotient_light_images(moved, lattice);
    int ways = 0;
    for (int k = 0; k < 12; ++k) {
      const dvec3 p = point_in_domain();
      // Brute force: every image in the big box, exact distances.
      std::vector<std::pair<double, dvec3>> all;
      for (int a = -6; a <= 6; ++a) {
        for (int b = -6; b <= 6; ++b) {
          for (int c = -3; c <= 3; ++c) {
            const dvec3 q = sol::multiply(lattice.element(a, b, c), lattice.teleport(light.position).point);
            if (sol::distance_lower_bound(p, q) <= 4.0) all.emplace_back(sol::distance(p, q), q);
          }
        }
      }
      double best = std::numeric_limits<double>::infinity();
      for (const auto& [d, q] : all) best = std::min(best, d);
      std::vector<sol::Connection> expected;
      for (const auto& [d, q] : all) {
        if (d > best + reach + 1e-9) continue;
        // Every image within reach is in the list.
        EXPECT_TRUE(std::any_of(images.begin(), images.end(), [&, q = q](const dvec3& m) { return glm::length(m - q) < 1e-9; }))
            << "missing image at distance " << d;
        for (const sol::Connection& c : reach > 0.0 ? sol::geodesics_between(p, q, best + reach) : sol::minimising_geodesics(p, q)) {
          expected.push_back(c);
        }
      }
      std::vector<sol::LightAtPoint> got = sol::lights_at(light, p, images);
      ASSERT_EQ(got.size(), expected.size()) << "point " << k;
      auto by_length = [](const auto& x, const auto& y) { return x.length < y.length; };
      std::sort(expected.begin(), expected.end(), by_length);
      std::sort(got.begin(), got.end(), by_length);
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_NEAR(got[i].length, expected[i].length, 1e-9);
        EXPECT_LT(glm::length(got[i].direction - glm::normalize(expected[i].direction)), 1e-8);
      }
      ways += static_cast<int>(got.size());
      // Moved by Γ, the light reaches p the same ways.
      std::vector<sol::LightAtPoint> same = sol::lights_at(moved, p, moved_images);
      ASSERT_EQ(same.size(), got.size());
      std::sort(same.begin(), same.end(), by_length);
      for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(same[i].attenuation, got[i].attenuation, 1e-9 * got[i].attenuation);
    }
    std::printf("quotient light, reach %g: %zu images listed, %d ways to 12 points\n", reach, images.size(), ways);
    if (reach > 0.0) {
      EXPECT_GT(ways, 12);  // the reach adds ways
    }
  }
}

}  // namespace
