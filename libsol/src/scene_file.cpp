#include "sol/scene_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <numbers>
#include <sstream>

#include "field_error.hpp"
#include "objects_internal.hpp"
#include "scene_reader.hpp"
#include "spaces/space_io.hpp"
#include "sol/aim.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"

namespace sol {
namespace detail {
void check_camera(const Camera& camera);  // camera.cpp
void check_world(const World& world);     // scene.cpp
void check_display(const Display& display);  // display.cpp
}  // namespace detail

namespace {

using detail::SceneFileReader;
using nlohmann::json;

// The camera's keys; a "look_at" point is returned, for the caller to aim
// the camera once the world's space is known.
std::optional<glm::dvec3> read_camera(const json& c, const SceneFileReader& r, Camera& camera) {
  if (!c.is_object()) r.fail("camera", "'camera' must be an object");
  r.require_known_keys(c,
                       {"position", "forward", "look_at", "up", "fov", "frustum", "projection", "fisheye_fov", "aperture",
                        "focus_distance"},
                       "camera", "camera");
  if (c.contains("look_at") && c.contains("forward")) {
    r.fail("camera.look_at", "camera: give either 'forward' or 'look_at', not both");
  }
  if (c.contains("projection")) {
    camera.projection = r.choice<Projection>(c["projection"], "camera.projection",
                                             {{"perspective", Projection::Perspective},
                                              {"equirectangular", Projection::Equirectangular},
                                              {"fisheye", Projection::Fisheye}});
  }
  if (c.contains("fisheye_fov")) camera.fisheye_fov = r.number(c["fisheye_fov"], "camera.fisheye_fov");
  if (c.contains("position")) camera.position = r.vec3(c["position"], "camera.position");
  if (c.contains("forward")) camera.forward = r.vec3(c["forward"], "camera.forward");
  if (c.contains("up")) camera.up = r.vec3(c["up"], "camera.up");
  if (c.contains("fov")) camera.fov = r.number(c["fov"], "camera.fov");
  if (c.contains("aperture")) camera.aperture = r.number(c["aperture"], "camera.aperture");
  if (c.contains("focus_distance")) camera.focus_distance = r.number(c["focus_distance"], "camera.focus_distance");
  if (c.contains("frustum")) {
    const json& f = c["frustum"];
    if (!f.is_array() || f.size() != 4) {
      r.fail("camera.frustum", "'camera.frustum' must be an array of 4 numbers [left, right, down, up], got " + SceneFileReader::json_text(f));
    }
    camera.frustum = Frustum{r.number(f[0], "camera.frustum[0]"), r.number(f[1], "camera.frustum[1]"),
                             r.number(f[2], "camera.frustum[2]"), r.number(f[3], "camera.frustum[3]")};
  }
  if (!c.contains("look_at")) return std::nullopt;
  return r.vec3(c["look_at"], "camera.look_at");
}

// The camera turned towards `target` in the world's space (sol::looking_at);
// without a focus distance of its own (`focus`) the lens focuses there.
void aim_camera(Camera& camera, const glm::dvec3& target, const std::optional<Lattice>& lattice, bool focus,
                const SceneFileReader& r) {
  try {
    detail::check_position(target, "camera.look_at");
    detail::check_position(camera.position, "camera.position");
  } catch (const detail::FieldError& e) {
    r.fail(e.path(), e.what());
  }
  // The library's messages name their function ("sol::aim: ..."): the file's field instead.
  auto fail = [&](const std::string& what) { r.fail("camera.look_at", "camera.look_at: " + without_function(what)); };
  try {
    const double given = camera.focus_distance;
    camera = looking_at(camera, target, lattice);
    if (!focus) camera.focus_distance = given;
  } catch (const InvalidArgument& e) {
    fail(e.what());
  } catch (const OutOfRange& e) {
    fail(e.what());
  }
}

Light read_light(const json& l, const SceneFileReader& r, const std::string& at) {
  if (!l.is_object()) r.fail(at, at + " must be an object");
  if (!l.contains("type")) r.fail(at, at + " needs a 'type' (directional or point)");
  Light light;
  const std::string type = SceneFileReader::text(l["type"]);
  if (type == "directional") {
    light.type = LightType::Directional;
    r.require_known_keys(l, {"type", "direction", "color", "intensity"}, at, at);
    if (l.contains("direction")) light.direction = r.vec3(l["direction"], at + ".direction");
  } else if (type == "point") {
    light.type = LightType::Point;
    r.require_known_keys(l, {"type", "position", "color", "intensity", "power", "exact", "reach", "falloff", "shadows"},
                         at, at);
    r.require_key(l, "position", at + " (a point light)", "a 'position'", at);
    light.position = r.vec3(l["position"], at + ".position");
    if (l.contains("exact")) light.exact = r.boolean(l["exact"], at + ".exact");
    if (l.contains("reach")) light.reach = r.number(l["reach"], at + ".reach");
    if (l.contains("falloff")) {
      light.falloff = r.choice<Falloff>(l["falloff"], at + ".falloff",
                                        {{"geodesic", Falloff::Geodesic}, {"inverse-square", Falloff::InverseSquare}});
    }
    if (l.contains("power")) {
      // The radiant power Φ, spread over the sphere of directions: I = Φ / 4π.
      if (l.contains("intensity")) r.fail(at + ".power", at + " takes 'power' or 'intensity', not both");
      const double power = r.number(l["power"], at + ".power");
      if (!(power >= 0.0) || !(power <= 4e9 * std::numbers::pi)) {
        r.fail(at + ".power", at + ".power must be in [0, 4pi x 1e9] (watts; intensity = power / 4pi)");
      }
      light.intensity = power / (4.0 * std::numbers::pi);
    }
  } else {
    r.fail(at + ".type", "'" + at + ".type' must be directional or point, got " + SceneFileReader::json_text(l["type"]));
  }
  if (l.contains("shadows")) light.shadows = r.boolean(l["shadows"], at + ".shadows");
  if (l.contains("color")) light.color = r.vec3(l["color"], at + ".color");
  if (l.contains("intensity")) light.intensity = r.number(l["intensity"], at + ".intensity");
  return light;
}

// An entry of "objects" (`at` its path) into `out`: an object, or an array
// of one, {"type": "array", "of": {...}, "count": [nx, ny, nz], "step":
// [sx, sy, sz]}: the nx·ny·nz left translates g·o of its object o (itself
// an object or an array) by the points g = (i sx, j sy, k sz), 0 <= i < nx,
// 0 <= j < ny, 0 <= k < nz, i the fastest. Left translations are Sol's
// isometries and take every kind to itself (shape_seen_from(o, g⁻¹)), so
// the copies are objects of the scene like any other. `origins` receives,
// for each object, the index in `paths` of its entry in the file (a copy's:
// its array's object), which the scene's checks name; `paths` holds each
// entry once, however many copies it makes.
void read_objects(const json& o, const SceneFileReader& r, const std::string& at, const Lattice* lattice,
                  std::vector<SceneObject>& out, std::vector<std::string>& paths, std::vector<std::uint32_t>& origins) {
  if (!o.is_object() || !o.contains("type") || o["type"] != "array") {
    out.push_back(detail::read_object(o, r, at, lattice));
    paths.push_back(at);
    origins.push_back(static_cast<std::uint32_t>(paths.size() - 1));
    return;
  }
  r.require_known_keys(o, {"type", "of", "count", "step"}, at + " (an array)", at);
  r.require_key(o, "of", at + " (an array)", "'of', the object it repeats", at);
  r.require_key(o, "count", at + " (an array)", "'count', its copies along x, y and z: [nx, ny, nz]", at);
  r.require_key(o, "step", at + " (an array)", "'step', the translation between copies: [sx, sy, sz]", at);
  const json& count = o["count"];
  std::array<std::uint64_t, 3> n{};
  const auto bad_count = [&] {
    r.fail(at + ".count", "'" + at + ".count' must be three integers of at least 1, got " + SceneFileReader::json_text(count));
  };
  if (!count.is_array() || count.size() != 3) bad_count();
  for (std::size_t a = 0; a < 3; ++a) {
    if (!count[a].is_number_integer() || count[a].get<std::int64_t>() < 1) bad_count();
    n[a] = count[a].get<std::uint64_t>();
    if (n[a] > kMaxObjects) {
      r.fail(at + ".count", "'" + at + ".count' makes more than " + std::to_string(kMaxObjects) + " objects");
    }
  }
  const std::uint64_t copies = n[0] * n[1] * n[2];  // each at most 2^20: no overflow
  if (copies > kMaxObjects) {
    r.fail(at + ".count", "'" + at + ".count' makes more than " + std::to_string(kMaxObjects) + " objects");
  }
  const glm::dvec3 step = r.vec3(o["step"], at + ".step");
  std::vector<SceneObject> one;
  std::vector<std::uint32_t> from;
  read_objects(o["of"], r, at + ".of", lattice, one, paths, from);
  if (one.size() * copies > kMaxObjects - std::min<std::size_t>(out.size(), kMaxObjects)) {
    r.fail(at + ".count", "'" + at + ".count' makes more than " + std::to_string(kMaxObjects) + " objects in the scene");
  }
  out.reserve(out.size() + one.size() * copies);
  for (std::uint64_t k = 0; k < n[2]; ++k) {
    for (std::uint64_t j = 0; j < n[1]; ++j) {
      for (std::uint64_t i = 0; i < n[0]; ++i) {
        const glm::dvec3 g = glm::dvec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)) * step;
        const glm::dvec3 back = inverse(g);
        for (std::size_t m = 0; m < one.size(); ++m) {
          SceneObject copy = one[m];
          copy.shape = shape_seen_from(one[m].shape, back);
          out.push_back(std::move(copy));
          origins.push_back(from[m]);
        }
      }
    }
  }
}

}  // namespace

