#include "sol/scene.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "sol/error.hpp"
#include "sol/lattice.hpp"

namespace sol {
namespace {

using nlohmann::json;

// The line on which each value of a JSON text starts, by path ("camera.fov",
// "objects[2].radius"): nlohmann::json keeps no positions, so errors found
// after parsing take their line from here. Run on text that parsed.
class LineIndex {
 public:
  explicit LineIndex(std::string_view text) : m_text(text) { value(""); }
  const std::map<std::string, int>& lines() const { return m_lines; }

 private:
  bool more() const { return m_pos < m_text.size(); }
  void skip_space() {
    while (more() && std::isspace(static_cast<unsigned char>(m_text[m_pos]))) {
      if (m_text[m_pos] == '\n') ++m_line;
      ++m_pos;
    }
  }
  std::string string() {
    std::string out;
    ++m_pos;  // opening quote
    while (more() && m_text[m_pos] != '"') {
      if (m_text[m_pos] == '\\' && m_pos + 1 < m_text.size()) ++m_pos;
      out += m_text[m_pos++];
    }
    ++m_pos;  // closing quote
    return out;
  }
  void value(const std::string& path) {
    skip_space();
    if (!more()) return;
    m_lines.emplace(path, m_line);
    const char c = m_text[m_pos];
    if (c == '{') {
      ++m_pos;
      for (;;) {
        skip_space();
        if (!more() || m_text[m_pos] == '}') break;
        if (m_text[m_pos] == ',') {
          ++m_pos;
          continue;
        }
        const std::string key = string();
        skip_space();
        if (more() && m_text[m_pos] == ':') ++m_pos;
        value(path.empty() ? key : path + "." + key);
      }
      ++m_pos;
    } else if (c == '[') {
      ++m_pos;
      for (int i = 0;; ++i) {
        skip_space();
        if (!more() || m_text[m_pos] == ']') break;
        if (m_text[m_pos] == ',') {
          ++m_pos;
          --i;
          continue;
        }
        value(path + "[" + std::to_string(i) + "]");
      }
      ++m_pos;
    } else if (c == '"') {
      string();
    } else {
      while (more() && std::string_view(",}] \t\r\n").find(m_text[m_pos]) == std::string_view::npos) ++m_pos;
    }
  }

