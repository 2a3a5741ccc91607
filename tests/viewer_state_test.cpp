// solview's state without a window (viewer/viewer_state.hpp): scenes and the
// last good world, a script's settings and their refusals, the keys that act
// on press, the cameras of a frame, the key that restarts refinement, the
// camera as solrender options and as scene JSON (read back by the scene
// parser), saving, aiming at a point, and hot reload of a scene file.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "viewer_state.hpp"

namespace {

using sol::viewer::Key;
using sol::viewer::Setting;
using sol::viewer::ViewerState;

// A state over three presets whose renderer refuses worlds of more than 1000 steps.
ViewerState make_state() {
  return ViewerState({"plane", "sandwich", "lattice-balls"}, [](const sol::World& w) {
    return w.max_steps > 1000 ? std::string("max_steps: this renderer takes at most 1000") : std::string();
  });
}

void tap(ViewerState& s, Key k) {
  s.key(k, true);
  s.key(k, false);
}

// A fresh folder under the system's temporary one.
std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("viewer_state_test-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ViewerState, SetSceneStartsAtItsCamera) {
  ViewerState s = make_state();
  s.set_scene("sandwich");
  const sol::Scene preset = sol::preset_scene("sandwich");
  EXPECT_EQ(s.scene_name, "sandwich");
  EXPECT_EQ(s.observer.position(), preset.camera.position);
  EXPECT_TRUE(s.world_changed);
  EXPECT_EQ(s.world_version, 1);
  EXPECT_FALSE(s.observer.lattice().has_value());
  s.set_scene("lattice-balls");
  EXPECT_TRUE(s.observer.lattice().has_value());  // bound to the world's lattice
  EXPECT_EQ(s.world_version, 2);
  EXPECT_THROW(s.set_scene("no-such-preset"), sol::InvalidArgument);
  EXPECT_EQ(s.scene_name, "lattice-balls");  // unchanged
}

TEST(ViewerState, LookAtTurnsTheObserverTowardsThePoint) {
  ViewerState s = make_state();
  s.set_scene("lattice-balls");  // in the golden quotient: the nearest image
  const glm::dvec3 target(2.6, -1.9, 1.1);
  s.act({.look_at = target}, 64, 48);
  EXPECT_TRUE(s.message.empty()) << s.message;
  const sol::Aim a = sol::aim(s.observer.position(), target, s.scene.lattice());
  EXPECT_LT(glm::length(s.observer.forward() - a.direction), 1e-12);
  s.act({.look_at = s.observer.position()}, 64, 48);  // no direction: refused, the camera kept
  EXPECT_NE(s.message.find("look at: "), std::string::npos);
  EXPECT_LT(glm::length(s.observer.forward() - a.direction), 1e-12);
}

TEST(ViewerState, BadEditsFallBackToTheLastGoodWorld) {
  ViewerState s = make_state();
  s.set_scene("plane");
  s.world_changed = false;
  s.scene.hit_epsilon = -1.0;  // invalid
  s.world_edited();
  EXPECT_EQ(s.scene.hit_epsilon, sol::preset_scene("plane").hit_epsilon);
  EXPECT_NE(s.message.find("hit_epsilon"), std::string::npos) << s.message;
  EXPECT_FALSE(s.world_changed);
  EXPECT_EQ(s.world_version, 1);
  s.scene.max_steps = 2000;  // valid, but the renderer refuses it
  s.world_edited();
  EXPECT_EQ(s.scene.max_steps, sol::preset_scene("plane").max_steps);
  EXPECT_NE(s.message.find("at most 1000"), std::string::npos) << s.message;
  s.scene.fog_density = 0.1;  // good
  s.world_edited();
  EXPECT_TRUE(s.world_changed);
  EXPECT_EQ(s.world_version, 2);
  EXPECT_TRUE(s.message.empty());
  EXPECT_EQ(s.good_world.fog_density, 0.1);
}

// Another monodromy (the panel's): the observer binds to the new lattice
// and is in its domain at once, its frame turned where the new lattice's
// teleport turns; back to Sol it is unbound.
TEST(ViewerState, AnotherMonodromyRebindsTheObserver) {
  ViewerState s = make_state();
  s.set_scene("plane");  // in Sol, the observer at (0, 0, 1.5): above the new lattice's domain (h = ln(2 + √3) = 1.32)
  const glm::dvec3 far_forward = s.observer.forward(), far_up = s.observer.up();
  sol::set_space(s.scene, sol::MonodromySpace{{-3, -1, -2, -1}});
  s.world_edited();
  EXPECT_TRUE(s.message.empty()) << s.message;
  ASSERT_TRUE(s.observer.lattice().has_value());
  const sol::Lattice lattice = *s.scene.lattice();
  EXPECT_TRUE(s.observer.lattice()->turns());
  EXPECT_EQ(s.observer.lattice()->generators(), lattice.generators());
  EXPECT_TRUE(lattice.contains(s.observer.position()));
  EXPECT_EQ(s.world_version, 2);
  // The observer at the preset's camera, moved into the new domain by γ3⁻¹
  // (which turns): its copy's word takes it back there, position and frame.
  const sol::LatticeWord w = s.observer.copy();
  const bool turned = w.c % 2 != 0;
  EXPECT_TRUE(turned);
  EXPECT_LT(glm::length(lattice.apply(w, s.observer.position()) - sol::preset_scene("plane").camera.position), 1e-12);
  EXPECT_LT(glm::length(sol::half_turn(s.observer.forward()) - far_forward), 1e-12);
  EXPECT_LT(glm::length(sol::half_turn(s.observer.up()) - far_up), 1e-12);
  EXPECT_LT(s.observer.up().y, -0.99);  // (0, 1, 0) turned
  // A matrix that is not hyperbolic is refused by set_space itself (the panel shows why).
  EXPECT_THROW(sol::set_space(s.scene, sol::MonodromySpace{{1, 1, 0, 1}}), sol::InvalidArgument);
  sol::set_space(s.scene, sol::SolSpace{});
  s.world_edited();
  EXPECT_FALSE(s.observer.lattice().has_value());
}

TEST(ViewerState, SettingsApplyOrAreRefusedByName) {
  ViewerState s = make_state();
  s.set_scene("plane");
  s.set(Setting::Fov, 200.0);
  EXPECT_NE(s.message.find("set fov: must be in (0, 180)"), std::string::npos) << s.message;
  EXPECT_EQ(s.scene.camera.fov, sol::preset_scene("plane").camera.fov);
  s.set(Setting::Fov, 60.0);
  EXPECT_EQ(s.scene.camera.fov, 60.0);
  s.set(Setting::MaxSteps, 2.5);
  EXPECT_NE(s.message.find("set max-steps"), std::string::npos) << s.message;
  s.set(Setting::MaxSteps, 50.0);
  EXPECT_EQ(s.scene.max_steps, 50);
  EXPECT_EQ(s.world_version, 2);  // a world setting prepares the world again
  s.adaptive = true;
  s.set(Setting::Scale, 0.5);
  EXPECT_EQ(s.scale, 0.5);
  EXPECT_FALSE(s.adaptive);
  s.set(Setting::Ipd, 11.0);
  EXPECT_EQ(s.ipd, 0.064);
  s.set(Setting::Ipd, 0.2);
  EXPECT_EQ(s.ipd, 0.2);
  // The exposure is the display's: the world is not prepared again; it
  // reaches the copied options (solrender's 8-bit file shows the same).
  s.set(Setting::Exposure, 25.0);
  EXPECT_NE(s.message.find("set exposure: must be in [-20, 20]"), std::string::npos) << s.message;
  s.set(Setting::Exposure, -1.5);
  EXPECT_EQ(s.scene.display.exposure, -1.5);
  EXPECT_EQ(s.world_version, 2);
  s.act({.copy_options = true}, 64, 48);
  ASSERT_TRUE(s.clipboard.has_value());
  EXPECT_NE(s.clipboard->find(" --exposure -1.5 --tone clamp -o"), std::string::npos) << *s.clipboard;
}

TEST(ViewerState, KeysActOnceOnPress) {
  ViewerState s = make_state();
  s.set_scene("plane");
  tap(s, Key::Tab);
  EXPECT_EQ(s.scene_name, "sandwich");
  tap(s, Key::Tab);
  tap(s, Key::Tab);
  EXPECT_EQ(s.scene_name, "plane");  // wraps around
  // A key held (down twice, as auto-repeat reports it) acts once.
  s.key(Key::T, true);
  s.key(Key::T, true);
  s.key(Key::T, false);
  EXPECT_TRUE(s.stereo);
  tap(s, Key::Minus);
  EXPECT_DOUBLE_EQ(s.scale, 1.0 / 1.25);
  for (int i = 0; i < 200; ++i) tap(s, Key::Minus);
  EXPECT_EQ(s.scale, s.min_scale);
  for (int i = 0; i < 200; ++i) tap(s, Key::Plus);
  EXPECT_EQ(s.scale, 1.0);
  tap(s, Key::Y);
  EXPECT_FALSE(s.vsync);
  EXPECT_TRUE(s.want_swapchain);
  tap(s, Key::F1);
  tap(s, Key::F11);
  tap(s, Key::P);
  EXPECT_TRUE(s.want_overlay_toggle && s.want_fullscreen_toggle && s.want_screenshot);
  EXPECT_FALSE(s.quit);
  tap(s, Key::Escape);
  EXPECT_TRUE(s.quit);
}

TEST(ViewerState, CamerasFollowTheObserverAndStereo) {
  ViewerState s = make_state();
  s.set_scene("sandwich");
  const auto still = s.view_key(64, 48);
  EXPECT_EQ(s.view_key(64, 48), still);
  s.scale = 0.5;
  EXPECT_EQ(s.view_key(64, 48), still);  // the scale is not what the frame shows
  EXPECT_NE(s.view_key(64, 32), still);
  s.observer.move({0.0, 0.0, 1.0}, 0.5);
  EXPECT_NE(s.view_key(64, 48), still);
  const sol::Camera moved = s.camera();
  EXPECT_EQ(moved.position, s.observer.position());
  EXPECT_EQ(moved.fov, s.scene.camera.fov);
  ASSERT_EQ(s.cameras().size(), 1u);
  s.stereo = true;
  s.ipd = 0.3;
  const std::vector<sol::Camera> eyes = s.cameras();
  const sol::StereoEyes expected = sol::stereo_eyes(moved, 0.3);
  ASSERT_EQ(eyes.size(), 2u);
  EXPECT_EQ(eyes[0].position, expected.left.position);
  EXPECT_EQ(eyes[1].position, expected.right.position);
  tap(s, Key::Home);
  EXPECT_EQ(s.observer.position(), sol::preset_scene("sandwich").camera.position);
}

TEST(ViewerState, CopiesTheCameraAsOptionsAndJsonAndSaves) {
  ViewerState s = make_state();
  s.set_scene("plane");
  s.observer.move({0.0, 0.0, 1.0}, 0.25);
  s.act({.copy_options = true}, 64, 48);
  ASSERT_TRUE(s.clipboard.has_value());
  // The position printed to 17 digits reads back exactly.
  const std::string options = *s.clipboard;
  const std::size_t at = options.find("--position ");
  ASSERT_NE(at, std::string::npos) << options;
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(options.c_str() + at, "--position %lf,%lf,%lf", &x, &y, &z), 3) << options;
  EXPECT_EQ(glm::dvec3(x, y, z), s.observer.position());
  EXPECT_NE(options.find("--width 64 --height 48"), std::string::npos) << options;
  s.clipboard.reset();
  s.act({.copy_json = true}, 64, 48);
  ASSERT_TRUE(s.clipboard.has_value());
  const sol::Scene back = sol::parse_scene(*s.clipboard);
  EXPECT_EQ(back.camera.position, s.observer.position());
  EXPECT_EQ(back.objects.size(), s.scene.objects.size());
  const auto dir = scratch("save");
  s.act({.save = (dir / "scene.json").string()}, 64, 48);
  EXPECT_EQ(s.message, "saved " + (dir / "scene.json").string());
  EXPECT_EQ(sol::load_scene((dir / "scene.json").string()).camera.position, s.observer.position());
  s.act({.save = dir.string()}, 64, 48);
  EXPECT_NE(s.message.find("it is a directory"), std::string::npos) << s.message;
  std::filesystem::remove_all(dir);
}

