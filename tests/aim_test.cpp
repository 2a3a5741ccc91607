// Aiming at a point (sol/aim.hpp): the geodesic of the found direction and
// length ends at the target (an image of it in a quotient), no image of
// the target is nearer (a brute-force window of lattice words), the cut
// locus's choice is the upward minimiser, and a camera aimed by the scene
// key camera.look_at sees the point at its centre pixel where the
// Euclidean direction does not.
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using glm::dvec3;

double diff(const dvec3& a, const dvec3& b) {
  const dvec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

sol::GeodesicState ends(const dvec3& eye, const sol::Aim& a) {
  return sol::flow(sol::GeodesicState{eye, a.direction}, a.distance);
}

TEST(Aim, TheGeodesicEndsAtTheTargetInSol) {
  const dvec3 eye(0.3, -0.2, 0.1), target(2.5, -1.7, 1.2);
  const sol::Aim a = sol::aim(eye, target);
  EXPECT_NEAR(glm::length(a.direction), 1.0, 1e-12);
  EXPECT_LT(diff(ends(eye, a).position, target), 1e-9);
  EXPECT_NEAR(a.distance, sol::distance(eye, target), 1e-10);
  EXPECT_FALSE(a.cut_locus);
  EXPECT_LT(diff(a.end, target), 1e-15);
  // Geodesics bend: the direction is far from the coordinate difference's
  // (here more than 10 degrees), which is why look_at is not forward = q - p.
  EXPECT_LT(glm::dot(a.direction, glm::normalize(target - eye)), std::cos(10.0 * 3.14159265358979 / 180.0));
}

TEST(Aim, OnTheCutLocusTheUpwardMinimiserIsTaken) {
  // (4, 4, 0) lies past the straight line's conjugate point (√2 π along
  // it): two minimisers (a, b, ±c) of one length reach it.
  const dvec3 eye(0.0), target(4.0, 4.0, 0.0);
  const sol::Aim a = sol::aim(eye, target);
  EXPECT_TRUE(a.cut_locus);
  EXPECT_GT(a.direction.z, 0.0);
  EXPECT_LT(diff(ends(eye, a).position, target), 1e-9);
  sol::Aim mirrored = a;
  mirrored.direction.z = -a.direction.z;
  EXPECT_LT(diff(ends(eye, mirrored).position, target), 1e-9);
  // Left translation keeps the choice: the same from another eye.
  const dvec3 p(1.5, -2.0, 0.7);
  const sol::Aim b = sol::aim(p, sol::multiply(p, target));
  EXPECT_TRUE(b.cut_locus);
  EXPECT_LT(diff(b.direction, a.direction), 1e-8);
}

// The nearest image of the target's domain point to the eye's, over a
// window of words far larger than any image within the found distance.
double brute_force_distance(const sol::Lattice& lattice, const dvec3& p, const dvec3& q) {
  double best = std::numeric_limits<double>::infinity();
  for (long long a = -8; a <= 8; ++a) {
    for (long long b = -8; b <= 8; ++b) {
      for (long long c = -2; c <= 2; ++c) {
        const dvec3 image = lattice.apply({a, b, c}, q);
        if (sol::distance_lower_bound(p, image) < best) best = std::min(best, sol::distance(p, image));
      }
    }
  }
  return best;
}

TEST(Aim, InAQuotientTheNearestImageIsAimedAt) {
  const struct {
    const char* name;
    sol::Lattice lattice;
  } cases[] = {
      {"golden", sol::Lattice::golden()},
      {"a turning monodromy", sol::Lattice::from_monodromy({-2, -1, -1, -1})},
      {"a z loop", sol::Lattice::z_loop(1.5)},
  };
  const dvec3 eye(0.4, 0.3, 0.2), target(-2.1, 2.6, 1.4);
  for (const auto& [name, lattice] : cases) {
    const sol::Aim a = sol::aim(eye, target, lattice);
    const dvec3 p = lattice.teleport(eye).point, q = lattice.teleport(target).point;
    // It reaches an image of the target, from the eye as given (outside D too).
    EXPECT_LT(diff(ends(eye, a).position, a.end), 1e-8) << name;
    EXPECT_LT(diff(lattice.teleport(a.end).point, q), 1e-8) << name;
    // No image is nearer, and the target's own copy is farther here.
    EXPECT_NEAR(a.distance, brute_force_distance(lattice, p, q), 1e-9) << name;
    EXPECT_LT(a.distance, sol::distance(eye, target) - 0.1) << name;
    std::printf("%s: distance %.6f, the target's own copy %.6f\n", name, a.distance, sol::distance(eye, target));
  }
}

TEST(Aim, ATargetAtTheEyeOrAlongUpIsRefused) {
  EXPECT_THROW(sol::aim(dvec3(1, 2, 3), dvec3(1, 2, 3)), sol::InvalidArgument);
  EXPECT_THROW(sol::aim(dvec3(1, 2, 3), dvec3(std::nan(""), 2, 3)), sol::InvalidArgument);
  // An image of the eye is the eye in the quotient.
  const sol::Lattice golden = sol::Lattice::golden();
  EXPECT_THROW(sol::aim(dvec3(0.2, 0.1, 0.3), golden.apply({1, 0, 0}, dvec3(0.2, 0.1, 0.3)), golden), sol::InvalidArgument);
  sol::Camera camera;
  camera.position = dvec3(0.0);
  camera.up = dvec3(0, 0, 1);
  EXPECT_THROW(sol::looking_at(camera, dvec3(0, 0, 2)), sol::InvalidArgument);  // straight up: along up
  const sol::Camera aimed = sol::looking_at(camera, dvec3(0, 0, -2) + dvec3(0.5, 0, 0));
  EXPECT_LT(diff(aimed.forward, sol::aim(camera.position, dvec3(0.5, 0, -2)).direction), 1e-15);
  EXPECT_LT(diff(aimed.up, camera.up), 1e-15);
}

TEST(Aim, TheObserverFacesADirectionKeepingItsUp) {
  sol::Observer o(dvec3(0.0), dvec3(1, 0, 0), dvec3(0, 0, 1));
  o.face(dvec3(0, 2, 1));
  EXPECT_LT(diff(o.forward(), glm::normalize(dvec3(0, 2, 1))), 1e-15);
  EXPECT_NEAR(glm::dot(o.up(), o.forward()), 0.0, 1e-15);
  EXPECT_GT(o.up().z, 0.8);  // the old up's part orthogonal to forward
  // Along the old up: the least rotation, which keeps the right vector.
  sol::Observer p(dvec3(0.0), dvec3(1, 0, 0), dvec3(0, 0, 1));
  const dvec3 right = p.right();
  p.face(dvec3(0, 0, 1));
  EXPECT_LT(diff(p.forward(), dvec3(0, 0, 1)), 1e-15);
  EXPECT_LT(diff(p.right(), right), 1e-15);
  EXPECT_THROW(p.face(dvec3(0.0)), sol::InvalidArgument);
}

// A small ball at the target, a camera that looks at it from a distance
// where geodesics bend: the centre pixel (of an odd-sized image) sees the
// ball; the camera pointed along the coordinate difference does not.
std::string look_at_scene(const char* quotient, const dvec3& eye, const dvec3& target, const char* aim) {
  char text[1024];
  std::snprintf(text, sizeof text,
                R"({"quotient": "%s", "camera": {"position": [%.17g, %.17g, %.17g], %s, "up": [0, 0, 1], "fov": 12},
                    "objects": [{"type": "ball", "center": [%.17g, %.17g, %.17g], "radius": 0.05}]})",
                quotient, eye.x, eye.y, eye.z, aim, target.x, target.y, target.z);
  return text;
}

