#include "viewer_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <utility>

#include <sol/aim.hpp>
#include <sol/scene_file.hpp>

#include "command_line.hpp"
#include "output_file.hpp"

namespace sol::viewer {

const char* const kControls =
    "controls:\n"
    "  W / S          move forward / back along the geodesic you look along\n"
    "  A / D          move left / right along the geodesic in that direction\n"
    "  R / F          move up / down along the geodesic in that direction\n"
    "  Shift          move 5x faster\n"
    "  arrows, drag   turn (left mouse button held: drag to look around)\n"
    "  Q / E          roll left / right\n"
    "  Home           back to the scene's camera\n"
    "  Tab            next preset scene\n"
    "  T              stereo side by side on / off\n"
    "  Y              vsync on / off\n"
    "  + / -          render scale up / down (fixes the scale: adaptive off)\n"
    "  G              adaptive render scale on / off\n"
    "  P              screenshot to solview-NNNN.png (the frame as shown)\n"
    "  F1             the overlay panel on / off: scene, camera and render settings\n"
    "                 as live controls, fps and frame times, rays/s, mean steps, the\n"
    "                 observer's position and frame (in the quotient the copy of D it\n"
    "                 is in), screenshot, record, copy the camera as solrender options\n"
    "                 or the scene as JSON, save the scene, reset\n"
    "  F11            fullscreen on / off\n"
    "  H              print these controls\n"
    "  Esc            quit\n"
    "The frame is parallel-transported along every move; in the quotient\n"
    "(lattice-balls) the observer is teleported back into the fundamental domain.\n";

namespace {

Scene load(const std::string& name) {
  Scene scene = cli::scene_argument(name);
  validate(scene);
  return scene;
}

}  // namespace

ViewerState::ViewerState(std::vector<std::string> preset_names, std::function<std::string(const World&)> supported)
    : presets(std::move(preset_names)),
      // The default scene until set_scene (from a preset, out of line: GCC 12
      // warns of an uninitialised light when a default World is built inline).
      scene(preset_scene("plane")),
      good_world(scene),
      observer(observer_at(scene)),
      m_supported(std::move(supported)) {}

void ViewerState::set_scene(const std::string& name) {
  scene = load(name);
  good_world = scene;
  scene_name = name;
  observer = observer_at(scene);
  world_changed = true;
  ++world_version;
  watch(name);
}

void ViewerState::watch(const std::string& name) {
  m_watched.reset();
  std::error_code ec;
  const bool preset = std::find(presets.begin(), presets.end(), name) != presets.end();
  if (!preset && std::filesystem::is_regular_file(name, ec)) {
    const auto time = std::filesystem::last_write_time(name, ec);
    if (!ec) m_watched = time;
  }
}

// A file missing for a moment (an editor saving by rename) is waited for.
void ViewerState::poll_reload() {
  if (!m_watched) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < m_next_poll) return;
  m_next_poll = now + std::chrono::milliseconds(200);
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(scene_name, ec);
  if (ec || time == *m_watched) return;
  m_watched = time;
  try {
    const Scene fresh = load(scene_name);
    if (const std::string why = m_supported(fresh); !why.empty()) throw std::runtime_error(why);
    const bool camera_moved = fresh.camera.position != scene.camera.position ||
                              fresh.camera.forward != scene.camera.forward || fresh.camera.up != scene.camera.up;
    const bool quotient_changed = !same_space(fresh, scene);
    m_before_reload.emplace(scene, observer);
    scene = fresh;
    good_world = scene;
    world_changed = true;
    ++world_version;
    if (camera_moved || quotient_changed) observer = observer_at(scene);
    message = "reloaded " + scene_name;
    std::fprintf(stderr, "solview: reloaded %s\n", scene_name.c_str());
  } catch (const std::exception& e) {
    message = std::string(e.what()) + " (the last good scene stays)";
    std::fprintf(stderr, "solview: %s\n", message.c_str());
  }
}