  std::string_view m_text;
  std::size_t m_pos = 0;
  int m_line = 1;
  std::map<std::string, int> m_lines;
};

// The index of the text being parsed (parse_scene sets it), so that every
// error message can say where in the file its field is.
thread_local const LineIndex* t_lines = nullptr;

bool identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// " (line N)" for the longest field path named in `what` (or `path`), if known.
std::string where_in_file(const std::string& what, const std::string& path) {
  if (!t_lines) return {};
  const auto& lines = t_lines->lines();
  if (!path.empty()) {
    const auto it = lines.find(path);
    return it == lines.end() ? std::string() : " (line " + std::to_string(it->second) + ")";
  }
  std::size_t best_length = 0;
  int best_line = 0;
  for (const auto& [p, line] : lines) {
    if (p.size() <= best_length) continue;
    for (std::size_t at = what.find(p); at != std::string::npos; at = what.find(p, at + 1)) {
      const bool starts = at == 0 || !identifier_char(what[at - 1]);
      const std::size_t end = at + p.size();
      const bool ends = end == what.size() || (!identifier_char(what[end]) && what[end] != '[');
      if (starts && ends) {
        best_length = p.size();
        best_line = line;
        break;
      }
    }
  }
  return best_length ? " (line " + std::to_string(best_line) + ")" : std::string();
}

[[noreturn]] void fail(std::string_view source, const std::string& what, const std::string& path = {}) {
  throw InvalidArgument(std::string(source) + ": " + what + where_in_file(what, path));
}

void require_known_keys(const json& object, std::initializer_list<const char*> keys, std::string_view source,
                        const std::string& where, const std::string& path = {}) {
  const std::set<std::string> known(keys.begin(), keys.end());
  for (const auto& item : object.items()) {
    if (!known.count(item.key())) {
      std::string list;
      for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      fail(source, "unknown key '" + item.key() + "' in " + where + " (known: " + list + ")",
           path.empty() ? item.key() : path + "." + item.key());
    }
  }
}

double number(const json& value, std::string_view source, const std::string& name) {
  if (!value.is_number()) fail(source, "'" + name + "' must be a number, got " + value.dump());
  const double v = value.get<double>();
  if (!std::isfinite(v)) fail(source, "'" + name + "' must be finite");
  return v;
}

glm::dvec3 vec3(const json& value, std::string_view source, const std::string& name) {
  if (!value.is_array() || value.size() != 3) fail(source, "'" + name + "' must be an array of 3 numbers, got " + value.dump());
  return {number(value[0], source, name + "[0]"), number(value[1], source, name + "[1]"),
          number(value[2], source, name + "[2]")};
}

ObjectType object_type(const json& value, std::string_view source, const std::string& name) {
  const std::string s = value.is_string() ? value.get<std::string>() : value.dump();
  if (s == "plane_x") return ObjectType::PlaneX;
  if (s == "plane_y") return ObjectType::PlaneY;
  if (s == "plane_z") return ObjectType::PlaneZ;
  if (s == "ball") return ObjectType::Ball;
  if (s == "tube") return ObjectType::Tube;
  fail(source, "'" + name + "' must be one of plane_x, plane_y, plane_z, ball, tube, got " + s);
}

// JSON names of the tube axes, indexed by TubeAxis.
constexpr const char* kAxisNames[] = {"x", "y", "z", "gamma1", "gamma2"};

Pattern pattern(const json& value, std::string_view source, const std::string& name) {
  const std::string s = value.is_string() ? value.get<std::string>() : value.dump();
  if (s == "none") return Pattern::None;
  if (s == "circles") return Pattern::Circles;
  if (s == "checker") return Pattern::Checker;
  fail(source, "'" + name + "' must be one of none, circles, checker, got " + s);
}

void validate_in(const Scene& s, std::string_view source) {
  const Camera& c = s.camera;
  auto finite3 = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  // Beyond 1e15 double cannot resolve unit-size features (ulp 0.125) and the
  // float AOVs cannot hold the coordinates: such input is refused.
  constexpr double kMaxCoordinate = 1e15;
  auto bounded3 = [&](const glm::dvec3& v) {
    return finite3(v) && std::abs(v.x) <= kMaxCoordinate && std::abs(v.y) <= kMaxCoordinate &&
           std::abs(v.z) <= kMaxCoordinate;
  };
  if (!bounded3(c.position)) fail(source, "camera.position must be finite and within 1e15 of the origin");
  if (!finite3(c.forward) || glm::length(c.forward) == 0.0) fail(source, "camera.forward must be finite and non-zero");
  if (!finite3(c.up) || glm::length(c.up) == 0.0) fail(source, "camera.up must be finite and non-zero");
  if (glm::length(glm::cross(glm::normalize(c.forward), glm::normalize(c.up))) < 1e-9) {
    fail(source, "camera.forward and camera.up must not be parallel");
  }
  if (!(c.fov > 0.0 && c.fov < 180.0)) fail(source, "camera.fov must be in (0, 180) degrees");
  if (c.frustum) {
    // Tangents up to 1e3: edges up to 89.94° from forward.
    const Frustum& f = *c.frustum;
    for (const double v : {f.left, f.right, f.down, f.up}) {
      if (!(std::abs(v) <= 1e3)) fail(source, "camera.frustum tangents must be finite and within [-1000, 1000]");
    }
    if (!(f.left < f.right) || !(f.down < f.up)) {
      fail(source, "camera.frustum must have left < right and down < up");
    }
  }
  if (s.objects.empty()) fail(source, "the scene has no objects");
  if (s.objects.size() > 64) fail(source, "at most 64 objects, got " + std::to_string(s.objects.size()));
  if (s.quotient == Quotient::Golden) {
    const Lattice lattice = Lattice::golden();
    for (std::size_t i = 0; i < s.objects.size(); ++i) {
      const SceneObject& o = s.objects[i];
      const std::string at = "objects[" + std::to_string(i) + "]";
      if (o.type == ObjectType::PlaneX || o.type == ObjectType::PlaneY) {
        fail(source, at + ".type: planes x, y = c are not supported in the quotient (Γ maps them to planes of "
                          "every slope, dense in M)");
      }
      if ((o.type == ObjectType::Ball || o.type == ObjectType::Tube) && o.radius > kMaxQuotientRadius) {
        fail(source, at + ".radius must be <= 0.45 in the quotient (one cell's height, 2 ln φ, less the longest step)");
      }
      if (o.type != ObjectType::Tube) continue;
      if (o.axis == kAxisX || o.axis == kAxisY) {
        fail(source, at + ".axis: tubes along x or y do not close up in the quotient (their images are dense); "
                          "use gamma1, gamma2 or z");
      }
      if (o.axis == kAxisZ && std::isfinite(o.center.x) && std::isfinite(o.center.y)) {
        // A vertical line closes up (as the curve of γ3) when it passes through
        // a lattice point of ⟨γ1, γ2⟩, which γ3 maps into the lattice.
        const glm::dvec2 st = lattice.lattice_coordinates(o.center.x, o.center.y);
        if (std::abs(st.x - std::round(st.x)) > 1e-9 || std::abs(st.y - std::round(st.y)) > 1e-9) {
          fail(source, at + ".through: a tube along z in the quotient must pass through a point (x, y) of the "
                            "lattice ⟨γ1, γ2⟩ (then it is the closed curve of γ3)");
        }
      }
    }
  }
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const SceneObject& o = s.objects[i];
    const std::string at = "objects[" + std::to_string(i) + "]";
    if (!std::isfinite(o.c) || std::abs(o.c) > kMaxCoordinate) fail(source, at + ".c must be finite and within 1e15");
    if (o.type == ObjectType::Ball || o.type == ObjectType::Tube) {
      if (!bounded3(o.center)) fail(source, at + ".center must be finite and within 1e15 of the origin");
      if (!(o.radius > 0.0) || !std::isfinite(o.radius)) fail(source, at + ".radius must be finite and > 0");
      if (o.type == ObjectType::Tube && (o.axis < kAxisX || o.axis > kAxisGamma2)) {
        fail(source, at + ".axis must be x, y, z, gamma1 or gamma2");
      }
    }
    if (o.cutout && (o.type == ObjectType::Ball || o.type == ObjectType::Tube || o.pattern == Pattern::None)) {
      fail(source, at + ".cutout needs a plane with a pattern (circles or checker)");
    }
    for (int k = 0; k < 3; ++k) {
      if (!(o.color[k] >= 0.0 && o.color[k] <= 1.0)) fail(source, at + ".color components must be in [0, 1]");
    }
  }
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    if (!(l.reach >= 0.0 && l.reach <= 10.0)) {
      fail(source, "lights[" + std::to_string(i) + "].reach must be in [0, 10]");
    }
  }
  if (s.lights.size() > static_cast<std::size_t>(kMaxLights)) {
    fail(source, "at most " + std::to_string(kMaxLights) + " lights, got " + std::to_string(s.lights.size()));
  }
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    const std::string at = "lights[" + std::to_string(i) + "]";
    if (l.type == LightType::Directional && (!finite3(l.direction) || glm::length(l.direction) == 0.0)) {
      fail(source, at + ".direction must be finite and non-zero");
    }
    if (l.type == LightType::Point && !bounded3(l.position)) {
      fail(source, at + ".position must be finite and within 1e15 of the origin");
    }
    for (int k = 0; k < 3; ++k) {
      if (!(l.color[k] >= 0.0 && l.color[k] <= 1.0)) fail(source, at + ".color components must be in [0, 1]");
    }
    if (!(l.intensity >= 0.0) || !std::isfinite(l.intensity)) fail(source, at + ".intensity must be finite and >= 0");
  }
  if (!(s.ambient >= 0.0 && s.ambient <= 1.0)) fail(source, "ambient must be in [0, 1]");
  for (int k = 0; k < 3; ++k) {
    if (!(s.fog_color[k] >= 0.0 && s.fog_color[k] <= 1.0)) fail(source, "fog.color components must be in [0, 1]");
  }
  if (!(s.fog_density >= 0.0) || !std::isfinite(s.fog_density)) fail(source, "fog.density must be finite and >= 0");
  if (!(s.max_distance > 0.0 && s.max_distance <= 1e4)) fail(source, "max_distance must be in (0, 10000]");
  if (!(s.max_steps >= 1 && s.max_steps <= 100000)) fail(source, "max_steps must be in [1, 100000]");
  if (!(s.hit_epsilon > 0.0 && s.hit_epsilon <= 0.1)) fail(source, "hit_epsilon must be in (0, 0.1]");
}

}  // namespace

