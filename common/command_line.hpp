// The command-line conventions every Sol program (solrender, solview, solxr)
// shares, on CLI11: one --help layout ("usage: ..." first, then the options,
// then the program's notes), one wording for bad values, and exit status 2
// for bad usage with "<program>: <message>" on stderr.
//
//   sol::cli::CommandLine cl("solrender", "[options] -o OUT", "Renders ...");
//   cl.add_integer("--width", width, 1, 16384, "W", "image width in pixels");
//   cl.add_choice("--device", device, {"auto", "vulkan", "cpu"}, "where to render");
//   cl.parse(argc, argv);  // --help prints and exits 0; bad usage exits 2
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <sol/scene.hpp>

namespace CLI {
class App;
}

namespace sol::cli {

class CommandLine {
 public:
  /// `usage` follows the program's name on the help's first line, `summary`
  /// is the line under it.
  CommandLine(std::string program, const std::string& usage, const std::string& summary);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;

  const std::string& program() const { return m_program; }

  // Options. `names` as CLI11 takes them ("-o,--output"); `value_name`
  // shows what the value is in --help ("W", "FILE"). Each option may be
  // given more than once: the last value counts.

  /// A flag without a value.
  void add_flag(const std::string& names, bool& target, const std::string& help);
  /// Any text.
  void add_text(const std::string& names, std::string& target, const std::string& value_name, const std::string& help);
  /// One of `choices`: "option --device expects auto, vulkan or cpu, got 'x'".
  void add_choice(const std::string& names, std::string& target, const std::vector<std::string>& choices,
                  const std::string& help);
  /// The same with the value optional: the option alone sets `implicit`
  /// ("--stereo" is "--stereo side-by-side").
  void add_optional_choice(const std::string& names, std::string& target, const std::vector<std::string>& choices,
                           const std::string& implicit, const std::string& help);
  /// An integer in [lo, hi]: "option --width expects an integer, got 'x'",
  /// "option --width must be in [1, 16384], got 0".
  template <class Int>
  void add_integer(const std::string& names, Int& target, long lo, long hi, const std::string& value_name,
                   const std::string& help) {
    add_value(names, value_name, help, [this, &target, lo, hi, name = long_name(names)](const std::string& text) {
      target = static_cast<Int>(integer(text, name, lo, hi));
    });
  }
  /// A finite number meeting `condition` when given: a predicate and the words it
  /// stands for ("> 0" gives "option --ipd must be > 0, got -1").
  struct Condition {
    std::function<bool(double)> holds;
    std::string words;
  };
  /// `target`: a double or a std::optional<double>.
  template <class Target>
  void add_number(const std::string& names, Target& target, const std::string& value_name, const std::string& help,
                  const std::optional<Condition>& condition = std::nullopt) {
    add_value(names, value_name, help, [this, &target, condition, name = long_name(names)](const std::string& text) {
      target = checked_number(text, name, condition);
    });
  }
  /// Three finite numbers "x,y,z".
  void add_vec3(const std::string& names, std::optional<glm::dvec3>& target, const std::string& value_name,
                const std::string& help);
  /// A value read by `read`, which reports a bad one with fail().
  void add_value(const std::string& names, const std::string& value_name, const std::string& help,
                 std::function<void(const std::string&)> read);

  /// Notes printed after the options in --help.
  void set_footer(const std::string& footer);

  /// Parses the command line: --help prints the help on stdout and exits 0;
  /// bad usage (an unknown option, a missing or bad value) prints
  /// "<program>: <message>" on stderr and exits 2.
  void parse(int argc, char** argv);

  /// The help text.
  std::string help() const;

  /// Prints "<program>: <message>" on stderr and exits with `status`.
  [[noreturn]] void fail(const std::string& message, int status = 2) const;

  // Reading values by hand (the same messages), failing with status 2.
  /// A finite number.
  double number(const std::string& text, const std::string& option) const;
  /// A finite number meeting `condition` when given.
  double checked_number(const std::string& text, const std::string& option,
                        const std::optional<Condition>& condition) const;
  /// An integer in [lo, hi].
  long integer(const std::string& text, const std::string& option, long lo, long hi) const;
  /// Three comma-separated finite numbers, "x,y,z".
  glm::dvec3 vec3(const std::string& text, const std::string& option) const;

 private:
  static std::string long_name(const std::string& names);
  std::string m_program;
  std::unique_ptr<CLI::App> m_app;
};

/// "> 0", ">= 0", "in (0, 1]": common conditions on numbers.
CommandLine::Condition positive();
CommandLine::Condition non_negative();
CommandLine::Condition in_unit_interval();
/// "in [lo, hi]" (bounds printed with %g).
CommandLine::Condition in_range(double lo, double hi);

/// The kernel's geodesic flow as the programs choose it: --integrator
/// closed|rk4 (the closed form, or RK4 from step to step for comparison)
/// and --rk-step H (RK4's substep in arc length, > 0).
struct IntegratorOptions {
  std::string integrator = "closed";
  double rk_step = 0.01;

  void add_to(CommandLine& command_line);
  bool rk4() const { return integrator == "rk4"; }
};

/// The options that override a scene's camera and limits: --position,
/// --forward, --up (frame components) or --look-at (a point the camera
/// aims at: sol::looking_at, and where the lens has no --focus-distance it
/// focuses there), --max-distance, --max-steps, and with `with_fov` --fov,
/// --aperture and --focus-distance (solxr takes its field of view from the
/// runtime and has no lens).
struct SceneOverrides {
  std::optional<double> fov, max_distance, aperture, focus_distance;
  std::optional<glm::dvec3> position, forward, up, look_at;
  std::optional<int> max_steps;

  /// Adds the options to `command_line`, `what` naming the camera in their help
  /// ("camera", "base observer").
  void add_to(CommandLine& command_line, const std::string& what, bool with_fov = true);
  /// Sets what was given on `scene` (not validated; --look-at throws
  /// InvalidArgument naming it where the point cannot be aimed at).
  void apply(Scene& scene) const;
};

/// The presets, comma-separated, for help texts.
std::string preset_list();

/// The scene a --scene argument names: a JSON file when it exists or looks
/// like a path (contains '.' or '/'), else a preset (sol::preset_scene).
/// Throws sol::InvalidArgument (unreadable or invalid file, unknown preset).
Scene scene_argument(const std::string& text);

}  // namespace sol::cli