TEST(Aim, TheLookAtPointIsAtTheCentrePixel) {
  const dvec3 eye(0.4, 0.3, 0.2), target(2.6, -1.9, 1.1);
  for (const char* quotient : {"none", "golden"}) {
    char look[160], naive[160];
    std::snprintf(look, sizeof look, R"("look_at": [%.17g, %.17g, %.17g])", target.x, target.y, target.z);
    const dvec3 d = glm::normalize(target - eye);
    std::snprintf(naive, sizeof naive, R"("forward": [%.17g, %.17g, %.17g])", d.x, d.y, d.z);
    const sol::Scene aimed = sol::parse_scene(look_at_scene(quotient, eye, target, look));
    const sol::Scene pointed = sol::parse_scene(look_at_scene(quotient, eye, target, naive));
    EXPECT_LT(diff(aimed.camera.forward, sol::aim(eye, target, aimed.lattice()).direction), 1e-15) << quotient;
    sol::RenderOptions settings;
    settings.width = 9;
    settings.height = 9;
    const std::size_t centre = 4 * 9 + 4;
    EXPECT_EQ(sol::render_cpu(aimed, settings).object[centre], 1.0f) << quotient;
    EXPECT_EQ(sol::render_cpu(pointed, settings).object[centre], 0.0f) << quotient;
  }
}

