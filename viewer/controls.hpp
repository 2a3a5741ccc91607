// solview's controls: held keys and mouse motion -> sol::Observer, and the
// timed input scripts (--script) that replay them. No window here: the same
// code runs for live input (GLFW callbacks feed it) and for replays.
//
// One step of `dt` seconds applies, in this order (tests/viewer re-derive
// positions from these rules with sol::Observer alone):
//   1. mouse motion since the last step, in arrival order: yaw(dx · kMouseTurn),
//      then pitch(-dy · kMouseTurn) for each motion;
//   2. keys: yaw((RIGHT - LEFT) · kTurnRate · dt), pitch((UP - DOWN) · kTurnRate · dt),
//      roll((E - Q) · kTurnRate · dt), each only when non-zero;
//   3. one move along the geodesic in the observer's local direction
//      normalize(D - A, R - F, W - S) by kSpeed · dt (× kShiftFactor with Shift).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <sol/observer.hpp>

namespace sol::viewer {

constexpr double kSpeed = 1.0;         ///< Sol units per second
constexpr double kShiftFactor = 5.0;   ///< speed factor with Shift held
constexpr double kTurnRate = 1.2;      ///< radians per second (arrow keys, Q/E)
constexpr double kMouseTurn = 0.0025;  ///< radians per pixel of mouse motion
constexpr double kScriptStep = 1.0 / 60.0;  ///< seconds of simulated time per frame in a replay

/// The keys the viewer knows, by the names scripts use.
enum class Key { W, S, A, D, R, F, Q, E, Up, Down, Left, Right, Shift, Tab, Home, T, Y, P, H, G, Plus, Minus, F1, F11, Escape };

/// "W", "LEFT", "SHIFT", ... (case-insensitive); std::nullopt for others.
std::optional<Key> key_from_name(const std::string& name);
/// Every name key_from_name accepts, for error messages.
std::string key_names();

/// The settings a script may set (`TIME set NAME VALUE`): what the overlay
/// panel's controls of the same name change.
enum class Setting { Fov, MaxDistance, MaxSteps, HitEpsilon, Scale, Ipd, Exposure };
/// "fov", "max-distance", "max-steps", "hit-epsilon", "scale", "ipd"; std::nullopt for others.
std::optional<Setting> setting_from_name(const std::string& name);
std::string setting_names();

/// The panel's buttons a script may press (`TIME button NAME`): "screenshot",
/// "record", "reset", "copy-options", "copy-json".
enum class Button { Screenshot, Record, Reset, CopyOptions, CopyJson };
std::optional<Button> button_from_name(const std::string& name);
std::string button_names();

/// One timed input of a script.
struct ScriptEvent {
  enum class Kind { Down, Up, Mouse, Set, Button } kind = Kind::Down;
  double time = 0;  ///< seconds of simulated time from the start
  Key key = Key::W;
  double dx = 0, dy = 0;  ///< mouse motion in pixels (Mouse)
  Setting setting = Setting::Fov;  ///< Set: which, to `value`
  double value = 0;
  Button button = Button::Screenshot;  ///< Button: which
};

/// Parses a script: one event per line, `TIME down KEY`, `TIME up KEY`,
/// `TIME mouse DX DY`, `TIME set NAME VALUE` or `TIME button NAME`, times in seconds,
/// non-decreasing; `#` starts a comment. Throws std::runtime_error naming
/// the file and line. (Set values are checked when applied, as the panel's.)
std::vector<ScriptEvent> load_script(const std::string& path);

/// Held keys and pending mouse motion, applied to an observer step by step.
class Controls {
 public:
  void key(Key k, bool down) { m_held[k] = down; }
  bool held(Key k) const {
    auto it = m_held.find(k);
    return it != m_held.end() && it->second;
  }
  void mouse(double dx, double dy) { m_mouse.push_back({dx, dy}); }
  void release_all() { m_held.clear(); }
  /// One step of dt seconds (see the order above).
  void step(Observer& observer, double dt);

 private:
  struct Motion {
    double dx, dy;
  };
  std::map<Key, bool> m_held;
  std::vector<Motion> m_mouse;
};

}  // namespace sol::viewer