TEST(ViewerState, ReloadsAChangedSceneFileAndKeepsTheLastGoodOne) {
  const auto dir = scratch("reload");
  const std::string path = (dir / "scene.json").string();
  sol::Scene scene = sol::preset_scene("plane");
  auto write = [&](const std::string& text) {
    std::ofstream(path) << text;
    // A later modification time than the one read (file systems with coarse times).
    static int bump = 0;
    std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now() + std::chrono::seconds(++bump));
  };
  write(sol::to_json(scene));
  ViewerState s = make_state();
  s.set_scene(path);
  const glm::dvec3 start = s.observer.position();
  s.observer.move({1.0, 0.0, 0.0}, 0.5);
  const glm::dvec3 walked = s.observer.position();
  s.poll_reload();  // nothing changed
  EXPECT_EQ(s.world_version, 1);
  scene.fog_density = 0.2;  // the world changes, the camera does not: the observer stays
  write(sol::to_json(scene));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));  // past the 0.2 s between polls
  s.poll_reload();
  EXPECT_EQ(s.world_version, 2);
  EXPECT_EQ(s.scene.fog_density, 0.2);
  EXPECT_EQ(s.observer.position(), walked);
  EXPECT_EQ(s.message, "reloaded " + path);
  write("{\"objects\": [{\"type\": \"plane_z\", \"c\": \"high\"}]}");  // bad
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  s.poll_reload();
  EXPECT_EQ(s.world_version, 2);
  EXPECT_EQ(s.scene.fog_density, 0.2);
  EXPECT_NE(s.message.find("the last good scene stays"), std::string::npos) << s.message;
  scene.camera.position = {0.0, 0.0, 2.0};  // the camera moves: so does the observer
  write(sol::to_json(scene));
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  s.poll_reload();
  EXPECT_EQ(s.observer.position(), glm::dvec3(0.0, 0.0, 2.0));
  EXPECT_NE(s.observer.position(), start);
  std::filesystem::remove_all(dir);
}

}  // namespace
