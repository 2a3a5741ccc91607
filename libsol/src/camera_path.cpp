#include "sol/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "field_error.hpp"
#include "scene_reader.hpp"
#include "sol/aim.hpp"
#include "sol/error.hpp"
#include "sol/lattice.hpp"
#include "sol/observer.hpp"

namespace sol {
namespace {

using detail::json;
using detail::SceneFileReader;

// The longest path and the largest single moves it takes: beyond them a
// film is not what was meant (and a walk of 1e300 never ends).
constexpr std::size_t kMaxSegments = 100000;
constexpr double kMaxDuration = 1e6;  // seconds, per segment
constexpr double kMaxDistance = 1e4;  // Sol units, per walk
constexpr double kMaxDegrees = 1e6;   // per turn

PathSegment read_segment(const json& j, const SceneFileReader& r, const std::string& at) {
  if (!j.is_object()) r.fail(at, at + " must be an object");
  PathSegment s;
  auto duration = [&](const char* key) {
    const double d = r.number(j[key], at + "." + key);
    if (!(d > 0.0 && d <= kMaxDuration)) r.fail(at + "." + key, at + "." + key + " must be in (0, 1e6] seconds");
    return d;
  };
  if (j.contains("walk")) {
    r.require_known_keys(j, {"walk", "distance", "duration", "look_at"}, at + " (a walk)", at);
    const glm::dvec3 direction = r.choice<glm::dvec3>(j["walk"], at + ".walk",
                                                      {{"forward", {0, 0, 1}}, {"back", {0, 0, -1}},
                                                       {"left", {-1, 0, 0}},   {"right", {1, 0, 0}},
                                                       {"up", {0, 1, 0}},      {"down", {0, -1, 0}}});
    r.require_key(j, "distance", at + " (a walk)", "a 'distance'", at);
    r.require_key(j, "duration", at + " (a walk)", "a 'duration'", at);
    s.kind = PathSegment::Kind::Walk;
    s.direction = direction;
    s.distance = r.number(j["distance"], at + ".distance");
    if (!(std::abs(s.distance) <= kMaxDistance)) r.fail(at + ".distance", at + ".distance must be within ±1e4");
    s.duration = duration("duration");
    if (j.contains("look_at")) {
      s.look_at = r.vec3(j["look_at"], at + ".look_at");
      try {
        detail::check_position(*s.look_at, at + ".look_at");
      } catch (const detail::FieldError& e) {
        r.fail(e.path(), e.what());
      }
    }
  } else if (j.contains("turn")) {
    r.require_known_keys(j, {"turn", "degrees", "duration"}, at + " (a turn)", at);
    s.axis = r.choice<PathSegment::Axis>(j["turn"], at + ".turn",
                                         {{"yaw", PathSegment::Axis::Yaw},
                                          {"pitch", PathSegment::Axis::Pitch},
                                          {"roll", PathSegment::Axis::Roll}});
    r.require_key(j, "degrees", at + " (a turn)", "'degrees'", at);
    r.require_key(j, "duration", at + " (a turn)", "a 'duration'", at);
    s.kind = PathSegment::Kind::Turn;
    const double degrees = r.number(j["degrees"], at + ".degrees");
    if (!(std::abs(degrees) <= kMaxDegrees)) r.fail(at + ".degrees", at + ".degrees must be within ±1e6");
    s.angle = degrees * std::numbers::pi / 180.0;
    s.duration = duration("duration");
  } else if (j.contains("hold")) {
    r.require_known_keys(j, {"hold"}, at + " (a hold)", at);
    s.kind = PathSegment::Kind::Hold;
    s.duration = duration("hold");
  } else {
    r.fail(at, at + " must be a walk, a turn or a hold ({\"walk\": ...}, {\"turn\": ...} or {\"hold\": seconds})");
  }
  return s;
}

// One segment applied to the observer, a fraction f of it.
// In a quotient a walk goes in steps of at most this, each teleported back
// into D as it ends (as solview walks, frame by frame): in one flow a long
// walk's point leaves D by a lattice element whose word grows with e^t and
// past about 35 units is no longer exact in double (Lattice::word_of).
constexpr double kQuotientWalkStep = 1.0;

// `focus`: set to the distance of a walk's look_at point as it faces it.
void apply(const PathSegment& s, double f, Observer& o, const std::optional<Lattice>& lattice, double& focus) {
  if (f <= 0.0) return;
  switch (s.kind) {
    case PathSegment::Kind::Walk:
      if (s.distance != 0.0) {
        const double length = s.distance * f;
        const int steps = lattice ? std::max(1, static_cast<int>(std::ceil(std::abs(length) / kQuotientWalkStep))) : 1;
        for (int k = 0; k < steps; ++k) o.move(s.direction, length / steps);
      }
      if (s.look_at) {
        try {
          const Aim to = aim(o.position(), *s.look_at, lattice);
          o.face(to.direction);
          focus = focus_on(to, focus);
        } catch (const InvalidArgument&) {
          // At the point itself (or one of its images): no direction; the frame stays.
        }
      }
      break;
    case PathSegment::Kind::Turn:
      if (s.axis == PathSegment::Axis::Yaw) o.yaw(s.angle * f);
      if (s.axis == PathSegment::Axis::Pitch) o.pitch(s.angle * f);
      if (s.axis == PathSegment::Axis::Roll) o.roll(s.angle * f);
      break;
    case PathSegment::Kind::Hold:
      break;
  }
}

}  // namespace

double CameraPath::duration() const {
  double total = 0.0;
  for (const PathSegment& s : segments) total += s.duration;
  return total;
}

long CameraPath::frame_count(double fps) const {
  if (!(fps > 0.0 && fps <= 1000.0)) throw InvalidArgument("sol::CameraPath::frame_count: fps must be in (0, 1000]");
  // The last frame at the end of the path, however the duration rounds.
  return static_cast<long>(std::floor(duration() * fps + 1e-9)) + 1;
}

Camera CameraPath::at(double t, const Camera& scene_camera, const std::optional<Lattice>& lattice) const {
  Camera c = scene_camera;
  if (position) c.position = *position;
  if (forward) c.forward = *forward;
  if (up) c.up = *up;
  if (fov) c.fov = *fov;
  if (aperture) c.aperture = *aperture;
  if (look_at) c = looking_at(c, *look_at, lattice);  // (focused there too)
  double focus = c.focus_distance;  // the lens's focus, tracking the points looked at where the path gives none
  c.focus_distance = focus_distance.value_or(focus);
  validate(c);
  Observer o(c.position, c.forward, c.up);
  if (lattice) o.bind(*lattice);
  double begin = 0.0;
  for (const PathSegment& s : segments) {
    if (t <= begin) break;
    const double end = begin + s.duration;
    apply(s, t >= end ? 1.0 : (t - begin) / s.duration, o, lattice, focus);
    begin = end;
  }
  c.position = o.position();
  c.forward = o.forward();
  c.up = o.up();
  c.focus_distance = focus_distance.value_or(focus);
  return c;
}

CameraPath parse_camera_path(std::string_view text, std::string_view source) {
  detail::check_json_text(text, source);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    throw InvalidArgument(std::string(source) + ": malformed JSON: " + SceneFileReader::shown(e.what(), 300));
  }
  const SceneFileReader r(text, source);
  if (!root.is_object()) r.fail("", "the path must be a JSON object");
  r.require_known_keys(root, {"start", "segments"}, "the path", "");
  CameraPath path;
  if (root.contains("start")) {
    const json& s = root["start"];
    if (!s.is_object()) r.fail("start", "'start' must be an object");
    r.require_known_keys(s, {"position", "forward", "look_at", "up", "fov", "aperture", "focus_distance"}, "start",
                         "start");
    if (s.contains("forward") && s.contains("look_at")) r.fail("start.look_at", "start: give either 'forward' or 'look_at', not both");
    if (s.contains("look_at")) path.look_at = r.vec3(s["look_at"], "start.look_at");
    if (s.contains("position")) path.position = r.vec3(s["position"], "start.position");
    if (s.contains("forward")) path.forward = r.vec3(s["forward"], "start.forward");
    if (s.contains("up")) path.up = r.vec3(s["up"], "start.up");
    if (s.contains("fov")) path.fov = r.number(s["fov"], "start.fov");
    if (s.contains("aperture")) path.aperture = r.number(s["aperture"], "start.aperture");
    if (s.contains("focus_distance")) path.focus_distance = r.number(s["focus_distance"], "start.focus_distance");
  }
  if (!root.contains("segments") || !root["segments"].is_array() || root["segments"].empty()) {
    r.fail("segments", "'segments' must be a non-empty array of walks, turns and holds");
  }
  const json& segments = root["segments"];
  if (segments.size() > kMaxSegments) r.fail("segments", "at most 100000 segments");
  for (std::size_t i = 0; i < segments.size(); ++i) {
    path.segments.push_back(read_segment(segments[i], r, "segments[" + std::to_string(i) + "]"));
  }
  // The start's fields as far as they go alone (the scene's camera fills
  // in the rest; CameraPath::at checks the whole camera).
  try {
    if (path.position) detail::check_position(*path.position, "start.position");
    if (path.forward) detail::check_direction(*path.forward, "start.forward");
    if (path.look_at) detail::check_position(*path.look_at, "start.look_at");
    if (path.up) detail::check_direction(*path.up, "start.up");
    if (path.forward && path.up && glm::length(glm::cross(glm::normalize(*path.forward), glm::normalize(*path.up))) < 1e-9) {
      detail::field_error("start.forward", "start.forward and start.up must not be parallel");
    }
    if (path.fov && !(*path.fov > 0.0 && *path.fov < 180.0)) detail::field_error("start.fov", "start.fov must be in (0, 180) degrees");
    if (path.aperture && !(*path.aperture >= 0.0 && *path.aperture <= 1.0)) {
      detail::field_error("start.aperture", "start.aperture must be in [0, 1]");
    }
    if (path.focus_distance && !(*path.focus_distance > 0.0 && *path.focus_distance <= 100.0)) {
      detail::field_error("start.focus_distance", "start.focus_distance must be in (0, 100]");
    }
  } catch (const detail::FieldError& e) {
    r.fail(e.path(), e.what());
  }
  return path;
}

CameraPath load_camera_path(const std::string& file) {
  return parse_camera_path(detail::read_text_file(file, "path"), file);
}

}  // namespace sol
