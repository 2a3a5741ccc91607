// Camera paths (sol/camera_path.hpp): the camera of time t is sol::Observer
// after the same moves, made here step by step with its own API; segments
// in proportion; the quotient keeps the camera in D; errors name the field.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using glm::dvec3;

double diff(const dvec3& a, const dvec3& b) {
  const dvec3 d = glm::abs(a - b);
  return std::max({d.x, d.y, d.z});
}

const char* kPath = R"({
  "start": {"position": [0.1, 0.2, 0.3], "forward": [1, 0.2, 0], "up": [0, 0, 1], "fov": 70},
  "segments": [
    {"walk": "forward", "distance": 2, "duration": 4},
    {"turn": "yaw", "degrees": 90, "duration": 2},
    {"hold": 1.5},
    {"walk": "up", "distance": -0.5, "duration": 1},
    {"turn": "pitch", "degrees": -30, "duration": 1},
    {"walk": "left", "distance": 1, "duration": 0.5},
    {"turn": "roll", "degrees": 45, "duration": 0.5}
  ]})";

TEST(CameraPath, FramesAreTheObserverAfterTheSameMoves) {
  const sol::CameraPath path = sol::parse_camera_path(kPath);
  EXPECT_DOUBLE_EQ(path.duration(), 10.5);
  EXPECT_EQ(path.frame_count(24.0), 253);  // t = 0, 1/24, ..., 10.5
  EXPECT_EQ(path.frame_count(2.0), 22);
  const sol::Camera scene = sol::preset_scene("sandwich").camera;
  auto observer = [] { return sol::Observer({0.1, 0.2, 0.3}, {1, 0.2, 0}, {0, 0, 1}); };
  constexpr double deg = std::numbers::pi / 180.0;
  auto expect_same = [](const sol::Camera& c, const sol::Observer& o, double t) {
    EXPECT_LT(diff(c.position, o.position()), 1e-12) << t;
    EXPECT_LT(diff(c.forward, o.forward()), 1e-12) << t;
    EXPECT_LT(diff(c.up, o.up()), 1e-12) << t;
  };
  {  // t = 0: the start (with the path's fov)
    const sol::Camera c = path.at(0.0, scene, std::nullopt);
    expect_same(c, observer(), 0.0);
    EXPECT_EQ(c.fov, 70.0);
  }
  {  // t = 3: three quarters of the first walk
    sol::Observer o = observer();
    o.move({0, 0, 1}, 1.5);
    expect_same(path.at(3.0, scene, std::nullopt), o, 3.0);
  }
  {  // t = 5: the walk, half the yaw
    sol::Observer o = observer();
    o.move({0, 0, 1}, 2.0);
    o.yaw(45 * deg);
    expect_same(path.at(5.0, scene, std::nullopt), o, 5.0);
  }
  {  // t = 7 (in the hold) equals t = 6 (its start)
    const sol::Camera a = path.at(6.0, scene, std::nullopt), b = path.at(7.0, scene, std::nullopt);
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.forward, b.forward);
  }
  {  // the end, and beyond it (clamped)
    sol::Observer o = observer();
    o.move({0, 0, 1}, 2.0);
    o.yaw(90 * deg);
    o.move({0, 1, 0}, -0.5);
    o.pitch(-30 * deg);
    o.move({-1, 0, 0}, 1.0);
    o.roll(45 * deg);
    expect_same(path.at(10.5, scene, std::nullopt), o, 10.5);
    expect_same(path.at(99.0, scene, std::nullopt), o, 99.0);
  }
}

TEST(CameraPath, TheQuotientKeepsTheCameraInTheDomain) {
  const sol::CameraPath path = sol::parse_camera_path(
      R"({"segments": [{"walk": "forward", "distance": 6, "duration": 6}, {"turn": "pitch", "degrees": 80, "duration": 1},
                       {"walk": "forward", "distance": 4, "duration": 4}]})");
  const sol::Scene scene = sol::preset_scene("lattice-balls");
  const sol::Lattice lattice = sol::Lattice::golden();
  sol::Observer free_walker(scene.camera.position, scene.camera.forward, scene.camera.up);
  for (long k = 0; k < path.frame_count(4.0); ++k) {
    const sol::Camera c = path.at(static_cast<double>(k) / 4.0, scene.camera, sol::Lattice::golden());
    ASSERT_TRUE(lattice.contains(c.position)) << k;
  }
  // The end is the unbound walk's end, teleported (up to the domain's wrap).
  free_walker.move({0, 0, 1}, 6.0);
  free_walker.pitch(80 * std::numbers::pi / 180.0);
  free_walker.move({0, 0, 1}, 4.0);
  const sol::Camera end = path.at(11.0, scene.camera, sol::Lattice::golden());
  const dvec3 expected = lattice.teleport(free_walker.position()).point;
  EXPECT_LT(diff(end.position, expected), 1e-8);
  EXPECT_LT(diff(end.forward, free_walker.forward()), 1e-9);
}