void ViewerState::world_refused(const std::string& why, const World& last) {
  if (m_before_reload) {  // a reload: its camera goes too
    scene = m_before_reload->first;
    observer = m_before_reload->second;
    m_before_reload.reset();
  } else if (!same_space(last, scene)) {
    observer.bind(last.lattice());  // an edit's quotient undone
  }
  static_cast<World&>(scene) = last;
  good_world = last;
  world_changed = true;
  ++world_version;
  message = why + " (the last good scene stays)";
  std::fprintf(stderr, "solview: %s\n", message.c_str());
}

void ViewerState::world_edited() {
  try {
    validate(scene);
    if (const std::string why = m_supported(scene); !why.empty()) throw std::runtime_error(why);
    good_world = scene;
    world_changed = true;
    ++world_version;
    message.clear();
  } catch (const std::exception& e) {
    static_cast<World&>(scene) = good_world;
    message = e.what();
    std::fprintf(stderr, "solview: %s\n", e.what());
  }
  // The observer follows a change of quotient (bound to the new lattice or to none).
  const std::optional<Lattice> lattice = scene.lattice();
  const std::optional<Lattice>& bound = observer.lattice();
  if (bound.has_value() != lattice.has_value() ||
      (lattice && (bound->generators() != lattice->generators() || bound->monodromy() != lattice->monodromy()))) {
    observer.bind(lattice);
  }
}

void ViewerState::act(const PanelActions& a, int render_width, int render_height) {
  if (a.world_changed) world_edited();
  if (a.load) {
    try {
      set_scene(*a.load);
      message.clear();
    } catch (const std::exception& e) {
      message = e.what();
      std::fprintf(stderr, "solview: %s\n", e.what());
    }
  }
  if (a.reset) observer = observer_at(scene);
  if (a.look_at) {
    try {
      const Aim to = aim(observer.position(), *a.look_at, scene.lattice());
      observer.face(to.direction);
      // The lens focuses on the point (as a scene file's look_at without a focus distance).
      scene.camera.focus_distance = focus_on(to, scene.camera.focus_distance);
      message.clear();
    } catch (const std::exception& e) {  // the point at the eye, or no minimiser found
      message = std::string("look at: ") + e.what();
    }
  }
  if (a.screenshot) want_screenshot = true;
  if (a.toggle_recording) {
    if (!recording) {
      std::error_code ec;
      std::filesystem::create_directories(record_dir, ec);
      if (ec || !std::filesystem::is_directory(record_dir)) {
        message = record_dir + ": cannot create the directory";
        return;
      }
    }
    recording = !recording;
    message = recording ? "recording to " + record_dir + "/" : "recording stopped";
  }
  if (a.copy_options || a.copy_json) {
    const int eyes = stereo ? 2 : 1;
    clipboard = a.copy_options ? solrender_command(render_width / eyes, render_height) : scene_json();
    message = a.copy_options ? "solrender options copied (and printed)" : "scene JSON copied (and printed)";
  }
  if (a.save) {
    try {
      if (std::filesystem::is_directory(*a.save)) throw std::runtime_error(*a.save + ": it is a directory, not a file");
      programs::write_text_file(*a.save, scene_json());
      message = "saved " + *a.save;
    } catch (const std::exception& e) {
      message = e.what();
    }
  }
}

void ViewerState::set(Setting setting, double value) {
  switch (setting) {
    case Setting::Fov:
      if (!(value > 0.0 && value < 180.0)) return refuse("set fov: must be in (0, 180)", value);
      scene.camera.fov = value;
      return;
    case Setting::Scale:
      if (!(value > 0.0 && value <= 1.0)) return refuse("set scale: must be in (0, 1]", value);
      scale = value;
      adaptive = false;
      return;
    case Setting::Ipd:
      if (!(value >= 0.0 && value <= 10.0)) return refuse("set ipd: must be in [0, 10]", value);
      ipd = value;
      return;
    case Setting::Exposure:  // the display alone: the frame is not rendered again
      if (!(std::abs(value) <= Display::kMaxExposure)) return refuse("set exposure: must be in [-20, 20]", value);
      scene.display.exposure = value;
      return;
    case Setting::MaxDistance: scene.max_distance = value; break;
    case Setting::MaxSteps:
      if (value != std::floor(value) || value < 1 || value > 1e6) {
        return refuse("set max-steps: must be an integer in [1, 1000000]", value);
      }
      scene.max_steps = static_cast<int>(value);
      break;
    case Setting::HitEpsilon: scene.hit_epsilon = value; break;
  }
  world_edited();
}