const char* to_string(ObjectType type) {
  switch (type) {
    case ObjectType::PlaneX:
      return "plane_x";
    case ObjectType::PlaneY:
      return "plane_y";
    case ObjectType::PlaneZ:
      return "plane_z";
    case ObjectType::Ball:
      return "ball";
    case ObjectType::Tube:
      return "tube";
  }
  return "?";
}

const char* to_string(Pattern p) {
  switch (p) {
    case Pattern::None:
      return "none";
    case Pattern::Circles:
      return "circles";
    case Pattern::Checker:
      return "checker";
  }
  return "?";
}

void validate(const Scene& scene) { validate_in(scene, "sol::validate(Scene)"); }

Scene parse_scene(std::string_view text, std::string_view source) {
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {  // syntax errors and numbers out of range
    fail(source, std::string("malformed JSON: ") + e.what());
  }
  const LineIndex index(text);
  struct Scope {  // the index is in effect for this parse only
    explicit Scope(const LineIndex* i) { t_lines = i; }
    ~Scope() { t_lines = nullptr; }
  } scope(&index);
  if (!root.is_object()) fail(source, "the scene must be a JSON object");
  require_known_keys(root,
                     {"camera", "objects", "lights", "ambient", "fog", "light", "fog_distance", "max_distance",
                      "max_steps", "hit_epsilon", "quotient"},
                     source, "the scene");
  Scene s;
  if (root.contains("camera")) {
    const json& c = root["camera"];
    if (!c.is_object()) fail(source, "'camera' must be an object");
    require_known_keys(c, {"position", "forward", "up", "fov", "frustum"}, source, "camera", "camera");
    if (c.contains("position")) s.camera.position = vec3(c["position"], source, "camera.position");
    if (c.contains("forward")) s.camera.forward = vec3(c["forward"], source, "camera.forward");
    if (c.contains("up")) s.camera.up = vec3(c["up"], source, "camera.up");
    if (c.contains("fov")) s.camera.fov = number(c["fov"], source, "camera.fov");
    if (c.contains("frustum")) {
      const json& f = c["frustum"];
      if (!f.is_array() || f.size() != 4) {
        fail(source, "'camera.frustum' must be an array of 4 numbers [left, right, down, up], got " + f.dump());
      }
      s.camera.frustum = Frustum{number(f[0], source, "camera.frustum[0]"), number(f[1], source, "camera.frustum[1]"),
                                 number(f[2], source, "camera.frustum[2]"), number(f[3], source, "camera.frustum[3]")};
    }
  }
  if (!root.contains("objects") || !root["objects"].is_array()) fail(source, "'objects' must be an array");
  const json& objects = root["objects"];
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const json& o = objects[i];
    const std::string at = "objects[" + std::to_string(i) + "]";
    if (!o.is_object()) fail(source, at + " must be an object");
    if (!o.contains("type")) fail(source, at + " needs a 'type'");
    SceneObject obj;
    obj.type = object_type(o["type"], source, at + ".type");
    if (obj.type == ObjectType::Ball) {
      require_known_keys(o, {"type", "center", "radius", "color", "pattern", "exact"}, source, at + " (a ball)", at);
      if (!o.contains("center")) fail(source, at + " (a ball) needs a 'center'");
      if (!o.contains("radius")) fail(source, at + " (a ball) needs a 'radius'");
      obj.center = vec3(o["center"], source, at + ".center");
      obj.radius = number(o["radius"], source, at + ".radius");
      if (o.contains("exact")) {
        if (!o["exact"].is_boolean()) fail(source, "'" + at + ".exact' must be true or false, got " + o["exact"].dump());
        obj.exact = o["exact"].get<bool>();
      }
    } else if (obj.type == ObjectType::Tube) {
      require_known_keys(o, {"type", "axis", "through", "radius", "color", "pattern"}, source, at + " (a tube)", at);
      for (const char* key : {"axis", "through", "radius"}) {
        if (!o.contains(key)) fail(source, at + " (a tube) needs '" + key + "'");
      }
      const std::string axis = o["axis"].is_string() ? o["axis"].get<std::string>() : o["axis"].dump();
      const auto known = std::find(std::begin(kAxisNames), std::end(kAxisNames), axis);
      if (axis == "gamma3") {
        obj.axis = kAxisZ;  // the closed curve of γ3 is the vertical line
      } else if (known == std::end(kAxisNames)) {
        fail(source, "'" + at + ".axis' must be x, y, z, gamma1, gamma2 or gamma3, got " + axis);
      } else {
        obj.axis = static_cast<int>(known - std::begin(kAxisNames));
      }
      obj.center = vec3(o["through"], source, at + ".through");
      obj.radius = number(o["radius"], source, at + ".radius");
    } else {
      require_known_keys(o, {"type", "c", "color", "pattern", "cutout"}, source, at, at);
      if (o.contains("cutout")) {
        if (!o["cutout"].is_boolean()) fail(source, "'" + at + ".cutout' must be true or false, got " + o["cutout"].dump());
        obj.cutout = o["cutout"].get<bool>();
      }
    }
    if (o.contains("c")) obj.c = number(o["c"], source, at + ".c");
    if (o.contains("color")) obj.color = vec3(o["color"], source, at + ".color");
    if (o.contains("pattern")) obj.pattern = pattern(o["pattern"], source, at + ".pattern");
    s.objects.push_back(obj);
  }
  // "light" and "fog_distance": the first schema's single directional light and fog.
  if (root.contains("light")) {
    const json& l = root["light"];
    if (!l.is_object()) fail(source, "'light' must be an object");
    require_known_keys(l, {"direction", "ambient"}, source, "light", "light");
    if (l.contains("direction")) s.lights[0].direction = vec3(l["direction"], source, "light.direction");
    if (l.contains("ambient")) s.ambient = number(l["ambient"], source, "light.ambient");
  }
  if (root.contains("lights")) {
    if (root.contains("light")) fail(source, "give either 'light' or 'lights', not both");
    const json& list = root["lights"];
    if (!list.is_array()) fail(source, "'lights' must be an array");
    s.lights.clear();
    for (std::size_t i = 0; i < list.size(); ++i) {
      const json& l = list[i];
      const std::string at = "lights[" + std::to_string(i) + "]";
      if (!l.is_object()) fail(source, at + " must be an object");
      if (!l.contains("type")) fail(source, at + " needs a 'type' (directional or point)");
      Light light;
      const std::string type = l["type"].is_string() ? l["type"].get<std::string>() : l["type"].dump();
      if (type == "directional") {
        light.type = LightType::Directional;
        require_known_keys(l, {"type", "direction", "color", "intensity"}, source, at, at);
        if (l.contains("direction")) light.direction = vec3(l["direction"], source, at + ".direction");
      } else if (type == "point") {
        light.type = LightType::Point;
        require_known_keys(l, {"type", "position", "color", "intensity", "exact", "reach"}, source, at, at);
        if (!l.contains("position")) fail(source, at + " (a point light) needs a 'position'");
        light.position = vec3(l["position"], source, at + ".position");
        if (l.contains("exact")) {
          if (!l["exact"].is_boolean()) fail(source, "'" + at + ".exact' must be true or false, got " + l["exact"].dump());
          light.exact = l["exact"].get<bool>();
        }
        if (l.contains("reach")) light.reach = number(l["reach"], source, at + ".reach");
      } else {
        fail(source, "'" + at + ".type' must be directional or point, got " + type);
      }
      if (l.contains("color")) light.color = vec3(l["color"], source, at + ".color");
      if (l.contains("intensity")) light.intensity = number(l["intensity"], source, at + ".intensity");
      s.lights.push_back(light);
    }
  }
  if (root.contains("ambient")) s.ambient = number(root["ambient"], source, "ambient");
  if (root.contains("quotient")) {
    const json& q = root["quotient"];
    const std::string name = q.is_string() ? q.get<std::string>() : q.dump();
    if (name == "none") {
      s.quotient = Quotient::None;
    } else if (name == "golden") {
      s.quotient = Quotient::Golden;
    } else {
      fail(source, "'quotient' must be none or golden, got " + name);
    }
  }
  if (root.contains("fog_distance")) {
    const double d = number(root["fog_distance"], source, "fog_distance");
    if (d < 0.0) fail(source, "fog_distance must be >= 0");
    s.fog_density = d > 0.0 ? 1.0 / d : 0.0;
  }
  if (root.contains("fog")) {
    if (root.contains("fog_distance")) fail(source, "give either 'fog' or 'fog_distance', not both");
    const json& f = root["fog"];
    if (!f.is_object()) fail(source, "'fog' must be an object");
    require_known_keys(f, {"color", "density"}, source, "fog", "fog");
    if (f.contains("color")) s.fog_color = vec3(f["color"], source, "fog.color");
    if (f.contains("density")) s.fog_density = number(f["density"], source, "fog.density");
  }
  if (root.contains("max_distance")) s.max_distance = number(root["max_distance"], source, "max_distance");
  if (root.contains("hit_epsilon")) s.hit_epsilon = number(root["hit_epsilon"], source, "hit_epsilon");
  if (root.contains("max_steps")) {
    const json& m = root["max_steps"];
    if (!m.is_number_integer()) fail(source, "'max_steps' must be an integer, got " + m.dump());
    const auto v = m.get<long long>();
    if (v < 1 || v > 100000) fail(source, "max_steps must be in [1, 100000]");
    s.max_steps = static_cast<int>(v);
  }
  validate_in(s, source);
  return s;
}