// A long walk in a compact quotient (125 units, as far as solview walks):
// every frame's camera, in D, as an observer walking it metre by metre in
// the quotient (each step teleported) finds it. In one flow the walk's
// point left D by a lattice element whose word was no longer exact in
// double past about 35 units, and the path was refused.
TEST(CameraPath, ALongWalkInTheQuotientIsTheObserversWalk) {
  const sol::CameraPath path = sol::parse_camera_path(
      R"({"segments": [{"walk": "forward", "distance": 125, "duration": 5}]})");
  const sol::Scene scene = sol::preset_scene("lattice-balls");
  const sol::Lattice lattice = sol::Lattice::golden();
  sol::Observer walker(scene.camera.position, dvec3(0.3, 0.5, 0.81), scene.camera.up);
  walker.bind(lattice);
  sol::Camera start = scene.camera;
  start.forward = dvec3(0.3, 0.5, 0.81);
  for (int k = 1; k <= 125; ++k) {
    walker.move({0, 0, 1}, 1.0);
    if (k % 25 != 0) continue;
    const sol::Camera c = path.at(k / 25.0, start, lattice);
    ASSERT_TRUE(lattice.contains(c.position)) << k;
    // The same steps in the same order: equal up to rounding, which the walk's instability (e^t) grows.
    EXPECT_LT(diff(c.position, walker.position()), 1e-6 * std::exp(0.1 * k)) << k;
  }
}

// The lens along a path: the start's aperture and focus distance override
// the scene camera's; where the path gives no focus distance the lens
// focuses on the start's look_at point and then on a tracking walk's
// point, frame by frame (its distance, sol::distance in Sol); a focus
// distance of the path's own stays.
TEST(CameraPath, TheLensFocusesOnThePointsLookedAt) {
  const sol::CameraPath tracking = sol::parse_camera_path(R"({"start": {"position": [0, 0, 0.5], "look_at": [2, 1, 0.5],
      "aperture": 0.05}, "segments": [{"walk": "right", "distance": 1.5, "duration": 2, "look_at": [3, -1, 0.2]}]})");
  const sol::Camera scene_camera;
  const sol::Camera start = tracking.at(0.0, scene_camera, std::nullopt);
  EXPECT_EQ(start.aperture, 0.05);
  EXPECT_NEAR(start.focus_distance, sol::distance(glm::dvec3(0, 0, 0.5), glm::dvec3(2, 1, 0.5)), 1e-9);
  for (const double t : {0.5, 1.0, 2.0}) {
    const sol::Camera c = tracking.at(t, scene_camera, std::nullopt);
    EXPECT_NEAR(c.focus_distance, sol::distance(c.position, glm::dvec3(3, -1, 0.2)), 1e-9) << t;
  }
  const sol::CameraPath fixed = sol::parse_camera_path(R"({"start": {"look_at": [2, 1, 0.5], "aperture": 0.05,
      "focus_distance": 0.8}, "segments": [{"walk": "right", "distance": 1, "duration": 1, "look_at": [3, -1, 0.2]}]})");
  EXPECT_EQ(fixed.at(0.5, scene_camera, std::nullopt).focus_distance, 0.8);
}

TEST(CameraPath, ErrorsNameTheField) {
  const std::pair<const char*, const char*> bad[] = {
      {R"({"segments": []})", "'segments' must be a non-empty array"},
      {R"({"segments": [{"walk": "sideways", "distance": 1, "duration": 1}]})", "'segments[0].walk' must be forward, back, left, right, up or down, got \"sideways\""},
      {R"({"segments": [{"walk": "up", "duration": 1}]})", "needs a 'distance'"},
      {"{\"segments\": [{\"hold\": 1},\n {\"turn\": \"yaw\", \"degrees\": 10, \"duration\": 0}]}",
       "segments[1].duration must be in (0, 1e6] seconds (line 2, column"},
      {R"({"segments": [{"turn": "spin", "degrees": 1, "duration": 1}]})", "'segments[0].turn' must be yaw, pitch or roll, got \"spin\""},
      {R"({"segments": [{"hold": 1, "walk": "up"}]})", "segments[0]"},
      {R"({"segments": [{"jump": 1}]})", "must be a walk, a turn or a hold"},
      {R"({"start": {"fov": 200}, "segments": [{"hold": 1}]})", "start.fov"},
      {R"({"start": {"aperture": 3}, "segments": [{"hold": 1}]})", "start.aperture must be in [0, 1]"},
      {R"({"start": {"focus_distance": -1}, "segments": [{"hold": 1}]})", "start.focus_distance must be in (0, 100]"},
      {R"({"start": {"position": [0, 0, "x"]}, "segments": [{"hold": 1}]})", "start.position"},
      {R"({"segments": [{"hold": 1}], "speed": 2})", "unknown key 'speed'"},
      {R"({"segments": [{"walk": "forward", "distance": 1e300, "duration": 1}]})", "segments[0].distance must be within"},
      {"[1, 2", "malformed JSON"},
      // A string where a number belongs is shown as the string it is.
      {R"({"segments": [{"walk": "forward", "distance": 1, "duration": "4"}]})",
       "'segments[0].duration' must be a number, got \"4\""},
  };
  for (const auto& [text, expected] : bad) {
    try {
      sol::parse_camera_path(text, "p.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("p.json: ", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW(sol::load_camera_path("/nonexistent/path.json"), sol::InvalidArgument);
  EXPECT_THROW(sol::parse_camera_path(kPath).frame_count(0.0), sol::InvalidArgument);
}

}  // namespace
