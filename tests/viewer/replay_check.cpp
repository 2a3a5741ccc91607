// solview --script against sol::Observer: runs solview with a script of timed
// inputs and compares the observer it reports at exit (--state, %.17g) with
// an Observer driven here by the same inputs, following the rules that
// viewer/controls.hpp documents (re-derived here, not linked: a change of
// solview's controls that breaks those rules fails this test).
//
//   solview_replay_check SOLVIEW WORK_DIR   (needs a display: run under xvfb-run)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sol/sol.hpp>

namespace {

struct Event {
  double time;
  std::string what, key;
  double dx = 0, dy = 0;
};

// The documented constants (viewer/controls.hpp, solview --help).
constexpr double kSpeed = 1.0, kShift = 5.0, kTurn = 1.2, kMouse = 0.0025, kStep = 1.0 / 60.0;

sol::Observer expected(const sol::Scene& scene, const std::vector<Event>& events, long frames) {
  sol::Observer o(scene.camera.position, scene.camera.forward, scene.camera.up);
  if (scene.quotient() != sol::Quotient::None) o.bind(sol::Lattice::golden());
  std::map<std::string, bool> held;
  std::size_t next = 0;
  for (long frame = 0; frame < frames; ++frame) {
    const double t = static_cast<double>(frame) * kStep;
    for (; next < events.size() && events[next].time <= t + 1e-9; ++next) {
      const Event& e = events[next];
      if (e.what == "mouse") {
        if (e.dx != 0.0) o.yaw(e.dx * kMouse);
        if (e.dy != 0.0) o.pitch(-e.dy * kMouse);
      } else {
        held[e.key] = e.what == "down";
      }
    }
    auto axis = [&](const char* plus, const char* minus) { return (held[plus] ? 1.0 : 0.0) - (held[minus] ? 1.0 : 0.0); };
    const double turn = kTurn * kStep;
    if (const double a = axis("RIGHT", "LEFT"); a != 0.0) o.yaw(a * turn);
    if (const double a = axis("UP", "DOWN"); a != 0.0) o.pitch(a * turn);
    if (const double a = axis("E", "Q"); a != 0.0) o.roll(a * turn);
    const glm::dvec3 d(axis("D", "A"), axis("R", "F"), axis("W", "S"));
    if (d != glm::dvec3(0.0)) o.move(glm::normalize(d), kSpeed * (held["SHIFT"] ? kShift : 1.0) * kStep);
  }
  return o;
}

bool check(const std::string& solview, const std::string& dir, const std::string& scene_name,
           const std::vector<Event>& events, long frames) {
  const std::string script = dir + "/" + scene_name + ".script", state = dir + "/" + scene_name + ".state";
  {
    std::ofstream out(script);
    out << "# solview_replay_check\n";
    for (const Event& e : events) {
      out << e.time << ' ' << e.what << ' ';
      if (e.what == "mouse") {
        out << e.dx << ' ' << e.dy << '\n';
      } else {
        out << e.key << '\n';
      }
    }
  }
  std::remove(state.c_str());
  const std::string command = "'" + solview + "' --scene " + scene_name + " --size 32x18 --frames " +
                              std::to_string(frames) + " --script '" + script + "' --state '" + state + "'";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "FAIL %s: '%s' failed\n", scene_name.c_str(), command.c_str());
    return false;
  }
  std::ifstream in(state);
  std::map<std::string, glm::dvec3> got;
  long got_frames = -1;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string name;
    words >> name;
    if (name == "frames") {
      words >> got_frames;
    } else {
      glm::dvec3 v;
      words >> v.x >> v.y >> v.z;
      got[name] = v;
    }
  }
  const sol::Observer want = expected(sol::preset_scene(scene_name), events, frames);
  bool ok = got_frames == frames;
  const std::pair<const char*, glm::dvec3> rows[] = {
      {"position", want.position()}, {"forward", want.forward()}, {"up", want.up()}};
  for (const auto& [name, v] : rows) {
    const glm::dvec3 g = got.count(name) ? got[name] : glm::dvec3(NAN);
    // Exact: solview applies the same Observer calls with the same doubles.
    const bool same = g == v;
    ok = ok && same;
    std::printf("%s %-8s solview (%.17g, %.17g, %.17g)  sol::Observer (%.17g, %.17g, %.17g) %s\n", scene_name.c_str(),
                name, g.x, g.y, g.z, v.x, v.y, v.z, same ? "equal" : "DIFFER");
  }
  // The script must have moved the observer (else the test proves nothing).
  const sol::Scene scene = sol::preset_scene(scene_name);
  if (glm::length(want.position() - scene.camera.position) < 0.1) {
    std::printf("%s: the script barely moved the observer\n", scene_name.c_str());
    ok = false;
  }
  // In the quotient the observer stays in the fundamental domain D.
  if (scene.quotient() != sol::Quotient::None && !sol::Lattice::golden().contains(got["position"])) {
    std::printf("%s: solview's observer left D\n", scene_name.c_str());
    ok = false;
  }
  if (!ok) std::fprintf(stderr, "FAIL %s (frames %ld of %ld)\n", scene_name.c_str(), got_frames, frames);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: solview_replay_check SOLVIEW WORK_DIR\n");
    return 2;
  }
  // Forward, a turn by the arrow keys, a mouse drag, sideways with Shift, a roll, up and back.
  const std::vector<Event> events = {
      {0.0, "down", "W"},     {0.25, "down", "RIGHT"}, {0.5, "up", "RIGHT"}, {0.5, "mouse", "", 40, -20},
      {0.6, "down", "SHIFT"}, {0.6, "down", "D"},      {0.8, "up", "W"},     {0.8, "down", "Q"},
      {0.9, "up", "SHIFT"},   {0.9, "down", "R"},      {1.0, "up", "Q"},     {1.0, "mouse", "", -15.5, 7},
      {1.1, "up", "D"},       {1.1, "down", "S"},      {1.2, "down", "UP"},  {1.3, "up", "UP"},
  };
  bool ok = true;
  // sandwich: in Sol; lattice-balls: the quotient, where the observer is teleported into D.
  for (const char* scene : {"sandwich", "lattice-balls"}) ok = check(argv[1], argv[2], scene, events, 84) && ok;
  return ok ? 0 : 1;
}
