// Depth of field (sol/lens.hpp): the lens samples cover the unit disk
// evenly; every ray of the lens meets its pixel ray's focus point (checked
// by the independent Bulirsch–Stoer geodesic of tests/support, not the
// closed form the solve uses), where the Euclidean guess does not; through
// the CPU renderer's march, a small ball at the focus is hit by every lens
// ray of the pixel that looks at it, one at twice the distance is missed by
// most; and the scene file's keys.
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/reference_geodesic.hpp"

namespace {

// The point at arc length t along the geodesic from `start` with frame
// direction d, by the reference integrator (coordinates, Bulirsch–Stoer).
glm::dvec3 reference_point(const glm::dvec3& start, const glm::dvec3& d, double t) {
  sol::test::ReferenceGeodesic<double> g(start, d, false, 1e-14);
  return g.at(t).position;
}

}  // namespace

// Sample 0 is the centre; the rest lie in the unit disk, evenly: a quarter
// of them within radius 1/2 and each quadrant a quarter (within 1 %: a
// low-discrepancy sequence of 4096 points is far closer than random ones'
// 1.6 % standard deviation), and the mean near the centre.
TEST(Lens, SamplesCoverTheDiskEvenly) {
  EXPECT_EQ(sol::lens_sample(0), glm::dvec2(0.0));
  EXPECT_THROW(sol::lens_sample(-1), sol::InvalidArgument);
  constexpr int n = 4096;
  int inner = 0, quadrant[4] = {0, 0, 0, 0};
  glm::dvec2 mean(0.0);
  for (int k = 1; k <= n; ++k) {
    const glm::dvec2 p = sol::lens_sample(k);
    ASSERT_LE(glm::length(p), 1.0 + 1e-15) << k;
    inner += glm::length(p) < 0.5 ? 1 : 0;
    ++quadrant[(p.x >= 0.0 ? 0 : 1) + (p.y >= 0.0 ? 0 : 2)];
    mean += p / static_cast<double>(n);
  }
  EXPECT_NEAR(inner / static_cast<double>(n), 0.25, 0.01);
  for (int q : quadrant) EXPECT_NEAR(q / static_cast<double>(n), 0.25, 0.01);
  EXPECT_LT(glm::length(mean), 0.01);
}

// For pixel rays in general directions, lenses of 0.01 to 0.3 and focus
// distances 0.5 to 3, the ray of every lens point meets F = exp(f u): its
// reference geodesic from the lens point reaches F within 1e-9 (the
// integrator's tolerance) after focus_length.
TEST(Lens, EveryLensRayMeetsTheFocus) {
  const glm::dvec3 directions[] = {glm::normalize(glm::dvec3(1.0, 0.2, 0.1)), glm::normalize(glm::dvec3(0.3, -0.8, 0.5)),
                                   glm::normalize(glm::dvec3(-0.6, 0.6, -0.5)), glm::dvec3(0.0, 0.0, 1.0)};
  for (const double aperture : {0.01, 0.1, 0.3}) {
    for (const double f : {0.5, 1.0, 2.0, 3.0}) {
      sol::Camera camera;
      camera.forward = glm::normalize(glm::dvec3(1.0, 0.1, 0.05));
      camera.aperture = aperture;
      camera.focus_distance = f;
      for (const glm::dvec3& u : directions) {
        const glm::dvec3 focus = reference_point(glm::dvec3(0.0), u, f);
        for (int k = 1; k <= 6; ++k) {
          const sol::LensRay ray = sol::lens_ray(camera, u, sol::lens_sample(k));
          ASSERT_TRUE(ray.focused) << aperture << " " << f << " " << k;
          EXPECT_NEAR(glm::length(ray.direction), 1.0, 1e-14);
          // The lens point: the geodesic of length a |disk| from the eye in the lens plane.
          const sol::CameraBasis basis = sol::camera_basis(camera);
          const glm::dvec2 disk = sol::lens_sample(k);
          const glm::dvec3 offset = aperture * (disk.x * basis.right + disk.y * basis.up);
          EXPECT_LT(glm::length(ray.start - reference_point(glm::dvec3(0.0), offset, glm::length(offset))), 1e-12);
          const glm::dvec3 end = reference_point(ray.start, ray.direction, ray.focus_length);
          EXPECT_LT(glm::length(end - focus), 1e-9 * std::max(1.0, glm::length(focus)))
              << "aperture " << aperture << ", f " << f << ", sample " << k;
        }
      }
    }
  }
  // The centre of the lens, or no aperture: the pixel ray itself.
  sol::Camera pinhole;
  const glm::dvec3 u = glm::normalize(glm::dvec3(0.3, 0.4, 0.5));
  EXPECT_EQ(sol::lens_ray(pinhole, u, sol::lens_sample(3)).direction, u);
  EXPECT_EQ(sol::lens_ray(pinhole, u, sol::lens_sample(3)).start, glm::dvec3(0.0));
  pinhole.aperture = 0.2;
  EXPECT_EQ(sol::lens_ray(pinhole, u, glm::dvec2(0.0)).direction, u);
}