bool uses_exact_lights(const Scene& scene) {
  return std::any_of(scene.lights.begin(), scene.lights.end(),
                     [](const Light& l) { return l.type == LightType::Point && l.exact; });
}

bool uses_exact(const Scene& scene) {
  return std::any_of(scene.objects.begin(), scene.objects.end(), [](const SceneObject& o) { return o.exact; }) ||
         uses_exact_lights(scene);
}

Scene load_scene(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidArgument(path + ": cannot open scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InvalidArgument(path + ": cannot read scene file");
  return parse_scene(text.str(), path);
}

std::vector<std::string> preset_names() {
  return {"plane", "sandwich", "sheets", "lattice-balls", "lattice-pillars", "spheres"};
}

glm::dvec3 tube_axis_direction(int axis) {
  constexpr double phi = kernel::kPhi;
  switch (axis) {
    case kAxisX:
      return {1.0, 0.0, 0.0};
    case kAxisY:
      return {0.0, 1.0, 0.0};
    case kAxisGamma1:
      return glm::normalize(glm::dvec3(phi, -1.0, 0.0));
    case kAxisGamma2:
      return glm::normalize(glm::dvec3(1.0, phi, 0.0));
    default:
      return {0.0, 0.0, 1.0};
  }
}

Scene preset_scene(std::string_view name) {
  Scene s;
  if (name == "plane") {
    // The paper's "rolled into a tube" view: z = 0 seen from above.
    s.camera = {{0.0, 0.0, 1.5}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
    s.objects = {{ObjectType::PlaneZ, 0.0, {0.95, 0.75, 0.3}, Pattern::Circles}};
  } else if (name == "sandwich") {
    // Looking along x + y: rays tilted up reach z = 1, tilted down z = -1
    // (straight along x every ray bends down, along y up).
    s.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 90.0};
    s.objects = {{ObjectType::PlaneZ, 1.0, {0.35, 0.6, 0.95}, Pattern::Circles},
                 {ObjectType::PlaneZ, -1.0, {0.95, 0.55, 0.3}, Pattern::Circles}};
    s.fog_density = 1.0 / 20.0;
  } else if (name == "sheets") {
    s.camera = {{1.0, 1.5, 0.2}, glm::normalize(glm::dvec3(-1.0, -1.2, -0.1)), {0.0, 0.0, 1.0}, 75.0};
    s.objects = {{ObjectType::PlaneX, 0.0, {0.9, 0.4, 0.35}, Pattern::Checker},
                 {ObjectType::PlaneY, 0.0, {0.35, 0.8, 0.45}, Pattern::Checker}};
    s.fog_density = 1.0 / 25.0;
  } else if (name == "lattice-balls") {
    // One ball at the base point of M = Γ\Sol: in the cover, a ball at every
    // point of Γ·o. Looking along z from inside the domain.
    s.quotient = Quotient::Golden;
    s.camera = {{0.9, 0.3, 0.45}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0};
    SceneObject ball;
    ball.type = ObjectType::Ball;
    ball.center = {0.0, 0.0, 0.0};
    ball.radius = 0.25;
    ball.color = {0.9, 0.55, 0.3};
    s.objects = {ball};
    s.fog_density = 1.0 / 12.0;
    s.max_distance = 12.0;
    s.max_steps = 400;
  } else if (name == "lattice-pillars") {
    // Tubes along the closed curves of γ1, γ2 and γ3 through the base point
    // of M: in the cover they run along the edges of the fundamental domains
    // and stake them out. Looking along x = y from the middle of the domain.
    s.quotient = Quotient::Golden;
    s.camera = {{1.3, 0.3, 0.48}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 90.0};
    SceneObject tube;
    tube.type = ObjectType::Tube;
    tube.radius = 0.06;
    for (const auto& [axis, color] : {std::pair{kAxisGamma1, glm::dvec3(0.9, 0.35, 0.3)},
                                      std::pair{kAxisGamma2, glm::dvec3(0.35, 0.8, 0.4)},
                                      std::pair{kAxisZ, glm::dvec3(0.35, 0.5, 0.95)}}) {
      tube.axis = axis;
      tube.color = color;
      s.objects.push_back(tube);
    }
    s.fog_density = 1.0 / 5.0;
    s.max_distance = 10.0;
    s.max_steps = 400;
  } else if (name == "spheres") {
    // True geodesic spheres (exact balls) of radii 0.3 to 0.6 on, above and
    // below z = 0, seen from the origin along x + y: above z = 0 they stretch
    // along y, below along x (where e^{∓z} makes that direction cheap). An
    // exact point light near the observer.
    s.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 100.0};
    const struct {
      glm::dvec3 center;
      double radius;
      glm::dvec3 color;
    } balls[] = {{{2.0, 2.0, 0.0}, 0.6, {0.9, 0.55, 0.3}},
                 {{1.0, 1.0, 1.0}, 0.4, {0.35, 0.6, 0.95}},
                 {{1.0, 1.0, -1.0}, 0.4, {0.4, 0.85, 0.45}},
                 {{2.0, 0.2, 0.0}, 0.3, {0.9, 0.85, 0.4}},
                 {{0.2, 2.0, 0.0}, 0.3, {0.85, 0.4, 0.8}}};
    for (const auto& b : balls) {
      SceneObject ball;
      ball.type = ObjectType::Ball;
      ball.center = b.center;
      ball.radius = b.radius;
      ball.color = b.color;
      ball.pattern = Pattern::Checker;
      ball.exact = true;
      s.objects.push_back(ball);
    }
    Light point;
    point.type = LightType::Point;
    point.position = {0.3, 0.2, 0.4};
    point.intensity = 4.0;
    point.exact = true;
    s.lights = {point};
    s.ambient = 0.2;
    s.max_distance = 14.0;
  } else {
    std::string list;
    for (const std::string& n : preset_names()) list += (list.empty() ? "" : ", ") + n;
    throw InvalidArgument("unknown preset '" + std::string(name) + "' (presets: " + list + ")");
  }
  return s;
}

