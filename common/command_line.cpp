#include "command_line.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <CLI/CLI.hpp>
#include <sol/aim.hpp>
#include <sol/error.hpp>
#include <sol/scene_file.hpp>

namespace sol::cli {
namespace {

// --help: "usage: <program> <usage>", the summary, the options, the notes.
class HelpFormatter : public CLI::Formatter {
 public:
  explicit HelpFormatter(std::string usage) : m_usage(std::move(usage)) {}
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
    std::string out = "usage: " + name + " " + m_usage + "\n";
    if (!app->get_description().empty()) out += app->get_description() + "\n";
    out += make_groups(app, mode);
    if (!app->get_footer().empty()) out += "\n" + app->get_footer() + "\n";
    return out;
  }

 private:
  std::string m_usage;
};

std::string join_choices(const std::vector<std::string>& choices) {
  std::string out;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    out += i == 0 ? "" : (i + 1 == choices.size() ? " or " : ", ");
    out += choices[i];
  }
  return out;
}

}  // namespace

CommandLine::CommandLine(std::string program, const std::string& usage, const std::string& summary)
    : m_program(std::move(program)), m_app(std::make_unique<CLI::App>(summary, m_program)) {
  m_app->formatter(std::make_shared<HelpFormatter>(usage));
  m_app->set_help_flag("-h,--help", "this text");
  m_app->get_formatter()->column_width(26);
  m_app->allow_extras();  // reported by parse() in our words
}

CommandLine::~CommandLine() = default;

std::string CommandLine::long_name(const std::string& names) {
  const std::size_t at = names.rfind("--");
  return at == std::string::npos ? names : names.substr(at);
}

void CommandLine::fail(const std::string& message, int status) const {
  std::fprintf(stderr, "%s: %s\n", m_program.c_str(), message.c_str());
  std::exit(status);
}

void CommandLine::add_value(const std::string& names, const std::string& value_name, const std::string& help,
                            std::function<void(const std::string&)> read) {
  m_app->add_option_function<std::string>(names, std::move(read), help)
      ->type_name(value_name)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

void CommandLine::add_optional_choice(const std::string& names, std::string& target,
                                      const std::vector<std::string>& choices, const std::string& implicit,
                                      const std::string& help) {
  std::string shown;
  for (const std::string& c : choices) shown += (shown.empty() ? "" : "|") + c;
  m_app
      ->add_option_function<std::string>(
          names,
          [this, &target, choices, name = long_name(names)](const std::string& text) {
            for (const std::string& c : choices) {
              if (c == text) {
                target = text;
                return;
              }
            }
            fail("option " + name + " expects " + join_choices(choices) + ", got '" + text + "'");
          },
          help)
      ->type_name("[" + shown + "]")
      ->expected(0, 1)
      ->default_str(implicit)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

void CommandLine::add_flag(const std::string& names, bool& target, const std::string& help) {
  m_app->add_flag(names, target, help);
}

void CommandLine::add_text(const std::string& names, std::string& target, const std::string& value_name,
                           const std::string& help) {
  add_value(names, value_name, help, [&target](const std::string& text) { target = text; });
}

void CommandLine::add_choice(const std::string& names, std::string& target, const std::vector<std::string>& choices,
                             const std::string& help) {
  std::string shown;
  for (const std::string& c : choices) shown += (shown.empty() ? "" : "|") + c;
  add_value(names, shown, help, [this, &target, choices, name = long_name(names)](const std::string& text) {
    for (const std::string& c : choices) {
      if (c == text) {
        target = text;
        return;
      }
    }
    fail("option " + name + " expects " + join_choices(choices) + ", got '" + text + "'");
  });
}

double CommandLine::checked_number(const std::string& text, const std::string& option,
                                   const std::optional<Condition>& condition) const {
  const double v = number(text, option);
  if (condition && !condition->holds(v)) fail("option " + option + " must be " + condition->words + ", got " + text);
  return v;
}

void CommandLine::add_vec3(const std::string& names, std::optional<glm::dvec3>& target, const std::string& value_name,
                           const std::string& help) {
  add_value(names, value_name, help,
            [this, &target, name = long_name(names)](const std::string& text) { target = vec3(text, name); });
}

void CommandLine::set_footer(const std::string& footer) { m_app->footer(footer); }

std::string CommandLine::help() const { return m_app->help(); }

void CommandLine::parse(int argc, char** argv) {
  try {
    m_app->parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(help().c_str(), stdout);
    std::exit(0);
  } catch (const CLI::ArgumentMismatch& e) {
    // A value missing after the last option ("--screenshot: 1 required FILE missing").
    const std::string what = e.what();
    const std::string option = what.substr(0, what.find(':'));
    fail("option " + option + " needs a value");
  } catch (const CLI::ParseError& e) {
    fail(e.what());
  }
  const std::vector<std::string> extra = m_app->remaining();
  if (!extra.empty()) fail("unknown option '" + extra.front() + "' (see " + m_program + " --help)");
}

double CommandLine::number(const std::string& text, const std::string& option) const {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
    fail("option " + option + " expects a finite number, got '" + text + "'");
  }
  return value;
}

long CommandLine::integer(const std::string& text, const std::string& option, long lo, long hi) const {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size()) fail("option " + option + " expects an integer, got '" + text + "'");
  if (value < lo || value > hi) {
    fail("option " + option + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text);
  }
  return value;
}

