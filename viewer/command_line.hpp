// What the programs (solrender, solview, solxr) share on the command line:
// reading option values and the --scene argument, with one wording of the
// errors. A bad value prints "<program>: <message>" on stderr and exits with
// status 2 (bad usage), as each program documents.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <glm/vec3.hpp>
#include <sol/scene.hpp>
#include <sol/scene_file.hpp>

namespace sol::cli {

class Arguments {
 public:
  explicit Arguments(std::string program) : m_program(std::move(program)) {}

  /// Prints "<program>: <message>" and exits with status 2.
  [[noreturn]] void fail(const std::string& message) const;

  /// A finite number.
  double number(const std::string& text, const std::string& option) const;
  /// An integer in [lo, hi].
  long integer(const std::string& text, const std::string& option, long lo, long hi) const;
  /// Three comma-separated finite numbers, "x,y,z".
  glm::dvec3 vec3(const std::string& text, const std::string& option) const;

 private:
  std::string m_program;
};

/// The options that override a scene's camera and limits: --position,
/// --forward, --up (frame components), --max-distance, --max-steps, and
/// with `with_fov` --fov (solxr takes its field of view from the runtime).
struct SceneOverrides {
  std::optional<double> fov, max_distance;
  std::optional<glm::dvec3> position, forward, up;
  std::optional<int> max_steps;

  /// Reads `option` when it is one of these, its value from `value()`;
  /// false when it is not (the caller tries its own options).
  bool read(const Arguments& args, const std::string& option, const std::function<std::string()>& value,
            bool with_fov = true);
  /// Sets what was given on `scene` (not validated).
  void apply(Scene& scene) const;
};

/// The scene a --scene argument names: a JSON file when it exists or looks
/// like a path (contains '.' or '/'), else a preset (sol::preset_scene).
/// Throws sol::InvalidArgument (unreadable or invalid file, unknown preset).
Scene scene_argument(const std::string& text);

}  // namespace sol::cli
