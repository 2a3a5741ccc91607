// solview: the real-time viewer. A GLFW window that shows the march kernel's
// image of a Sol scene (presenter.hpp puts the frames on the screen), and
// controls to walk along geodesics (controls.hpp). This file is the
// application: options, the scene and its world (prepared once per scene by
// the renderer), input, the adaptive render scale, screenshots and the
// frame loop. See docs/solview.md.
//
//   solview --scene sandwich
//   solview --scene plane --size 320x180 --frames 60 --screenshot last.png
#include <GLFW/glfw3.h>  // after vulkan_core.h (GLFW_INCLUDE_VULKAN is defined by CMake)

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <sol/sol.hpp>
#include <sol/vk/buffer.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/error.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/march.hpp>
#include <sol/vk/pipeline.hpp>

#include "adaptive_scale.hpp"
#include "command_line.hpp"
#include "controls.hpp"
#include "image_file.hpp"
#include "output_file.hpp"
#include "overlay.hpp"
#include "panel.hpp"
#include "presenter.hpp"
#include "refinement.hpp"
#include "viewer_state.hpp"

namespace {

using sol::viewer::Key;

struct Options {
  std::string scene = "plane";
  int width = 640, height = 360;
  double scale = 1.0, min_scale = 0.05, ipd = 0.064;
  std::optional<double> target_fps;
  std::string vsync = "on", present = "auto", overlay = "off";
  bool fullscreen = false, stereo = false, validation = false, stats = false;
  long frames = 0;  // 0: until the window closes
  int refine = 16;  // samples per pixel a still view accumulates (0: off)
  bool refine_paths = false;  // the refinement's samples are paths (path tracing)
  std::string screenshot, script, record, state;
};

// The command line; exits 0 after --help and 2 on bad usage.
void add_options(sol::cli::CommandLine& cl, Options& o) {
  cl.add_text("--scene", o.scene, "NAME|FILE", "a preset (" + sol::cli::preset_list() + ") or a JSON scene file (default plane)");
  cl.add_value("--size", "WxH", "window size in pixels (default 640x360)", [&cl, &o](const std::string& v) {
    const auto x = v.find('x');
    if (x == std::string::npos) cl.fail("option --size expects WxH like 640x360, got '" + v + "'");
    o.width = static_cast<int>(cl.integer(v.substr(0, x), "--size (width)", 1, 16384));
    o.height = static_cast<int>(cl.integer(v.substr(x + 1), "--size (height)", 1, 16384));
  });
  cl.add_number("--scale", o.scale, "S", "render at S times the window size, (0, 1] (default 1), then upscale",
                sol::cli::in_unit_interval());
  cl.add_number("--target-fps", o.target_fps, "F", "adapt the render scale to hold F frames per second", sol::cli::positive());
  cl.add_number("--min-scale", o.min_scale, "S", "lowest adaptive scale, (0, 1] (default 0.05)", sol::cli::in_unit_interval());
  cl.add_integer("--refine", o.refine, 0, 4096, "N",
                 "when the view has not changed for 0.25 s: render at full resolution, then accumulate up to N "
                 "jittered samples per pixel (anti-aliasing, as solrender --spp N); any change starts again at the "
                 "moving scale; 0: off (default 16)");
  cl.add_flag("--refine-paths", o.refine_paths,
              "refine by path tracing: each of the --refine samples is one path per pixel (solrender --transport path: "
              "diffuse interreflection, glowing objects, mirrors, no ambient light; docs/lighting.md), while the "
              "moving view stays direct light");
  cl.add_choice("--vsync", o.vsync, {"on", "off"}, "wait for the display's refresh (default on)");
  cl.add_choice("--present", o.present, {"auto", "blit"},
                "auto (default): the kernel writes straight into the swapchain image at render scale 1 when the surface "
                "allows it; blit: always through an RGBA float image and a blit");
  cl.add_flag("--fullscreen", o.fullscreen, "start fullscreen");
  cl.add_choice("--overlay", o.overlay, {"on", "off"},
                "the overlay panel (F1) at the start; on: also in screenshots and recorded frames, which "
                "otherwise leave it out (default off)");
  cl.add_flag("--stereo", o.stereo, "both eyes side by side (each eye half the width)");
  cl.add_number("--ipd", o.ipd, "D", "eye separation in Sol units, [0, 10] (default 0.064)", sol::cli::in_range(0.0, 10.0));
  cl.add_integer("--frames", o.frames, 1, 100000000, "N", "exit after N frames");
  cl.add_text("--screenshot", o.screenshot, "FILE", "at exit, write the last frame as shown (window size) to FILE");
  cl.add_text("--script", o.script, "FILE",
              "replay timed inputs: lines 'TIME down KEY', 'TIME up KEY', 'TIME mouse DX DY', 'TIME set NAME VALUE' "
              "(a panel setting: " + sol::viewer::setting_names() + "), 'TIME button NAME' (a panel button: " +
                  sol::viewer::button_names() + "); TIME in seconds; replays step 1/60 s per frame");
  cl.add_text("--record", o.record, "DIR",
              "write every frame as DIR/frame-NNNNNN.png (the panel's record button starts and stops it; "
              "without --record it writes to solview-recording/)");
  cl.add_text("--state", o.state, "FILE", "at exit, write the observer's position and frame to FILE");
  cl.add_flag("--validation", o.validation, "enable the Vulkan validation layer; its errors make the exit status 3");
  cl.add_flag("--stats", o.stats,
              "print at exit 'mono frames: N, mean X ms, p99 Y ms, missed Z' ('stereo' with --stereo): the time "
              "between rendered frames' ends on the device; missed: device work plus host recording over the "
              "period of --target-fps, else of the display's refresh");
  cl.set_footer(std::string(sol::viewer::kControls) + "\nScript key names: " + sol::viewer::key_names() +
                ".\n\nExit status: 0 on success, 1 when no window can be opened (no display), 2 for bad options,\n"
                "3 for validation errors, 4 for other failures.");
}

std::optional<Key> key_of(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_W: return Key::W;
    case GLFW_KEY_S: return Key::S;
    case GLFW_KEY_A: return Key::A;
    case GLFW_KEY_D: return Key::D;
    case GLFW_KEY_R: return Key::R;
    case GLFW_KEY_F: return Key::F;
    case GLFW_KEY_Q: return Key::Q;
    case GLFW_KEY_E: return Key::E;
    case GLFW_KEY_UP: return Key::Up;
    case GLFW_KEY_DOWN: return Key::Down;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_LEFT_SHIFT:
    case GLFW_KEY_RIGHT_SHIFT: return Key::Shift;
    case GLFW_KEY_TAB: return Key::Tab;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_T: return Key::T;
    case GLFW_KEY_Y: return Key::Y;
    case GLFW_KEY_P: return Key::P;
    case GLFW_KEY_H: return Key::H;
    case GLFW_KEY_G: return Key::G;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD: return Key::Plus;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT: return Key::Minus;
    case GLFW_KEY_F1: return Key::F1;
    case GLFW_KEY_F11: return Key::F11;
    case GLFW_KEY_ESCAPE: return Key::Escape;
    default: return std::nullopt;
  }
}

