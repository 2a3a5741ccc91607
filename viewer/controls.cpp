#include "controls.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

namespace sol::viewer {
namespace {

const std::pair<const char*, Key> kNames[] = {
    {"W", Key::W},       {"S", Key::S},         {"A", Key::A},         {"D", Key::D},
    {"R", Key::R},       {"F", Key::F},         {"Q", Key::Q},         {"E", Key::E},
    {"UP", Key::Up},     {"DOWN", Key::Down},   {"LEFT", Key::Left},   {"RIGHT", Key::Right},
    {"SHIFT", Key::Shift}, {"TAB", Key::Tab},   {"HOME", Key::Home},   {"T", Key::T},
    {"Y", Key::Y},       {"P", Key::P},         {"H", Key::H},         {"G", Key::G},
    {"PLUS", Key::Plus}, {"MINUS", Key::Minus}, {"F1", Key::F1},       {"F11", Key::F11},
    {"ESCAPE", Key::Escape},
};

const std::pair<const char*, Setting> kSettings[] = {
    {"fov", Setting::Fov},     {"max-distance", Setting::MaxDistance}, {"max-steps", Setting::MaxSteps},
    {"hit-epsilon", Setting::HitEpsilon}, {"scale", Setting::Scale},   {"ipd", Setting::Ipd},
    {"exposure", Setting::Exposure},
};

const std::pair<const char*, Button> kButtons[] = {
    {"screenshot", Button::Screenshot}, {"record", Button::Record},         {"reset", Button::Reset},
    {"copy-options", Button::CopyOptions}, {"copy-json", Button::CopyJson},
};

bool parse_double(const std::string& text, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(out);
}

}  // namespace

namespace {

// A name's entry in one of the tables above, and the table's names for messages.
template <class T, std::size_t N>
std::optional<T> find_name(const std::pair<const char*, T> (&table)[N], const std::string& name) {
  for (const auto& [n, value] : table) {
    if (name == n) return value;
  }
  return std::nullopt;
}

template <class T, std::size_t N>
std::string list_names(const std::pair<const char*, T> (&table)[N]) {
  std::string out;
  for (const auto& [n, value] : table) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

}  // namespace

std::optional<Key> key_from_name(const std::string& name) {
  std::string upper = name;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  return find_name(kNames, upper);
}
std::string key_names() { return list_names(kNames); }
std::optional<Button> button_from_name(const std::string& name) { return find_name(kButtons, name); }
std::string button_names() { return list_names(kButtons); }
std::optional<Setting> setting_from_name(const std::string& name) { return find_name(kSettings, name); }
std::string setting_names() { return list_names(kSettings); }

std::vector<ScriptEvent> load_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open script file");
  std::vector<ScriptEvent> events;
  std::string line;
  int number = 0;
  double last = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string s; words >> s;) w.push_back(s);
    if (w.empty()) continue;
    ScriptEvent e;
    if (!parse_double(w[0], e.time) || e.time < 0) {
      throw std::runtime_error(where + "expected a time in seconds >= 0, got '" + w[0] + "'");
    }
    if (e.time < last) throw std::runtime_error(where + "times must not decrease (" + w[0] + " after " + std::to_string(last) + ")");
    last = e.time;
    if (w.size() == 3 && (w[1] == "down" || w[1] == "up")) {
      const auto key = key_from_name(w[2]);
      if (!key) throw std::runtime_error(where + "unknown key '" + w[2] + "' (keys: " + key_names() + ")");
      e.kind = w[1] == "down" ? ScriptEvent::Kind::Down : ScriptEvent::Kind::Up;
      e.key = *key;
    } else if (w.size() == 4 && w[1] == "mouse") {
      if (!parse_double(w[2], e.dx) || !parse_double(w[3], e.dy)) {
        throw std::runtime_error(where + "mouse expects two numbers DX DY, got '" + w[2] + " " + w[3] + "'");
      }
      e.kind = ScriptEvent::Kind::Mouse;
    } else if (w.size() == 3 && w[1] == "button") {
      const auto button = button_from_name(w[2]);
      if (!button) throw std::runtime_error(where + "unknown button '" + w[2] + "' (buttons: " + button_names() + ")");
      e.kind = ScriptEvent::Kind::Button;
      e.button = *button;
    } else if (w.size() == 4 && w[1] == "set") {
      const auto setting = setting_from_name(w[2]);
      if (!setting) throw std::runtime_error(where + "unknown setting '" + w[2] + "' (settings: " + setting_names() + ")");
      if (!parse_double(w[3], e.value)) throw std::runtime_error(where + "set " + w[2] + " expects a number, got '" + w[3] + "'");
      e.kind = ScriptEvent::Kind::Set;
      e.setting = *setting;
    } else {
      throw std::runtime_error(where + "expected 'TIME down KEY', 'TIME up KEY', 'TIME mouse DX DY', 'TIME set NAME VALUE' or 'TIME button NAME', got '" +
                               line + "'");
    }
    events.push_back(e);
  }
  return events;
}

void Controls::step(Observer& observer, double dt) {
  for (const Motion& m : m_mouse) {
    if (m.dx != 0.0) observer.yaw(m.dx * kMouseTurn);
    if (m.dy != 0.0) observer.pitch(-m.dy * kMouseTurn);
  }
  m_mouse.clear();
  auto axis = [&](Key plus, Key minus) { return (held(plus) ? 1.0 : 0.0) - (held(minus) ? 1.0 : 0.0); };
  const double turn = kTurnRate * dt;
  if (const double a = axis(Key::Right, Key::Left); a != 0.0) observer.yaw(a * turn);
  if (const double a = axis(Key::Up, Key::Down); a != 0.0) observer.pitch(a * turn);
  if (const double a = axis(Key::E, Key::Q); a != 0.0) observer.roll(a * turn);
  const glm::dvec3 direction(axis(Key::D, Key::A), axis(Key::R, Key::F), axis(Key::W, Key::S));
  if (direction != glm::dvec3(0.0)) {
    const double speed = kSpeed * (held(Key::Shift) ? kShiftFactor : 1.0);
    observer.move(glm::normalize(direction), speed * dt);
  }
}

}  // namespace sol::viewer