Scene parse_scene(std::string_view text, std::string_view source) {
  detail::check_json_text(text, source);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {  // syntax errors and numbers out of range
    // The parser's message quotes the offending token whole: cut.
    throw InvalidArgument(std::string(source) + ": malformed JSON: " + SceneFileReader::shown(e.what(), 300));
  }
  const SceneFileReader r(text, source);
  if (!root.is_object()) r.fail("", "the scene must be a JSON object");
  r.require_known_keys(root,
                       {"camera", "objects", "lights", "ambient", "fog", "light", "fog_distance", "max_distance",
                        "max_steps", "hit_epsilon", "quotient", "samples", "max_bounces", "exposure", "tone"},
                       "the scene", "");
  Scene s;
  std::optional<glm::dvec3> look_at;
  if (root.contains("camera")) look_at = read_camera(root["camera"], r, s.camera);
  if (!root.contains("objects") || !root["objects"].is_array()) r.fail("objects", "'objects' must be an array");
  // The quotient first: objects name their axes by its lattice's generators.
  if (root.contains("quotient")) s.space = read_space(root["quotient"], r);
  std::optional<Lattice> lattice;
  try {
    detail::check_space(s.space);
    lattice = s.lattice();
  } catch (const detail::FieldError& e) {
    r.fail(e.path(), e.what());
  }
  if (look_at) {
    const bool focus = !root["camera"].contains("focus_distance");
    aim_camera(s.camera, *look_at, lattice, focus, r);
  }
  const json& objects = root["objects"];
  std::vector<std::string> paths;       // the file's object entries
  std::vector<std::uint32_t> origins;  // each object's entry among them
  for (std::size_t i = 0; i < objects.size(); ++i) {
    read_objects(objects[i], r, "objects[" + std::to_string(i) + "]", lattice ? &*lattice : nullptr, s.objects, paths, origins);
  }
  // "light" and "fog_distance": the first schema's single directional light and fog.
  if (root.contains("light")) {
    const json& l = root["light"];
    if (!l.is_object()) r.fail("light", "'light' must be an object");
    r.require_known_keys(l, {"direction", "ambient"}, "light", "light");
    if (l.contains("direction")) s.lights[0].direction = r.vec3(l["direction"], "light.direction");
    if (l.contains("ambient")) s.ambient = r.number(l["ambient"], "light.ambient");
  }
  if (root.contains("lights")) {
    if (root.contains("light")) r.fail("lights", "give either 'light' or 'lights', not both");
    const json& list = root["lights"];
    if (!list.is_array()) r.fail("lights", "'lights' must be an array");
    s.lights.clear();
    for (std::size_t i = 0; i < list.size(); ++i) s.lights.push_back(read_light(list[i], r, "lights[" + std::to_string(i) + "]"));
  }
  if (root.contains("ambient")) s.ambient = r.number(root["ambient"], "ambient");
  if (root.contains("fog_distance")) {
    const double d = r.number(root["fog_distance"], "fog_distance");
    if (!(d == 0.0 || (d >= 1e-6))) r.fail("fog_distance", "fog_distance must be 0 (no fog) or at least 1e-6");
    s.fog_density = d > 0.0 ? 1.0 / d : 0.0;
  }
  if (root.contains("fog")) {
    if (root.contains("fog_distance")) r.fail("fog", "give either 'fog' or 'fog_distance', not both");
    const json& f = root["fog"];
    if (!f.is_object()) r.fail("fog", "'fog' must be an object");
    r.require_known_keys(f, {"color", "density"}, "fog", "fog");
    if (f.contains("color")) s.fog_color = r.vec3(f["color"], "fog.color");
    if (f.contains("density")) s.fog_density = r.number(f["density"], "fog.density");
  }
  if (root.contains("max_distance")) s.max_distance = r.number(root["max_distance"], "max_distance");
  if (root.contains("hit_epsilon")) s.hit_epsilon = r.number(root["hit_epsilon"], "hit_epsilon");
  if (root.contains("max_bounces")) {
    const json& m = root["max_bounces"];
    if (!m.is_number_integer()) {
      r.fail("max_bounces", "'max_bounces' must be an integer, got " + SceneFileReader::json_text(m));
    }
    const auto v = m.get<long long>();
    if (v < 0 || v > 64) r.fail("max_bounces", "max_bounces must be in [0, 64]");
    s.max_bounces = static_cast<int>(v);
  }
  if (root.contains("max_steps")) {
    const json& m = root["max_steps"];
    if (!m.is_number_integer()) r.fail("max_steps", "'max_steps' must be an integer, got " + SceneFileReader::json_text(m));
    const auto v = m.get<long long>();
    if (v < 1 || v > 100000) r.fail("max_steps", "max_steps must be in [1, 100000]");
    s.max_steps = static_cast<int>(v);
  }
  if (root.contains("samples")) {
    const json& m = root["samples"];
    if (!m.is_number_integer()) r.fail("samples", "'samples' must be an integer, got " + SceneFileReader::json_text(m));
    const auto v = m.get<long long>();
    if (v < 1 || v > 4096) r.fail("samples", "samples must be in [1, 4096]");
    s.samples = static_cast<int>(v);
  }
  if (root.contains("exposure")) s.display.exposure = r.number(root["exposure"], "exposure");
  if (root.contains("tone")) {
#define SOL_TONE_CHOICE(Enum, code_name, code, name) {name, Tone::Enum},
    s.display.tone = r.choice<Tone>(root["tone"], "tone", {SOL_TONE_CURVES(SOL_TONE_CHOICE)});
#undef SOL_TONE_CHOICE
  }
  try {
    detail::check_camera(s.camera);
    detail::check_display(s.display);
    detail::check_world(s);
  } catch (const detail::FieldError& e) {
    // An object's field: named by its entry in the file (an array's copy by
    // the array's object), where the world's check counts the copies.
    std::string path = e.path(), what = e.what();
    std::size_t k = 0;
    if (std::sscanf(path.c_str(), "objects[%zu]", &k) == 1 && k < origins.size()) {
      const std::string counted = "objects[" + std::to_string(k) + "]";
      const std::string& entry = paths[origins[k]];
      if (path.compare(0, counted.size(), counted) == 0 && entry != counted) {
        path = entry + path.substr(counted.size());
        if (const std::size_t at = what.find(counted); at != std::string::npos) what.replace(at, counted.size(), entry);
      }
    }
    r.fail(path, what);
  }
  return s;
}