std::string glfw_error;
void on_glfw_error(int, const char* description) { glfw_error = description ? description : "unknown GLFW error"; }

// The viewer: its window-free state (viewer_state.hpp) and what the window
// side holds, reached by the callbacks through the window's user pointer.
struct App : sol::viewer::ViewerState {
  App()
      : ViewerState(
            [] {  // the presets the kernel renders (MarchRenderer::supports)
              std::vector<std::string> names;
              for (const std::string& n : sol::preset_names()) {
                if (sol::vk::MarchRenderer::supports(sol::preset_scene(n))) names.push_back(n);
              }
              return names;
            }(),
            [this](const sol::World& world) {
              // (Called once the options are read: paths refine a still view with --refine-paths.)
              return sol::vk::MarchRenderer::unsupported(world, options.refine_paths ? sol::Transport::Path
                                                                                     : sol::Transport::Direct);
            }) {}

  sol::cli::CommandLine command_line{"solview", "[options]",
                                     "Walks through Thurston's Sol geometry in a window: every pixel follows a Sol "
                                     "geodesic."};
  Options options;
  // The overlay panel (F1): shown, taken into screenshots (--overlay on), its text fields.
  sol::viewer::Overlay* overlay = nullptr;
  bool overlay_visible = false, overlay_in_capture = false;
  sol::viewer::PanelText panel_text;
  double fps = 0.0;
  std::vector<float> frame_ms;  // the last frames' times for the panel's graph
  bool fullscreen = false;
  int screenshots = 0;
  bool dragging = false;
  double last_x = 0, last_y = 0;
  int windowed[4] = {0, 0, 640, 360};
  GLFWwindow* window = nullptr;

