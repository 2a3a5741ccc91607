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
#include <sol/vk/context.hpp>
#include <sol/vk/march.hpp>

#include "command_line.hpp"
#include "controls.hpp"
#include "image_file.hpp"
#include "output_file.hpp"
#include "overlay.hpp"
#include "panel.hpp"
#include "presenter.hpp"
#include "viewer_state.hpp"

namespace {

using sol::viewer::Key;

struct Options {
  std::string scene = "plane";
  int width = 640, height = 360;
  double scale = 1.0, min_scale = 0.05, ipd = 0.064;
  std::optional<double> target_fps;
  std::string vsync = "on", present = "auto", overlay = "off";
  bool fullscreen = false, stereo = false, validation = false;
  long frames = 0;  // 0: until the window closes
  int refine = 16;  // samples per pixel a still view accumulates (0: off)
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
            [](const sol::World& world) { return sol::vk::MarchRenderer::unsupported(world); }) {}

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

// The render scale that holds the target frame rate: the frame time goes
// with the pixel count, scale². Updated every 8 frames, or at once when a
// frame took over twice the target time (a slow scene must not crawl
// through 8 full-size frames first).
class AdaptiveScale {
 public:
  AdaptiveScale(double target_fps, double min_scale) : m_target_fps(target_fps), m_min_scale(min_scale) {}
  double target() const { return m_target_fps; }
  double next(double scale, long frame, double frame_seconds) {
    if (frame > 0) m_smoothed_ms = m_smoothed_ms == 0 ? frame_seconds * 1e3 : 0.8 * m_smoothed_ms + 0.2 * frame_seconds * 1e3;
    const bool far_too_slow = frame > 1 && frame_seconds * m_target_fps > 2.0;
    if (far_too_slow) m_smoothed_ms = frame_seconds * 1e3;
    if ((frame % 8 != 0 && !far_too_slow) || m_smoothed_ms <= 0) return scale;
    // Aim 10% above the target so that the dead band below never leaves the rate under it.
    const double wanted = scale * std::sqrt(1e3 / (1.1 * m_target_fps) / m_smoothed_ms);
    const double next = std::clamp(wanted, m_min_scale, 1.0);
    // A 5% dead band against dithering; the bounds are taken whatever the
    // step (scale 1 is the direct path, see Presenter; at 0.97 it would
    // never be reached).
    const bool at_bound = next == m_min_scale || next == 1.0;
    return std::abs(next - scale) > 0.05 * scale || (at_bound && next != scale) ? next : scale;
  }

 private:
  double m_target_fps, m_min_scale;
  double m_smoothed_ms = 0;
};

int run(App& app) {
  Options& opt = app.options;
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
  // Files written at exit: refused now rather than after the session.
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

  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    cl.fail("cannot open a window: " + glfw_error +
                (std::getenv("DISPLAY") ? "" : " (DISPLAY is not set: run under a display or xvfb-run)"),
            1);
  }
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfw_guard;
  if (!glfwVulkanSupported()) cl.fail("cannot open a window: GLFW finds no Vulkan loader", 1);