glm::dvec3 CommandLine::vec3(const std::string& text, const std::string& option) const {
  std::vector<std::string> parts(1);
  for (char c : text) {
    if (c == ',') {
      parts.emplace_back();
    } else {
      parts.back() += c;
    }
  }
  if (parts.size() != 3) {
    fail("option " + option + " expects three comma-separated numbers like 0,0,1.5, got '" + text + "'");
  }
  return {number(parts[0], option), number(parts[1], option), number(parts[2], option)};
}

CommandLine::Condition positive() {
  return {[](double v) { return v > 0.0; }, "> 0"};
}
CommandLine::Condition non_negative() {
  return {[](double v) { return v >= 0.0; }, ">= 0"};
}
namespace {
// %g without exponent padding: 1e-06 -> 1e-6, 1e+06 -> 1e6.
std::string compact(double v) {
  char text[48];
  std::snprintf(text, sizeof text, "%g", v);
  std::string s = text;
  const std::size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}
}  // namespace

CommandLine::Condition in_range(double lo, double hi) {
  return {[lo, hi](double v) { return v >= lo && v <= hi; }, "in [" + compact(lo) + ", " + compact(hi) + "]"};
}
CommandLine::Condition in_unit_interval() {
  return {[](double v) { return v > 0.0 && v <= 1.0; }, "in (0, 1]"};
}

void IntegratorOptions::add_to(CommandLine& cl) {
  cl.add_choice("--integrator", integrator, {"closed", "rk4"},
                "the kernel's geodesic flow: the closed form, or RK4 from step to step for comparison (default "
                "closed; the Vulkan kernel only)");
  cl.add_number("--rk-step", rk_step, "H", "RK4 substep in arc length for --integrator rk4 (default 0.01)", positive());
}

void SceneOverrides::add_to(CommandLine& cl, const std::string& what, bool with_fov) {
  if (with_fov) {
    cl.add_number("--fov", fov, "DEG", "vertical field of view in degrees, (0, 180)");
    cl.add_number("--aperture", aperture, "A",
                  "depth of field: the radius of a thin lens at the eye, an arc length in [0, 1] (default 0: a pinhole)");
    cl.add_number("--focus-distance", focus_distance, "F",
                  "the arc length along each pixel's geodesic that is in focus, (0, 100] (default: the --look-at "
                  "point's distance, else the scene's)");
  }
  cl.add_vec3("--position", position, "X,Y,Z", what + " position (Sol coordinates)");
  cl.add_vec3("--forward", forward, "A,B,C", what + " view direction, frame components");
  cl.add_vec3("--up", up, "A,B,C", what + " up direction, frame components (not parallel to forward)");
  cl.add_vec3("--look-at", look_at, "X,Y,Z",
              "aim the " + what + " at this point (in place of --forward): along the minimising geodesic's start, so "
              "the point is at the image's centre (in a quotient its nearest image)");
  cl.add_number("--max-distance", max_distance, "D", "arc length after which a ray misses");
  cl.add_integer("--max-steps", max_steps, 1, 100000, "N", "march steps after which a ray misses");
}

void SceneOverrides::apply(Scene& scene) const {
  if (fov) scene.camera.fov = *fov;
  if (position) scene.camera.position = *position;
  if (forward) scene.camera.forward = *forward;
  if (up) scene.camera.up = *up;
  if (look_at) {
    if (forward) throw InvalidArgument("--look-at: give either --forward or --look-at, not both");
    try {
      scene.camera = looking_at(scene.camera, *look_at, scene.lattice());  // (focused there too)
    } catch (const std::exception& e) {  // the library's message names its function: the option's instead
      throw InvalidArgument("--look-at: " + without_function(e.what()));
    }
  }
  if (aperture) scene.camera.aperture = *aperture;
  if (focus_distance) scene.camera.focus_distance = *focus_distance;
  if (max_distance) scene.max_distance = *max_distance;
  if (max_steps) scene.max_steps = *max_steps;
}

std::string preset_list() {
  std::string names;
  for (const std::string& n : preset_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

Scene scene_argument(const std::string& text) {
  const bool is_file = std::filesystem::exists(text) || text.find('.') != std::string::npos ||
                       text.find('/') != std::string::npos;
  return is_file ? load_scene(text) : preset_scene(text);
}

}  // namespace sol::cli