std::string to_json(const Scene& s) {
  auto arr = [](const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); };
  json root;
  root["camera"] = {{"position", arr(s.camera.position)},
                    {"forward", arr(s.camera.forward)},
                    {"up", arr(s.camera.up)},
                    {"fov", s.camera.fov}};
  if (s.camera.frustum) {
    const Frustum& f = *s.camera.frustum;
    root["camera"]["frustum"] = json::array({f.left, f.right, f.down, f.up});
  }
  root["objects"] = json::array();
  for (const SceneObject& o : s.objects) {
    if (o.type == ObjectType::Tube) {
      root["objects"].push_back({{"type", to_string(o.type)},
                                 {"axis", kAxisNames[std::clamp(o.axis, 0, 4)]},
                                 {"pattern", to_string(o.pattern)},
                                 {"through", arr(o.center)},
                                 {"radius", o.radius},
                                 {"color", arr(o.color)}});
    } else if (o.type == ObjectType::Ball) {
      root["objects"].push_back({{"type", to_string(o.type)},
                                 {"center", arr(o.center)},
                                 {"radius", o.radius},
                                 {"pattern", to_string(o.pattern)},
                                 {"color", arr(o.color)},
                                 {"exact", o.exact}});
    } else {
      root["objects"].push_back({{"type", to_string(o.type)},
                                 {"c", o.c},
                                 {"color", arr(o.color)},
                                 {"pattern", to_string(o.pattern)},
                                 {"cutout", o.cutout}});
    }
  }
  root["lights"] = json::array();
  for (const Light& l : s.lights) {
    json j = {{"color", arr(l.color)}, {"intensity", l.intensity}};
    if (l.type == LightType::Directional) {
      j["type"] = "directional";
      j["direction"] = arr(l.direction);
    } else {
      j["type"] = "point";
      j["position"] = arr(l.position);
      j["exact"] = l.exact;
      j["reach"] = l.reach;
    }
    root["lights"].push_back(j);
  }
  root["ambient"] = s.ambient;
  root["fog"] = {{"color", arr(s.fog_color)}, {"density", s.fog_density}};
  root["quotient"] = s.quotient == Quotient::Golden ? "golden" : "none";
  root["max_distance"] = s.max_distance;
  root["max_steps"] = s.max_steps;
  root["hit_epsilon"] = s.hit_epsilon;
  return root.dump(2);
}

}  // namespace sol