  // The state's requests that need the window.
  void carry_out_requests() {
    if (want_fullscreen_toggle) {
      want_fullscreen_toggle = false;
      toggle_fullscreen();
    }
    if (want_overlay_toggle) {
      want_overlay_toggle = false;
      if (overlay) {
        overlay_visible = !overlay_visible;
      } else {
        std::fprintf(stderr, "solview: the overlay cannot be drawn on this window's surface\n");
      }
    }
    if (clipboard) {
      if (window) glfwSetClipboardString(window, clipboard->c_str());
      std::printf("%s\n", clipboard->c_str());
      std::fflush(stdout);
      clipboard.reset();
    }
  }
  void toggle_fullscreen() {
    if (!window) return;
    fullscreen = !fullscreen;
    if (fullscreen) {
      glfwGetWindowPos(window, &windowed[0], &windowed[1]);
      glfwGetWindowSize(window, &windowed[2], &windowed[3]);
      GLFWmonitor* monitor = glfwGetPrimaryMonitor();
      const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
      if (mode) glfwSetWindowMonitor(window, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
    } else {
      glfwSetWindowMonitor(window, nullptr, windowed[0], windowed[1], windowed[2], windowed[3], 0);
    }
    want_swapchain = true;
  }
};

App& app_of(GLFWwindow* w) { return *static_cast<App*>(glfwGetWindowUserPointer(w)); }

// SIGINT, SIGTERM, SIGHUP end the session as Esc does (the screenshot, the
// state and the validation report are written); a second one ends it at
// once, through the handler install_signal_cleanup() set (no partial files).
volatile std::sig_atomic_t g_stop_signal = 0;
struct sigaction g_cleanup_action[3];
constexpr int kStopSignals[3] = {SIGINT, SIGTERM, SIGHUP};

void stop_on_signal(int signal) {
  for (int i = 0; i < 3; ++i) {
    if (kStopSignals[i] != signal) continue;
    if (g_stop_signal != 0) {
      sigaction(signal, &g_cleanup_action[i], nullptr);
      std::raise(signal);
    }
  }
  g_stop_signal = signal;
}

void install_stop_on_signal() {
  for (int i = 0; i < 3; ++i) {
    sigaction(kStopSignals[i], nullptr, &g_cleanup_action[i]);
    if (g_cleanup_action[i].sa_handler == SIG_IGN) continue;  // ignored by whoever started us: stays so
    struct sigaction action {};
    action.sa_handler = stop_on_signal;
    sigemptyset(&action.sa_mask);
    sigaction(kStopSignals[i], &action, nullptr);
  }
}

std::string frame_name(const std::string& dir, long frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame-%06ld.png", frame);
  return (std::filesystem::path(dir) / buf).string();
}

void write_state(const std::string& path, const sol::Observer& o, long frames) {
  std::string text;
  char line[256];
  auto row = [&](const char* name, const glm::dvec3& v) {
    std::snprintf(line, sizeof line, "%s %.17g %.17g %.17g\n", name, v.x, v.y, v.z);
    text += line;
  };
  row("position", o.position());
  row("forward", o.forward());
  row("up", o.up());
  std::snprintf(line, sizeof line, "frames %ld\n", frames);
  text += line;
  sol::programs::write_text_file(path, text);
}

// Loads --script and refuses the files written at exit (or their folder),
// before a window opens.
std::vector<sol::viewer::ScriptEvent> prepare_files(App& app) {
  const Options& opt = app.options;
  const sol::cli::CommandLine& cl = app.command_line;
  std::vector<sol::viewer::ScriptEvent> script;
  if (!opt.script.empty()) {
    try {
      script = sol::viewer::load_script(opt.script);
    } catch (const std::exception& e) {
      cl.fail(e.what());
    }
  }
  if (!opt.screenshot.empty() && !sol::programs::can_write(opt.screenshot)) {
    cl.fail("--screenshot " + opt.screenshot + ": no image format for this file name extension");
  }
  for (const auto& [option, path] : {std::pair{"--screenshot", opt.screenshot}, std::pair{"--state", opt.state}}) {
    if (!path.empty() && std::filesystem::is_directory(path)) cl.fail(std::string(option) + " " + path + ": it is a directory, not a file");
  }
  if (!opt.record.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(opt.record, ec);
    if (ec || !std::filesystem::is_directory(opt.record)) cl.fail("--record " + opt.record + ": cannot create the directory");
    app.record_dir = opt.record;
    app.recording = true;
  }
  return script;
}

// GLFW for the session; no display is exit status 1.
struct GlfwSession {
  explicit GlfwSession(const sol::cli::CommandLine& cl) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
      cl.fail("cannot open a window: " + glfw_error +
                  (std::getenv("DISPLAY") ? "" : " (DISPLAY is not set: run under a display or xvfb-run)"),
              1);
    }
    if (!glfwVulkanSupported()) {
      glfwTerminate();
      cl.fail("cannot open a window: GLFW finds no Vulkan loader", 1);
    }
  }
  ~GlfwSession() { glfwTerminate(); }
  GlfwSession(const GlfwSession&) = delete;
  GlfwSession& operator=(const GlfwSession&) = delete;
};

// The Vulkan context: the instance extensions GLFW presents with, a swapchain.
sol::vk::ContextOptions context_options(const Options& opt, const sol::cli::CommandLine& cl) {
  sol::vk::ContextOptions options;
  options.pipeline_cache_dir = sol::vk::default_pipeline_cache_dir();  // compiled kernels kept between runs
  options.validation = opt.validation;
  std::uint32_t n_ext = 0;
  const char** ext = glfwGetRequiredInstanceExtensions(&n_ext);
  if (!ext) cl.fail("cannot open a window: GLFW cannot present Vulkan images here (" + glfw_error + ")", 1);
  for (std::uint32_t i = 0; i < n_ext; ++i) options.instance_extensions.emplace_back(ext[i]);
  options.device_extensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  return options;
}