// Why the solve: the Euclidean thin lens (from δ along f u − offset) misses
// the focus by a share of the aperture that grows with f (its closest
// approach at f = 3: 0.67 apertures for a ray along x and a lens offset
// along z, 0.83 for a ray along z and an offset along y), where the lens
// ray meets it within 1e-9.
TEST(Lens, TheEuclideanGuessMissesTheFocus) {
  struct Case {
    glm::dvec3 forward, up;
    double least;  // the least miss, in apertures
  };
  const Case cases[] = {{{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 0.5}, {{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, 0.5}};
  for (const Case& c : cases) {
    sol::Camera camera;
    camera.forward = c.forward;
    camera.up = c.up;
    camera.aperture = 0.01;
    camera.focus_distance = 3.0;
    const glm::dvec3 u = c.forward;
    const glm::dvec2 disk(0.0, 1.0);  // the lens offset along the camera's up
    const glm::dvec3 offset = camera.aperture * sol::camera_basis(camera).up;
    const glm::dvec3 focus = reference_point(glm::dvec3(0.0), u, camera.focus_distance);
    const glm::dvec3 start = sol::exp_map(offset);
    const glm::dvec3 guess = glm::normalize(camera.focus_distance * u - offset);
    double nearest = 1e30;  // the guess's closest approach to the focus
    for (double t = 2.8; t <= 3.2; t += 1e-4) nearest = std::min(nearest, glm::length(reference_point(start, guess, t) - focus));
    EXPECT_GT(nearest, c.least * camera.aperture);
    const sol::LensRay ray = sol::lens_ray(camera, u, disk);
    EXPECT_LT(glm::length(reference_point(ray.start, ray.direction, ray.focus_length) - focus), 1e-9);
    std::printf("Euclidean thin lens at f = 3, forward (%g, %g, %g): misses the focus by %.3f apertures\n", u.x, u.y, u.z,
                nearest / camera.aperture);
  }
}

// Through the CPU renderer's march: a ball of radius 0.02 at the focus point
// of the centre pixel is hit by every lens ray of that pixel; a ball seen
// behind it by the pinhole, at twice the distance, is missed by most lens
// rays of an aperture 20 times its radius.
TEST(Lens, TheFocusIsHitByEveryLensRayAndTheBackgroundBlurs) {
  sol::Scene scene;
  scene.camera.position = {0.2, -0.1, 0.3};
  scene.camera.forward = glm::normalize(glm::dvec3(1.0, 0.3, -0.1));
  scene.camera.aperture = 0.4;
  scene.camera.focus_distance = 1.5;
  const glm::dvec3 u = glm::normalize(scene.camera.forward);
  const glm::dvec3 focus = sol::multiply(scene.camera.position, sol::exp_map(1.5 * u));
  const glm::dvec3 behind = sol::multiply(scene.camera.position, sol::exp_map(3.0 * u));
  sol::SceneObject near, far;
  near.shape = sol::Ball{focus, 0.02, true};
  far.shape = sol::Ball{behind, 0.02, true};
  for (const int which : {0, 1, 2, 3}) {
    scene.space = which < 2 ? sol::Space(sol::SolSpace{}) : sol::Space(sol::GoldenSpace{});
    scene.objects = {which % 2 == 0 ? near : far};
    sol::CpuRenderer renderer(scene);
    int hits = 0;
    constexpr int n = 32;
    for (int k = 1; k <= n; ++k) {
      const sol::LensRay ray = sol::lens_ray(scene.camera, u, sol::lens_sample(k));
      sol::Camera at = scene.camera;
      at.position = sol::multiply(scene.camera.position, ray.start);
      hits += renderer.march(at, ray.direction).object == 1 ? 1 : 0;
    }
    EXPECT_EQ(renderer.march(scene.camera, u).object, 1);  // the pinhole sees both
    if (which % 2 == 0) {
      EXPECT_EQ(hits, n) << which;
    } else {
      EXPECT_LT(hits, n / 4) << which;
    }
  }
}

// Scene files: "aperture" and "focus_distance" in the camera, written back;
// with look_at and no focus_distance the lens focuses on the point; the
// refusals name the field.
TEST(Lens, SceneKeys) {
  const std::string objects = R"("objects": [{"type": "plane_z"}])";
  const sol::Scene s = sol::parse_scene(R"({"camera": {"aperture": 0.1, "focus_distance": 4}, )" + objects + "}");
  EXPECT_EQ(s.camera.aperture, 0.1);
  EXPECT_EQ(s.camera.focus_distance, 4.0);
  const sol::Scene back = sol::parse_scene(sol::to_json(s));
  EXPECT_EQ(back.camera.aperture, 0.1);
  EXPECT_EQ(back.camera.focus_distance, 4.0);
  const glm::dvec3 eye(0.1, 0.2, 0.3), target(1.7, -0.4, 0.9);
  const sol::Scene aimed = sol::parse_scene(R"({"camera": {"position": [0.1, 0.2, 0.3], "look_at": [1.7, -0.4, 0.9],
      "aperture": 0.1}, )" + objects + "}");
  EXPECT_NEAR(aimed.camera.focus_distance, sol::distance(eye, target), 1e-9);
  const sol::Scene kept = sol::parse_scene(R"({"camera": {"position": [0.1, 0.2, 0.3], "look_at": [1.7, -0.4, 0.9],
      "aperture": 0.1, "focus_distance": 0.7}, )" + objects + "}");
  EXPECT_EQ(kept.camera.focus_distance, 0.7);
  auto rejected = [&](const std::string& camera, const std::string& words) {
    try {
      (void)sol::parse_scene(R"({"camera": )" + camera + ", " + objects + "}");
      ADD_FAILURE() << "accepted " << camera;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  rejected(R"({"aperture": -0.1})", "camera.aperture must be in [0, 1]");
  rejected(R"({"aperture": 2})", "camera.aperture must be in [0, 1]");
  rejected(R"({"focus_distance": 0})", "camera.focus_distance must be in (0, 100]");
  rejected(R"({"aperture": 0.1, "projection": "equirectangular"})", "for the perspective and fisheye projections only");
}