  sol::vk::ContextOptions context_options;
  context_options.pipeline_cache_dir = sol::vk::default_pipeline_cache_dir();  // compiled kernels kept between runs
  context_options.validation = opt.validation;
  std::uint32_t n_ext = 0;
  const char** ext = glfwGetRequiredInstanceExtensions(&n_ext);
  if (!ext) cl.fail("cannot open a window: GLFW cannot present Vulkan images here (" + glfw_error + ")", 1);
  for (std::uint32_t i = 0; i < n_ext; ++i) context_options.instance_extensions.emplace_back(ext[i]);
  context_options.device_extensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  sol::vk::Context context(context_options);
  sol::vk::MarchRenderer renderer(context);

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, "solview", nullptr, nullptr);
  if (!window) cl.fail("cannot open a window: " + glfw_error, 1);
  struct WindowGuard {
    GLFWwindow* w;
    ~WindowGuard() { glfwDestroyWindow(w); }
  } window_guard{window};
  app.window = window;
  glfwSetWindowUserPointer(window, &app);
  if (opt.fullscreen) app.toggle_fullscreen();
  const bool replay = !opt.script.empty();
  // During a replay live input is ignored: the script alone moves the observer.
  if (!replay) {
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
      App& a = app_of(w);
      // Typing into the panel's fields is not walking.
      const bool panel_typing = a.overlay && a.overlay_visible && a.overlay->wants_keyboard();
      if (auto k = key_of(key); k && action != GLFW_REPEAT && (!panel_typing || action == GLFW_RELEASE)) {
        a.key(*k, action == GLFW_PRESS);
      }
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
      if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      App& a = app_of(w);
      if (action == GLFW_PRESS && a.overlay && a.overlay_visible && a.overlay->wants_mouse()) return;  // the panel's
      a.dragging = action == GLFW_PRESS;
      glfwGetCursorPos(w, &a.last_x, &a.last_y);
    });
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
      App& a = app_of(w);
      if (a.dragging) a.controls.mouse(x - a.last_x, y - a.last_y);
      a.last_x = x;
      a.last_y = y;
    });
  }
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { app_of(w).want_swapchain = true; });

  sol::viewer::Presenter presenter(context, window, app.vsync, opt.present == "auto", app.scale == 1.0);
  // The overlay, after the viewer's own callbacks (ImGui's GLFW backend chains to them).
  std::optional<sol::viewer::Overlay> overlay;
  if (presenter.overlay_capable()) {
    overlay.emplace(context, window);
    app.overlay = &*overlay;
  } else if (opt.overlay == "on") {
    std::fprintf(stderr, "solview: the overlay cannot be drawn on this window's surface (no colour-attachment use)\n");
  }
  app.overlay_visible = app.overlay && opt.overlay == "on";
  app.overlay_in_capture = opt.overlay == "on";
  if (opt.target_fps) app.target_fps = *opt.target_fps;
  auto last_steps = std::chrono::steady_clock::now() - std::chrono::seconds(10);
  // Progressive refinement: the view last seen, for how long, and the samples accumulated (-1: not refining).
  constexpr double kRefineDelay = 0.25;
  std::array<double, 16> last_key{};
  double still_for = 0.0, refine_full_s = 0.0;
  int refined = -1;
  auto refine_began = std::chrono::steady_clock::now();
  double mean_steps = -1.0;
  std::optional<AdaptiveScale> adaptive;
  if (opt.target_fps) adaptive.emplace(*opt.target_fps, opt.min_scale);
  std::size_t next_event = 0;
  long frame = 0;
  auto last = std::chrono::steady_clock::now();
  auto title_time = last;
  long title_frames = 0;
  constexpr long kWarmupFrames = 5;
  auto measure_start = std::chrono::steady_clock::now();
  double scale_sum = 0;    // over the measured frames
  double host_ms_sum = 0;  // host time to prepare and record a frame, over the measured frames
  long direct_frames = 0, blit_frames = 0;
  int shown_w = 0, shown_h = 0;  // of the last frame's rendered image (both eyes)
  const long first_measured = std::max(kWarmupFrames, opt.frames / 2) + 1;

  while (!glfwWindowShouldClose(window) && !app.quit && (opt.frames == 0 || frame < opt.frames)) {
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
    // Input: a replay steps fixed 1/60 s per frame (deterministic), live input by the clock.
    const auto now = std::chrono::steady_clock::now();
    const double frame_seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    double dt = std::min(frame_seconds, 0.1);
    if (replay) {
      dt = sol::viewer::kScriptStep;
      const double t = static_cast<double>(frame) * sol::viewer::kScriptStep;
      for (; next_event < script.size() && script[next_event].time <= t + 1e-9; ++next_event) {
        const auto& e = script[next_event];
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
          const VkExtent2D size = presenter.extent();
          app.act(pressed, static_cast<int>(size.width), static_cast<int>(size.height));
        } else {
          app.key(e.key, e.kind == sol::viewer::ScriptEvent::Kind::Down);
        }
      }
    }
    if (app.quit) break;
    app.controls.step(app.observer, dt);
    if (app.adaptive && (!adaptive || adaptive->target() != app.target_fps)) adaptive.emplace(app.target_fps, opt.min_scale);
    // Refinement frames are full-size on purpose: they do not steer the adaptive scale.
    if (adaptive && refined < 0) {
      const double next = adaptive->next(app.scale, frame, frame_seconds);
      if (app.adaptive) app.scale = next;
    }
    if (frame > 0) {
      app.frame_ms.push_back(static_cast<float>(frame_seconds * 1e3));
      if (app.frame_ms.size() > 120) app.frame_ms.erase(app.frame_ms.begin());
    }

    // The overlay panel: built now, drawn over the frame by present().
    std::optional<sol::viewer::OverlayDraw> overlay_draw;
    if (app.overlay && app.overlay_visible) {
      const int eyes_now = app.stereo ? 2 : 1;
      const VkExtent2D window_extent = presenter.extent();
      const double shown_scale = refined >= 0 ? 1.0 : app.scale;  // refinement renders at full resolution
      const int rw = std::max(1, static_cast<int>(std::lround(window_extent.width * shown_scale / eyes_now))) * eyes_now;
      const int rh = std::max(1, static_cast<int>(std::lround(window_extent.height * shown_scale)));
      app.overlay->begin_frame(presenter.format());
      sol::viewer::PanelModel model{app.scene, app.scene_name, app.presets, app.stereo, app.ipd, app.scale,
                                    app.adaptive, app.target_fps, opt.min_scale, app.recording, app.observer,
                                    app.frame_ms, app.fps, app.fps * rw * rh, mean_steps, rw, rh, refined,
                                    opt.refine, app.message};
      const sol::viewer::PanelActions actions = sol::viewer::draw_panel(model, app.panel_text);
      app.overlay->end_frame();
      app.act(actions, rw, rh);
      overlay_draw = sol::viewer::OverlayDraw{
          [&app](VkCommandBuffer cb, VkImageView view, VkFormat format, std::uint32_t w, std::uint32_t h) {
            app.overlay->record(cb, view, format, w, h);
          },
          app.overlay_in_capture};
    }
    if (app.quit) break;

    const int eyes = app.stereo ? 2 : 1;
    const VkExtent2D extent = presenter.extent();
    // Progressive refinement: a view unchanged for kRefineDelay (in the
    // replay's time when replaying) is rendered at full resolution, then
    // sample by sample into a running mean, up to --refine samples; then
    // that image is shown as it is. Any change starts again.
    const std::array<double, 16> key = app.view_key(static_cast<int>(extent.width), static_cast<int>(extent.height));
    if (key != last_key) {
      last_key = key;
      still_for = 0.0;
      if (refined >= 0 && adaptive) adaptive.emplace(app.target_fps, opt.min_scale);  // forget the full-size frames
      refined = -1;
    } else {
      still_for += dt;
    }
    if (refined < 0 && opt.refine > 0 && still_for >= kRefineDelay && (app.scale < 1.0 || opt.refine > 1)) {
      refined = 0;
      refine_began = std::chrono::steady_clock::now();
    }
    const double render_scale = refined >= 0 ? 1.0 : app.scale;
    const int eye_w = std::max(1, static_cast<int>(std::lround(extent.width * render_scale / eyes)));
    const int eye_h = std::max(1, static_cast<int>(std::lround(extent.height * render_scale)));

    const auto host_begin = std::chrono::steady_clock::now();
    // The world is prepared once per scene; per frame only the cameras change.
    if (app.world_changed) {
      presenter.wait_for_frame();  // the previous frame still reads the old world
      renderer.set_world(app.scene);
      app.world_changed = false;
    }
    const std::vector<sol::Camera> cameras = app.cameras();
    // The panel's mean march steps: a small render with its AOVs once a second.
    if (app.overlay_visible && std::chrono::steady_clock::now() - last_steps > std::chrono::seconds(1)) {
      presenter.wait_for_frame();  // the frame in flight reads the renderer's uniforms
      const sol::RenderResult probe = renderer.render(cameras[0], {.width = 64, .height = std::max(1, 64 * eye_h / std::max(1, eye_w))});
      double sum = 0;
      for (float v : probe.steps) sum += v;
      mean_steps = probe.steps.empty() ? -1.0 : sum / static_cast<double>(probe.steps.size());
      last_steps = std::chrono::steady_clock::now();
    }
    const double prepare_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - host_begin).count();
    sol::viewer::Presenter::FrameOptions frame_options;
    frame_options.capture = app.recording || !opt.screenshot.empty() || app.want_screenshot;
    frame_options.vsync = app.vsync;
    frame_options.overlay = overlay_draw ? &*overlay_draw : nullptr;
    if (refined >= 0 && refined < opt.refine) {
      frame_options.sample = sol::vk::PixelSample{sol::pixel_sample(refined), 1.0 / (refined + 1)};
    } else if (refined >= opt.refine) {
      frame_options.reuse = true;
    }
    const std::optional<sol::viewer::Presenter::Shown> shown =
        presenter.present(renderer, cameras, eye_w, eye_h, frame_options);
    if (!shown) continue;  // the swapchain went out of date: re-created at the top
    if (refined >= 0 && refined < opt.refine) {
      ++refined;
      const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - refine_began).count();
      if (refined == 1) refine_full_s = since;
      if (refined == opt.refine) {
        // Wall-clock time from the end of the pause (the view still for
        // kRefineDelay) to the frames shown, for docs/solview.md's table.
        std::fprintf(stderr,
                     "solview: refined: full resolution %.3f s and %d samples %.3f s after the %.2f s pause\n",
                     refine_full_s, opt.refine, since, kRefineDelay);
      }
    }
    ++frame;
    ++(shown->direct ? direct_frames : blit_frames);
    shown_w = eye_w * eyes;
    shown_h = eye_h;
    // The run's mean frame rate leaves out the first frames (pipeline builds, first allocations).
    // With --frames, the second half only: the adaptive scale has settled by then.
    if (frame == first_measured - 1) measure_start = std::chrono::steady_clock::now();

    if (app.recording) presenter.save(frame_name(app.record_dir, frame - 1));
    if (app.want_screenshot) {
      app.want_screenshot = false;
      char name[32];
      std::snprintf(name, sizeof name, "solview-%04d.png", app.screenshots++);
      presenter.save(name);
      std::printf("solview: screenshot %s\n", name);
    }

    if (frame >= first_measured) {
      scale_sum += app.scale;
      host_ms_sum += prepare_ms + shown->record_ms;
    }
    ++title_frames;
    const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - title_time).count();
    if (since >= 0.5) {
      const double fps = static_cast<double>(title_frames) / since;
      app.fps = fps;
      title_frames = 0;
      title_time = std::chrono::steady_clock::now();
      const glm::dvec3 p = app.observer.position();
      char title[256];
      std::snprintf(title, sizeof title, "solview - %s - %.1f fps - scale %.2f%s - (%.3f, %.3f, %.3f) - H: help",
                    app.scene_name.c_str(), fps, app.scale, app.adaptive ? " (adaptive)" : "", p.x, p.y, p.z);
      glfwSetWindowTitle(window, title);
    }
  }
  context.wait_idle();
  // --screenshot: the last frame shown, however the run ended (--frames, Esc, closing the window).
  if (!opt.screenshot.empty()) {
    try {
      presenter.save(opt.screenshot);
    } catch (const std::runtime_error&) {
      throw std::runtime_error("--screenshot " + opt.screenshot + ": no frame was rendered");
    }
  }
  if (!opt.state.empty()) write_state(opt.state, app.observer, frame);
  if (app.overlay_visible) {  // where the panel was (tests compare the frame around it)
    const std::array<float, 4>& r = app.panel_text.rect;
    std::fprintf(stderr, "solview: overlay panel at %.0f,%.0f size %.0fx%.0f\n", r[0], r[1], r[2], r[3]);
  }
  const long measured = frame - first_measured + 1;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - measure_start).count();
  if (measured > 0) {
    std::fprintf(stderr, "solview: %s: %.2f fps (mean over frames %ld..%ld), mean render scale %.2f\n",
                 app.scene_name.c_str(), static_cast<double>(measured) / seconds, first_measured, frame,
                 scale_sum / static_cast<double>(measured));
    // The host's share of a frame: the cameras, the world when it changed,
    // and the recorded commands (no waits on the device).
    std::fprintf(stderr, "solview: host %.3f ms per frame to prepare and record (mean over frames %ld..%ld)\n",
                 host_ms_sum / static_cast<double>(measured), first_measured, frame);
  }
  std::fprintf(stderr, "solview: %ld frames, render scale %.2f at the end (%dx%d of %ux%u)\n", frame, app.scale, shown_w,
               shown_h, presenter.extent().width, presenter.extent().height);
  // Which path presented the frames (docs/solview.md: How solview presents a frame).
  std::fprintf(stderr, "solview: present: direct %ld frames, blit %ld frames (direct path %s)\n", direct_frames,
               blit_frames, presenter.direct_capable() ? "available" : "unavailable on this surface");
  if (context.validation_enabled()) {
    const std::vector<std::string> errors = context.validation_errors();
    for (const std::string& e : errors) std::fprintf(stderr, "solview: validation: %s\n", e.c_str());
    if (!errors.empty()) return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
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
