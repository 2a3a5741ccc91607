// solview's application state, without a window: the scene and its last
// good world, the observer, the render settings, the overlay panel's
// actions and a script's settings, the keys that act on press, hot reload
// of a scene file, and what the frame shows (its cameras, the key that
// restarts progressive refinement, the camera as solrender options or as
// scene JSON). What needs the window (clipboard, fullscreen, the overlay
// itself) it asks for through its requests, which solview.cpp carries out.
// tests/viewer_state_test.cpp holds it to its behaviour; docs/solview.md.
#pragma once

#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <sol/observer.hpp>
#include <sol/scene.hpp>

#include "controls.hpp"
#include "panel.hpp"

namespace sol::viewer {

class ViewerState {
 public:
  /// `presets`: those Tab cycles through (solview: the presets the kernel
  /// renders); `supported`: "" when the renderer draws a world, else why
  /// not (refused like an invalid one).
  ViewerState(std::vector<std::string> presets, std::function<std::string(const World&)> supported);

  // ---- The scene
  /// Loads a preset or scene file (sol::cli::scene_argument), validates it,
  /// puts the observer at its camera and watches the file for changes.
  /// Throws what loading throws (the state stays as it was).
  void set_scene(const std::string& name);
  /// Hot reload, every 0.2 s at most: a scene file that changed on disk is
  /// read again; a good one replaces the world (the observer stays unless
  /// its camera or quotient changed), a bad one leaves the last good world
  /// and says why in `message` (and on stderr).
  void poll_reload();
  /// After an edit of the world (the panel, a script's set): prepared again
  /// when it validates, else the last good world comes back and `message`
  /// says why. The observer follows a change of quotient.
  void world_edited();
  /// The renderer could not prepare the world that validated (a
  /// monodromy whose lattice needs over a million words, say): `last`, the
  /// world it holds, stays (scene and good_world), and the message says why.
  void world_refused(const std::string& why, const World& last);
  /// The renderer prepared the world: a later refusal no longer undoes the
  /// reload before it.
  void world_prepared() { m_before_reload.reset(); }

  // ---- Input
  /// What the panel asked for besides its edits in place (the render's
  /// size for the solrender options it may copy).
  void act(const PanelActions& actions, int render_width, int render_height);
  /// A script's `set NAME VALUE`: what the panel's control of that name does.
  void set(Setting setting, double value);
  /// A key going down or up: keys with an effect act on press, the held
  /// ones move the observer in Controls::step.
  void key(Key k, bool down);

  // ---- What the frame shows
  /// The current camera: the observer's, with the scene's fov.
  Camera camera() const;
  /// The cameras of this frame: the observer's (both eyes in stereo).
  std::vector<Camera> cameras() const;
  /// What the frame shows, for progressive refinement: any change restarts
  /// it (not the render scale: a refined frame is at full resolution).
  std::array<double, 16> view_key(int width, int height) const;
  /// The current camera as solrender options, rendering width × height per eye.
  std::string solrender_command(int width, int height) const;
  /// The scene seen from the current camera, as JSON.
  std::string scene_json() const;

  // ---- The state (read and set by the frame loop and the panel)
  std::vector<std::string> presets;
  Scene scene;
  World good_world;            ///< the last world that validated: edits fall back to it
  std::string scene_name;
  bool world_changed = true;   ///< the renderer needs set_world(scene) before the next frame
  long world_version = 0;      ///< counts the worlds shown (a change restarts refinement)
  std::string message;         ///< the last error or notice, for the panel (empty: none)
  Observer observer;
  Controls controls;
  double scale = 1.0, min_scale = 0.05, ipd = 0.064, target_fps = 20.0;
  bool adaptive = false, stereo = false, vsync = true;
  bool recording = false;
  std::string record_dir = "solview-recording";

  // ---- Requests to the window's side, each cleared by whoever carries it out
  bool want_screenshot = false;
  bool want_swapchain = false;         ///< the presentation changed (vsync, fullscreen): rebuild the swapchain
  bool want_fullscreen_toggle = false;
  bool want_overlay_toggle = false;
  bool quit = false;
  std::optional<std::string> clipboard;  ///< text to put on the clipboard (and print)

 private:
  void press(Key k);
  void refuse(const std::string& what, double value);
  void watch(const std::string& name);

  std::function<std::string(const World&)> m_supported;
  std::optional<std::filesystem::file_time_type> m_watched;  ///< the file's time when last read (none: a preset)
  std::chrono::steady_clock::time_point m_next_poll{};
  /// The scene and observer a reload replaced, until the renderer prepares
  /// the reloaded world (world_refused puts them back).
  std::optional<std::pair<Scene, Observer>> m_before_reload;
};

/// solview's help on its keys (H prints it).
extern const char* const kControls;

}  // namespace sol::viewer