// The window and its input. During a replay live input is ignored: the
// script alone moves the observer.
class Window {
 public:
  Window(App& app, bool replay) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(app.options.width, app.options.height, "solview", nullptr, nullptr);
    if (!window_) app.command_line.fail("cannot open a window: " + glfw_error, 1);
    app.window = window_;
    glfwSetWindowUserPointer(window_, &app);
    if (app.options.fullscreen) app.toggle_fullscreen();
    if (!replay) take_input();
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { app_of(w).want_swapchain = true; });
  }
  ~Window() { glfwDestroyWindow(window_); }
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;
  GLFWwindow* get() const { return window_; }

 private:
  void take_input() {
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
      App& a = app_of(w);
      // Typing into the panel's fields is not walking.
      const bool panel_typing = a.overlay && a.overlay_visible && a.overlay->wants_keyboard();
      if (auto k = key_of(key); k && action != GLFW_REPEAT && (!panel_typing || action == GLFW_RELEASE)) {
        a.key(*k, action == GLFW_PRESS);
      }
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      App& a = app_of(w);
      if (action == GLFW_PRESS && a.overlay && a.overlay_visible && a.overlay->wants_mouse()) return;  // the panel's
      a.dragging = action == GLFW_PRESS;
      glfwGetCursorPos(w, &a.last_x, &a.last_y);
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      App& a = app_of(w);
      if (a.dragging) a.controls.mouse(x - a.last_x, y - a.last_y);
      a.last_x = x;
      a.last_y = y;
    });
  }

  GLFWwindow* window_ = nullptr;
};

// --script: its events carried out at their times, the replay stepping
// fixed 1/60 s per frame (deterministic).
class Replay {
 public:
  // `active`: --script was given (its events may be none).
  Replay(std::vector<sol::viewer::ScriptEvent> script, bool active) : script_(std::move(script)), active_(active) {}
  bool active() const { return active_; }

  // The events up to frame `frame`'s time; `size` is the window's, for the panel's buttons.
  void step(App& app, long frame, VkExtent2D size) {
    const double t = static_cast<double>(frame) * sol::viewer::kScriptStep;
    for (; next_ < script_.size() && script_[next_].time <= t + 1e-9; ++next_) {
      const auto& e = script_[next_];
      if (e.kind == sol::viewer::ScriptEvent::Kind::Mouse) {
        app.controls.mouse(e.dx, e.dy);
      } else if (e.kind == sol::viewer::ScriptEvent::Kind::Set) {
        app.set(e.setting, e.value);
      } else if (e.kind == sol::viewer::ScriptEvent::Kind::Button) {
        // What the panel's button of that name does.
        using sol::viewer::Button;
        sol::viewer::PanelActions pressed;
        pressed.screenshot = e.button == Button::Screenshot;
        pressed.toggle_recording = e.button == Button::Record;
        pressed.reset = e.button == Button::Reset;
        pressed.copy_options = e.button == Button::CopyOptions;
        pressed.copy_json = e.button == Button::CopyJson;
        app.act(pressed, static_cast<int>(size.width), static_cast<int>(size.height));
      } else {
        app.key(e.key, e.kind == sol::viewer::ScriptEvent::Kind::Down);
      }
    }
  }

 private:
  std::vector<sol::viewer::ScriptEvent> script_;
  bool active_;
  std::size_t next_ = 0;
};

// solview's use of the shared refinement (sol::programs::Refinement): the
// frame's sample or the finished image again, and the times of a finished
// refinement on stderr (docs/solview.md's table).
class Refinement : public sol::programs::Refinement {
 public:
  Refinement(int samples, bool paths) : sol::programs::Refinement(samples), m_paths(paths) {}
  void set(sol::viewer::Presenter::FrameOptions& options) const {
    if (const auto s = sample()) {
      // By paths: the k-th path of every pixel (seed 0), as solrender --transport path --spp N.
      options.sample = sol::vk::PixelSample{s->offset, s->weight, m_paths ? s->index : -1, 0, s->index};
    } else if (reuse()) {
      options.reuse = true;
    }
  }
  void shown() {
    double full = 0.0;
    if (const auto since = sol::programs::Refinement::shown(&full)) {
      // Wall-clock time from the end of the pause to the frames shown.
      std::fprintf(stderr, "solview: refined: full resolution %.3f s and %d samples %.3f s after the %.2f s pause\n",
                   full, samples(), *since, kDelay);
    }
  }

 private:
  bool m_paths;
};

// The run's figures, printed at exit: the mean frame rate, render scale and
// host time after the first frames (pipeline builds, first allocations;
// with --frames, the second half only: the adaptive scale has settled by
// then), over the frames the kernel rendered (a finished refinement shown
// again costs nothing and would inflate the rate), and which path
// presented the frames.
class RunFigures {
 public:
  explicit RunFigures(long frames) : first_measured_(std::max(kWarmupFrames, frames / 2) + 1) {}

  // Frame `frame` (counted from 1) was shown at `scale`, `w` x `h` pixels;
  // `rendered`: the kernel made it (not a finished image shown again).
  void shown(long frame, double scale, double host_ms, bool direct, int w, int h, bool rendered) {
    frames_ = frame;
    ++(direct ? direct_frames_ : blit_frames_);
    shown_w_ = w;
    shown_h_ = h;
    const auto now = std::chrono::steady_clock::now();
    if (frame >= first_measured_) {
      if (rendered) {
        ++measured_;
        scale_sum_ += scale;
        host_ms_sum_ += host_ms;
        rendering_s_ += std::chrono::duration<double>(now - last_shown_).count();
      } else {
        ++reused_;
      }
    }
    last_shown_ = now;
  }

