#include "command_line.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace sol::cli {

void Arguments::fail(const std::string& message) const {
  std::fprintf(stderr, "%s: %s\n", m_program.c_str(), message.c_str());
  std::exit(2);
}

double Arguments::number(const std::string& text, const std::string& option) const {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
    fail("option " + option + " expects a finite number, got '" + text + "'");
  }
  return value;
}

long Arguments::integer(const std::string& text, const std::string& option, long lo, long hi) const {
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size()) fail("option " + option + " expects an integer, got '" + text + "'");
  if (value < lo || value > hi) {
    fail("option " + option + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text);
  }
  return value;
}

glm::dvec3 Arguments::vec3(const std::string& text, const std::string& option) const {
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

bool SceneOverrides::read(const Arguments& args, const std::string& option, const std::function<std::string()>& value,
                          bool with_fov) {
  if (with_fov && option == "--fov") {
    fov = args.number(value(), option);
  } else if (option == "--position") {
    position = args.vec3(value(), option);
  } else if (option == "--forward") {
    forward = args.vec3(value(), option);
  } else if (option == "--up") {
    up = args.vec3(value(), option);
  } else if (option == "--max-distance") {
    max_distance = args.number(value(), option);
  } else if (option == "--max-steps") {
    max_steps = static_cast<int>(args.integer(value(), option, 1, 100000));
  } else {
    return false;
  }
  return true;
}

void SceneOverrides::apply(Scene& scene) const {
  if (fov) scene.camera.fov = *fov;
  if (position) scene.camera.position = *position;
  if (forward) scene.camera.forward = *forward;
  if (up) scene.camera.up = *up;
  if (max_distance) scene.max_distance = *max_distance;
  if (max_steps) scene.max_steps = *max_steps;
}

Scene scene_argument(const std::string& text) {
  const bool is_file = std::filesystem::exists(text) || text.find('.') != std::string::npos ||
                       text.find('/') != std::string::npos;
  return is_file ? load_scene(text) : preset_scene(text);
}

}  // namespace sol::cli