void ViewerState::refuse(const std::string& what, double value) {
  message = what + ", got " + std::to_string(value);
  std::fprintf(stderr, "solview: %s\n", message.c_str());
}

std::array<double, 16> ViewerState::view_key(int width, int height) const {
  const glm::dvec3 p = observer.position(), f = observer.forward(), u = observer.up();
  return {p.x, p.y, p.z, f.x, f.y, f.z, u.x, u.y, u.z, scene.camera.fov, stereo ? ipd : -1.0,
          static_cast<double>(world_version), static_cast<double>(width), static_cast<double>(height),
          scene.camera.aperture, scene.camera.focus_distance};
}

Camera ViewerState::camera() const {
  Camera c = scene.camera;
  c.position = observer.position();
  c.forward = observer.forward();
  c.up = observer.up();
  return c;
}

std::string ViewerState::solrender_command(int width, int height) const {
  const Camera c = camera();
  char shown[96] = "";  // the display, where it is not the default
  if (scene.display != Display{}) {
    std::snprintf(shown, sizeof shown, " --exposure %.17g --tone %s", scene.display.exposure, tone_name(scene.display.tone));
  }
  char lens[96] = "";  // the lens, where there is one
  if (c.aperture > 0.0) std::snprintf(lens, sizeof lens, " --aperture %.17g --focus-distance %.17g", c.aperture, c.focus_distance);
  char text[1024];
  std::snprintf(text, sizeof text,
                "solrender --scene %s --width %d --height %d --fov %.17g --position %.17g,%.17g,%.17g "
                "--forward %.17g,%.17g,%.17g --up %.17g,%.17g,%.17g --max-distance %.17g --max-steps %d%s%s%s -o solview.png",
                scene_name.c_str(), width, height, c.fov, c.position.x, c.position.y, c.position.z, c.forward.x,
                c.forward.y, c.forward.z, c.up.x, c.up.y, c.up.z, scene.max_distance, scene.max_steps,
                stereo ? (" --stereo --ipd " + std::to_string(ipd)).c_str() : "",
                lens, shown);
  return text;
}

std::string ViewerState::scene_json() const {
  Scene s = scene;
  s.camera = camera();
  return to_json(s);
}

std::vector<Camera> ViewerState::cameras() const {
  const Camera c = camera();
  if (!stereo) return {c};
  const StereoEyes eyes = stereo_eyes(c, ipd);
  return {eyes.left, eyes.right};
}

void ViewerState::press(Key k) {
  switch (k) {
    case Key::Home: observer = observer_at(scene); break;
    case Key::Tab: {
      if (presets.empty()) break;
      auto it = std::find(presets.begin(), presets.end(), scene_name);
      const std::size_t next = it == presets.end() ? 0 : (static_cast<std::size_t>(it - presets.begin()) + 1) % presets.size();
      set_scene(presets[next]);
      break;
    }
    case Key::T: stereo = !stereo; break;
    case Key::Y: vsync = !vsync; want_swapchain = true; break;
    case Key::G: adaptive = !adaptive; break;
    case Key::Plus: adaptive = false; scale = std::min(1.0, scale * 1.25); break;
    case Key::Minus: adaptive = false; scale = std::max(min_scale, scale / 1.25); break;
    case Key::P: want_screenshot = true; break;
    case Key::H: std::printf("%s", kControls); std::fflush(stdout); break;
    case Key::F1: want_overlay_toggle = true; break;
    case Key::F11: want_fullscreen_toggle = true; break;
    case Key::Escape: quit = true; break;
    default: break;
  }
}

void ViewerState::key(Key k, bool down) {
  if (down && !controls.held(k)) press(k);
  controls.key(k, down);
}

}  // namespace sol::viewer