  void report(const App& app, const sol::viewer::Presenter& presenter) const {
    const long measured = measured_;
    if (measured == 0 && reused_ > 0) {
      std::fprintf(stderr, "solview: %s: no frame rendered from frame %ld on to measure (%ld finished images shown again)\n",
                   app.scene_name.c_str(), first_measured_, reused_);
    }
    if (measured > 0) {
      // The rate of rendered frames: their count over the time they took
      // (from the frame before each), a refined image's reshowing left out.
      char reused[96] = "";
      if (reused_ > 0) std::snprintf(reused, sizeof reused, "; %ld finished images shown again not counted", reused_);
      std::fprintf(stderr, "solview: %s: %.2f fps (mean over the %ld rendered frames of %ld..%ld%s), mean render scale %.2f\n",
                   app.scene_name.c_str(), static_cast<double>(measured) / rendering_s_, measured, first_measured_, frames_,
                   reused, scale_sum_ / static_cast<double>(measured));
      // The host's share of a frame: the cameras, the world when it changed,
      // and the recorded commands (no waits on the device).
      std::fprintf(stderr, "solview: host %.3f ms per frame to prepare and record (mean over frames %ld..%ld)\n",
                   host_ms_sum_ / static_cast<double>(measured), first_measured_, frames_);
    }
    std::fprintf(stderr, "solview: %ld frames, render scale %.2f at the end (%dx%d of %ux%u)\n", frames_, app.scale, shown_w_,
                 shown_h_, presenter.extent().width, presenter.extent().height);
    // Which path presented the frames (docs/solview.md: How solview presents a frame).
    std::fprintf(stderr, "solview: present: direct %ld frames, blit %ld frames (direct path %s)\n", direct_frames_,
                 blit_frames_, presenter.direct_capable() ? "available" : "unavailable on this surface");
  }

 private:
  static constexpr long kWarmupFrames = 5;
  long first_measured_, frames_ = 0;
  double scale_sum_ = 0, host_ms_sum_ = 0;
  long direct_frames_ = 0, blit_frames_ = 0;
  int shown_w_ = 0, shown_h_ = 0;  // of the last frame's rendered image (both eyes)
  long measured_ = 0, reused_ = 0;  // frames from first_measured_ on: rendered, shown again
  double rendering_s_ = 0.0;        // the rendered ones' time, each from the frame before
  std::chrono::steady_clock::time_point last_shown_ = std::chrono::steady_clock::now();
};

// The window's title: the frame rate (also the panel's), twice a second:
// the frames the kernel rendered, as the exit summary counts them (a
// finished refinement shown again is not a rendered frame; while only
// that is shown the rate is 0).
class Title {
 public:
  void frame(App& app, bool rendered) {
    if (rendered) ++frames_;
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - since_).count();
    if (since < 0.5) return;
    app.fps = static_cast<double>(frames_) / since;
    frames_ = 0;
    since_ = std::chrono::steady_clock::now();
    const glm::dvec3 p = app.observer.position();
    char title[256];
    std::snprintf(title, sizeof title, "solview - %s - %.1f fps - scale %.2f%s - (%.3f, %.3f, %.3f) - H: help",
                  app.scene_name.c_str(), app.fps, app.scale, app.adaptive ? " (adaptive)" : "", p.x, p.y, p.z);
    glfwSetWindowTitle(app.window, title);
  }

 private:
  long frames_ = 0;
  std::chrono::steady_clock::time_point since_ = std::chrono::steady_clock::now();
};

