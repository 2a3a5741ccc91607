// solview's overlay panel (F1): the scene, the camera and the render
// settings as live controls, readouts of the frame, and actions. Immediate
// mode: draw_panel() builds the panel for this frame from the viewer's state
// (PanelModel, edited in place) and says what else the user asked for
// (PanelActions), which the viewer carries out. See docs/solview.md.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <sol/observer.hpp>
#include <sol/scene.hpp>

namespace sol::viewer {

/// The viewer's state the panel shows and edits.
struct PanelModel {
  Scene& scene;  ///< the world (objects, lights, fog, limits) and the camera's fov
  const std::string& scene_name;
  const std::vector<std::string>& presets;
  bool& stereo;
  double& ipd;
  double& scale;       ///< render scale, (0, 1]
  bool& adaptive;      ///< the scale follows target_fps
  double& target_fps;  ///< > 0
  double min_scale;
  bool recording;  ///< frames are being written (the record button's state)
  // Readouts.
  const Observer& observer;
  std::span<const float> frame_ms;  ///< the last frames' times, oldest first
  double fps = 0;
  double rays_per_second = 0;
  double mean_steps = -1;  ///< < 0: not measured yet
  int render_width = 0, render_height = 0;
  int refined = -1;       ///< samples accumulated by progressive refinement (-1: moving)
  int refine_target = 0;  ///< --refine
  const std::string& message;  ///< the last error or notice (empty: none)
  bool refine_paths = false;   ///< the refinement's samples are paths (max bounces: a path's scatterings)
  double clipped = -1;         ///< the share of the probe's pixels the display cuts at white (< 0: not measured)
};

/// What the user asked for in this frame besides the edits made in place.
struct PanelActions {
  bool world_changed = false;  ///< the world was edited: prepare it again
  std::optional<std::string> load;  ///< a preset's name or a scene file's path
  std::optional<std::string> save;  ///< write the scene (world and current camera) as JSON to this path
  bool screenshot = false;
  bool toggle_recording = false;
  bool copy_options = false;  ///< the current camera as solrender options, to the clipboard and stdout
  bool copy_json = false;     ///< the scene with the current camera as JSON, to the clipboard and stdout
  bool reset = false;         ///< back to the scene's camera
  /// Turn the camera to look at this point (sol::aim, in the world's space).
  std::optional<glm::dvec3> look_at;
};

/// Text typed into the panel's fields, kept between frames.
struct PanelText {
  std::array<char, 1024> file{};
  std::array<char, 1024> save{};
  std::array<float, 4> rect{};  ///< where the panel was last drawn: x, y, width, height in window pixels
  std::array<int, 4> monodromy{2, 1, 1, 1};  ///< the monodromy being typed, a, b, c, d (applied on Enter)
  std::string refusal;                       ///< why the last monodromy typed was not applied (empty: it was)
  std::array<double, 3> look_at{0.0, 0.0, 0.0};  ///< the point the "look at" button aims the camera at
};

/// Builds the panel in the current ImGui frame.
PanelActions draw_panel(PanelModel& model, PanelText& text);

/// An object's image texture in the current ImGui window: its file, read
/// through the program's reader (sol::read_texture) when Enter is pressed
/// in the field (an error shown below it, the texture kept), taken off by
/// the "no texture" button (the last widget where there is one), and the
/// pattern cells one copy spans as powers of two. Whether it changed.
bool texture_controls(SceneObject& o);

/// Why the world cannot be the golden quotient (sol::validate's message), or
/// empty when it can.
std::string quotient_refusal(const World& world);

}  // namespace sol::viewer