TEST(Aim, LookAtErrorsNameTheField) {
  const auto message = [](const std::string& text) {
    try {
      sol::parse_scene(text, "s.json");
    } catch (const sol::InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string both = message(
      R"({"camera": {"forward": [1, 0, 0], "look_at": [1, 2, 3]}, "objects": [{"type": "plane_z", "c": 0}]})");
  EXPECT_NE(both.find("camera: give either 'forward' or 'look_at', not both"), std::string::npos) << both;
  const std::string at_eye = message(
      R"({"camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}, "objects": [{"type": "plane_z", "c": 0}]})");
  EXPECT_NE(at_eye.find("camera.look_at: the target is at the eye"), std::string::npos) << at_eye;
  const std::string up = message(
      R"({"camera": {"position": [0, 0, 0], "look_at": [0, 0, 3]}, "objects": [{"type": "plane_z", "c": 0}]})");
  EXPECT_NE(up.find("camera.look_at: the target is seen straight along the camera's up"), std::string::npos) << up;
  try {
    sol::parse_camera_path(R"({"start": {"forward": [1, 0, 0], "look_at": [1, 2, 3]}, "segments": [{"hold": 1}]})", "p.json");
    ADD_FAILURE() << "a start with forward and look_at accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("start: give either 'forward' or 'look_at'"), std::string::npos) << e.what();
  }
  try {
    sol::parse_camera_path(R"({"segments": [{"walk": "left", "distance": 1, "duration": 1, "look_at": [1, 2]}]})", "p.json");
    ADD_FAILURE() << "a look_at of two numbers accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("segments[0].look_at"), std::string::npos) << e.what();
  }
}

TEST(Aim, CameraPathsLookAtTheirPoint) {
  const dvec3 target(1.5, 1.0, 0.4);
  const sol::CameraPath path = sol::parse_camera_path(R"({
    "start": {"position": [0, 0, 0.2], "look_at": [1.5, 1.0, 0.4], "up": [0, 0, 1]},
    "segments": [{"walk": "right", "distance": 1.5, "duration": 2, "look_at": [1.5, 1.0, 0.4]},
                 {"hold": 1}]})");
  const sol::Camera scene = sol::preset_scene("plane").camera;
  for (const std::optional<sol::Lattice>& lattice : {std::optional<sol::Lattice>{}, std::optional(sol::Lattice::golden())}) {
    for (double t : {0.0, 0.7, 2.0, 2.5}) {
      const sol::Camera c = path.at(t, scene, lattice);
      EXPECT_LT(diff(c.forward, sol::aim(c.position, target, lattice).direction), 1e-12) << t;
      EXPECT_NEAR(glm::dot(c.forward, c.up), 0.0, 1e-12);
    }
  }
}

}  // namespace