// The panel's mean march steps: a small render with its AOVs once a second,
// recorded into a submission of its own after the frame and read when its
// fence says it is done (a later frame looks): the loop never waits for it.
class StepsProbe {
 public:
  explicit StepsProbe(sol::vk::Context& context) : context_(context) {
    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                 VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, context.queue_family_index()};
    sol::vk::check(vkCreateCommandPool(context.device(), &pool, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool_,
                                         VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
    sol::vk::check(vkAllocateCommandBuffers(context.device(), &allocate, &commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, VK_FENCE_CREATE_SIGNALED_BIT};
    sol::vk::check(vkCreateFence(context.device(), &fence, nullptr, &done_), "vkCreateFence");
  }
  ~StepsProbe() {
    vkWaitForFences(context_.device(), 1, &done_, VK_TRUE, UINT64_MAX);
    vkDestroyFence(context_.device(), done_, nullptr);
    vkDestroyCommandPool(context_.device(), pool_, nullptr);
  }
  StepsProbe(const StepsProbe&) = delete;
  StepsProbe& operator=(const StepsProbe&) = delete;

  double mean() const { return mean_; }
  /// The share of the probe's pixels whose colour the display cut at white (-1: not measured yet).
  double clipped() const { return clipped_; }
  /// The display the last measured probe was shown through.
  const sol::Display& display() const { return display_; }
  void update(sol::vk::MarchRenderer& renderer, const sol::Camera& camera, int eye_w, int eye_h,
              const sol::Display& display) {
    if (pending_) {
      if (vkGetFenceStatus(context_.device(), done_) != VK_SUCCESS) return;  // not yet: a later frame looks
      pending_ = false;
      const auto* hits = reinterpret_cast<const float*>(readback_->bytes().data());
      const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
      const float* colour = hits + 4 * n;
      double sum = 0;
      std::size_t cut = 0;
      for (std::size_t k = 0; k < n; ++k) {
        sum += hits[4 * k + 2];  // object, distance, steps, 0
        cut += submitted_.clips(colour[4 * k]) || submitted_.clips(colour[4 * k + 1]) || submitted_.clips(colour[4 * k + 2]);
      }
      mean_ = n == 0 ? -1.0 : sum / static_cast<double>(n);
      clipped_ = n == 0 ? -1.0 : static_cast<double>(cut) / static_cast<double>(n);
      display_ = submitted_;
    }
    if (std::chrono::steady_clock::now() - last_ <= std::chrono::seconds(1)) return;
    last_ = std::chrono::steady_clock::now();
    width_ = 64;
    height_ = std::max(1, 64 * eye_h / std::max(1, eye_w));
    const auto w = static_cast<std::uint32_t>(width_), h = static_cast<std::uint32_t>(height_);
    if (!color_ || color_->width() != w || color_->height() != h) {  // (no probe pending reads the old ones)
      color_.emplace(context_, w, h);
      hit_.emplace(context_, w, h);
      point_.emplace(context_, w, h);
      readback_.emplace(context_, VkDeviceSize{w} * h * 32);  // the hit image, then the colour
    }
    submitted_ = display;
    sol::vk::check(vkResetFences(context_.device(), 1, &done_), "vkResetFences");
    sol::vk::check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                   VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    sol::vk::check(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
    renderer.record(commands_, std::span(&camera, 1), width_, height_, *color_, *hit_, *point_);
    // The kernel's AOVs, then to the host: a copy of the hit image into the mapped buffer.
    // (Read from the layout made for transfers, then back to GENERAL for the next probe's kernel.)
    sol::vk::image_barrier(commands_, hit_->handle(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    sol::vk::image_barrier(commands_, color_->handle(), VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                           VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {w, h, 1};
    vkCmdCopyImageToBuffer(commands_, hit_->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_->handle(), 1, &copy);
    copy.bufferOffset = VkDeviceSize{w} * h * 16;
    vkCmdCopyImageToBuffer(commands_, color_->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_->handle(), 1, &copy);
    for (VkImage image : {hit_->handle(), color_->handle()}) {
      sol::vk::image_barrier(commands_, image, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    }
    sol::vk::record_memory_barrier(commands_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    sol::vk::check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    sol::vk::check(vkQueueSubmit(context_.queue(), 1, &submit, done_), "vkQueueSubmit");
    pending_ = true;
  }

 private:
  sol::vk::Context& context_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer commands_ = VK_NULL_HANDLE;
  VkFence done_ = VK_NULL_HANDLE;
  std::optional<sol::vk::StorageImage> color_, hit_, point_;
  std::optional<sol::vk::Buffer> readback_;
  int width_ = 0, height_ = 0;
  bool pending_ = false;
  double mean_ = -1.0, clipped_ = -1.0;
  sol::Display submitted_{}, display_{};  // the pending probe's display; the measured one's
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now() - std::chrono::seconds(10);
};

// A frame the display cuts at white is said once per display on stderr (the
// panel shows the share as it changes): no highlight clips unsaid.
void note_clipping(const StepsProbe& probe, std::optional<sol::Display>& noted) {
  if (probe.clipped() <= 0.01 || noted == probe.display()) return;
  noted = probe.display();
  std::fprintf(stderr,
               "solview: note: %.0f %% of the frame is brighter than white under exposure %+g and tone %s and clips; "
               "%s keeps its highlights\n",
               100.0 * probe.clipped(), noted->exposure, sol::tone_name(noted->tone),
               noted->tone == sol::Tone::Clamp ? "a lower exposure or the aces curve" : "a lower exposure");
}

// The overlay panel: built now, drawn over the frame by present(); its
// actions carried out.
std::optional<sol::viewer::OverlayDraw> build_panel(App& app, const sol::viewer::Presenter& presenter, int refined,
                                                    double mean_steps, double clipped) {
  if (!app.overlay || !app.overlay_visible) return std::nullopt;
  const int eyes = app.stereo ? 2 : 1;
  const VkExtent2D window_extent = presenter.extent();
  const double shown_scale = refined >= 0 ? 1.0 : app.scale;  // refinement renders at full resolution
  const int rw = std::max(1, static_cast<int>(std::lround(window_extent.width * shown_scale / eyes))) * eyes;
  const int rh = std::max(1, static_cast<int>(std::lround(window_extent.height * shown_scale)));
  app.overlay->begin_frame(presenter.format());
  sol::viewer::PanelModel model{app.scene, app.scene_name, app.presets, app.stereo, app.ipd, app.scale,
                                app.adaptive, app.target_fps, app.options.min_scale, app.recording, app.observer,
                                app.frame_ms, app.fps, app.fps * rw * rh, mean_steps, rw, rh, refined,
                                app.options.refine, app.message, app.options.refine_paths};
  model.clipped = clipped;
  const sol::viewer::PanelActions actions = sol::viewer::draw_panel(model, app.panel_text);
  app.overlay->end_frame();
  app.act(actions, rw, rh);
  return sol::viewer::OverlayDraw{
      [&app](VkCommandBuffer cb, VkImageView view, VkFormat format, std::uint32_t w, std::uint32_t h) {
        app.overlay->record(cb, view, format, w, h);
      },
      app.overlay_in_capture};
}

// After the frame loop: --screenshot (the last frame shown, however the run
// ended: --frames, Esc, closing the window), --state, and where the panel was.
void finish(const App& app, sol::viewer::Presenter& presenter, long frames) {
  const Options& opt = app.options;
  if (!opt.screenshot.empty()) {
    try {
      presenter.save(opt.screenshot);
    } catch (const std::runtime_error& e) {  // (no frame, or the file: the writer names it and why)
      throw std::runtime_error(std::string("--screenshot ") + e.what());
    }
  }
  if (!opt.state.empty()) write_state(opt.state, app.observer, frames);
  if (app.overlay_visible) {  // where the panel was (tests compare the frame around it)
    const std::array<float, 4>& r = app.panel_text.rect;
    std::fprintf(stderr, "solview: overlay panel at %.0f,%.0f size %.0fx%.0f\n", r[0], r[1], r[2], r[3]);
  }
}

// The period a frame must fit: that of --target-fps (or the panel's
// target), else the display's refresh (60 Hz where the monitor gives none).
double display_period_ms(const App& app) {
  if (app.adaptive && app.target_fps > 0.0) return 1000.0 / app.target_fps;
  if (app.options.target_fps) return 1000.0 / *app.options.target_fps;
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();
  const GLFWvidmode* mode = monitor != nullptr ? glfwGetVideoMode(monitor) : nullptr;
  return 1000.0 / (mode != nullptr && mode->refreshRate > 0 ? mode->refreshRate : 60);
}

int run(App& app) {
  const Options& opt = app.options;
  Replay replay(prepare_files(app), !opt.script.empty());
  const GlfwSession glfw(app.command_line);
  sol::vk::Context context(context_options(opt, app.command_line));
  // One more frame than the presenter keeps in flight: the steps probe's
  // render() between two frames then never touches a pending frame's set.
  sol::vk::MarchRenderer renderer(context, {.frames_in_flight = sol::viewer::kFramesInFlight + 1});
  const Window window(app, replay.active());
  sol::viewer::Presenter presenter(context, window.get(), app.vsync, opt.present == "auto", app.scale == 1.0);
  // The overlay, after the viewer's own callbacks (ImGui's GLFW backend chains to them).
  std::optional<sol::viewer::Overlay> overlay;
  if (presenter.overlay_capable()) {
    overlay.emplace(context, window.get());
    app.overlay = &*overlay;
  } else if (opt.overlay == "on") {
    std::fprintf(stderr, "solview: the overlay cannot be drawn on this window's surface (no colour-attachment use)\n");
  }
  app.overlay_visible = app.overlay && opt.overlay == "on";
  app.overlay_in_capture = opt.overlay == "on";
  if (opt.target_fps) app.target_fps = *opt.target_fps;
  // The render scale that holds the target frame rate (sol::programs::AdaptiveScale).
  std::optional<sol::programs::AdaptiveScale> adaptive;
  if (opt.target_fps) adaptive.emplace(1e3 / *opt.target_fps, opt.min_scale);
  Refinement refinement(opt.refine, opt.refine_paths);
  RunFigures figures(opt.frames);
  Title title;
  StepsProbe steps(context);
  std::optional<sol::Display> noted_clipping;  // the display whose clipping was last said
  long frame = 0;
  auto last = std::chrono::steady_clock::now();
  std::optional<sol::World> prepared_world;  // the world the renderer holds

  while (!glfwWindowShouldClose(window.get()) && !app.quit && (opt.frames == 0 || frame < opt.frames)) {
    if (g_stop_signal != 0) {
      std::fprintf(stderr, "solview: signal %d: ending the session\n", static_cast<int>(g_stop_signal));
      break;
    }
    glfwPollEvents();
    app.poll_reload();
    app.carry_out_requests();
    if (app.want_swapchain || presenter.out_of_date() || !presenter.ready()) {
      app.want_swapchain = false;
      presenter.recreate(app.vsync);
      if (!presenter.ready()) {  // minimised
        glfwWaitEventsTimeout(0.1);  // (and look at signals and the scene file now and then)
        continue;
      }
    }
    // Input: a replay steps fixed 1/60 s per frame, live input by the clock.
    const auto now = std::chrono::steady_clock::now();
    const double frame_seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    double dt = std::min(frame_seconds, 0.1);
    if (replay.active()) {
      dt = sol::viewer::kScriptStep;
      replay.step(app, frame, presenter.extent());
    }
    if (app.quit) break;
    app.controls.step(app.observer, dt);
    if (app.adaptive && (!adaptive || adaptive->target_ms() != 1e3 / app.target_fps)) {
      adaptive.emplace(1e3 / app.target_fps, opt.min_scale);
    }
    // Refinement frames are full-size on purpose: they do not steer the adaptive scale.
    if (adaptive && refinement.refined() < 0) {
      const double next = adaptive->next(app.scale, frame, frame_seconds * 1e3);
      if (app.adaptive) app.scale = next;
    }
    if (frame > 0) {
      app.frame_ms.push_back(static_cast<float>(frame_seconds * 1e3));
      if (app.frame_ms.size() > 120) app.frame_ms.erase(app.frame_ms.begin());
    }
    const std::optional<sol::viewer::OverlayDraw> overlay_draw =
        build_panel(app, presenter, refinement.refined(), steps.mean(), steps.clipped());
    if (app.quit) break;

    const int eyes = app.stereo ? 2 : 1;
    const VkExtent2D extent = presenter.extent();
    if (!refinement.update(app.view_key(static_cast<int>(extent.width), static_cast<int>(extent.height)), dt, app.scale) &&
        adaptive) {
      adaptive.emplace(1e3 / app.target_fps, opt.min_scale);  // forget the full-size frames
    }
    const double render_scale = refinement.refined() >= 0 ? 1.0 : app.scale;
    const int eye_w = std::max(1, static_cast<int>(std::lround(extent.width * render_scale / eyes)));
    const int eye_h = std::max(1, static_cast<int>(std::lround(extent.height * render_scale)));

    const auto host_begin = std::chrono::steady_clock::now();
    // The world is prepared once per scene; per frame only the cameras change.
    if (app.world_changed) {
      app.world_changed = false;
      try {
        renderer.set_world(app.scene);  // frames in flight keep reading the old world's buffers
        prepared_world = app.scene;
        app.world_prepared();
      } catch (const std::exception& e) {
        // A world that validated but cannot be prepared: the renderer keeps the last one it held.
        if (!prepared_world) throw;
        app.world_refused(e.what(), *prepared_world);
        app.world_changed = false;
      }
    }
    const std::vector<sol::Camera> cameras = app.cameras();
    if (app.overlay_visible) {
      steps.update(renderer, cameras[0], eye_w, eye_h, app.scene.display);
      note_clipping(steps, noted_clipping);
    }
    const double prepare_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - host_begin).count();
    sol::viewer::Presenter::FrameOptions frame_options;
    frame_options.capture = app.recording || !opt.screenshot.empty() || app.want_screenshot;
    frame_options.vsync = app.vsync;
    frame_options.overlay = overlay_draw ? &*overlay_draw : nullptr;
    frame_options.period_ms = display_period_ms(app);
    frame_options.display = app.scene.display;
    refinement.set(frame_options);
    const std::optional<sol::viewer::Presenter::Shown> shown =
        presenter.present(renderer, cameras, eye_w, eye_h, frame_options);
    if (!shown) continue;  // the swapchain went out of date: re-created at the top
    refinement.shown();
    ++frame;
    figures.shown(frame, app.scale, prepare_ms + shown->record_ms, shown->direct, eye_w * eyes, eye_h, shown->rendered);

    if (app.recording) presenter.save(frame_name(app.record_dir, frame - 1));
    if (app.want_screenshot) {
      app.want_screenshot = false;
      char name[32];
      std::snprintf(name, sizeof name, "solview-%04d.png", app.screenshots++);
      presenter.save(name);
      std::printf("solview: screenshot %s\n", name);
    }
    title.frame(app, shown->rendered);
  }
  presenter.wait_for_frame();  // the frames still in flight: done, and counted
  context.wait_idle();
  finish(app, presenter, frame);
  figures.report(app, presenter);
  if (opt.stats) {
    std::printf("%s\n", presenter.stats().summary(app.stereo ? "stereo" : "mono").c_str());
    std::printf("solview: %s\n", presenter.stats().details().c_str());
  }
  if (context.validation_enabled()) {
    const std::vector<std::string> errors = context.validation_errors();
    for (const std::string& e : errors) std::fprintf(stderr, "solview: validation: %s\n", e.c_str());
    if (!errors.empty()) return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_texture_reader();  // scene files' "texture" keys
  App app;
  add_options(app.command_line, app.options);
  app.command_line.parse(argc, argv);
  sol::programs::install_signal_cleanup();  // screenshots, frames and the state: complete or absent
  install_stop_on_signal();
  try {
    app.set_scene(app.options.scene);
  } catch (const std::exception& e) {
    app.command_line.fail(e.what());
  }
  app.scale = app.options.scale;
  app.adaptive = app.options.target_fps.has_value();
  app.stereo = app.options.stereo;
  app.vsync = app.options.vsync == "on";
  app.ipd = app.options.ipd;
  app.min_scale = app.options.min_scale;
  try {
    return run(app);
  } catch (const std::exception& e) {
    app.command_line.fail(e.what(), 4);
  }
}