Scene load_scene(const std::string& path) { return parse_scene(detail::read_text_file(path, "scene"), path); }

std::string to_json(const Scene& s) {
  auto arr = [](const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); };
  json root;
  root["camera"] = {{"position", arr(s.camera.position)},
                    {"forward", arr(s.camera.forward)},
                    {"up", arr(s.camera.up)},
                    {"fov", s.camera.fov}};
  if (s.camera.projection != Projection::Perspective) {
    root["camera"]["projection"] = s.camera.projection == Projection::Equirectangular ? "equirectangular" : "fisheye";
    root["camera"]["fisheye_fov"] = s.camera.fisheye_fov;
  }
  if (s.camera.aperture != 0.0) {
    root["camera"]["aperture"] = s.camera.aperture;
    root["camera"]["focus_distance"] = s.camera.focus_distance;
  }
  if (s.camera.frustum) {
    const Frustum& f = *s.camera.frustum;
    root["camera"]["frustum"] = json::array({f.left, f.right, f.down, f.up});
  }
  root["objects"] = json::array();
  const std::optional<Lattice> lattice = s.lattice();
  for (const SceneObject& o : s.objects) root["objects"].push_back(detail::write_object(o, lattice ? &*lattice : nullptr));
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
      j["falloff"] = falloff_of(l) == Falloff::Geodesic ? "geodesic" : "inverse-square";
      j["shadows"] = l.shadows;
    }
    root["lights"].push_back(j);
  }
  root["ambient"] = s.ambient;
  root["fog"] = {{"color", arr(s.fog_color)}, {"density", s.fog_density}};
  root["quotient"] = detail::write_space(s.space);
  root["max_distance"] = s.max_distance;
  root["max_steps"] = s.max_steps;
  if (s.max_bounces) root["max_bounces"] = *s.max_bounces;
  root["hit_epsilon"] = s.hit_epsilon;
  root["samples"] = s.samples;
  if (s.display.exposure != 0.0) root["exposure"] = s.display.exposure;
  if (s.display.tone != Tone::Clamp) root["tone"] = tone_name(s.display.tone);
  return root.dump(2);
}

}  // namespace sol
