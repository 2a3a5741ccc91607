// libFuzzer target: camera path files. Every input is either refused with
// sol::InvalidArgument or gives a path whose duration is finite and whose
// camera at its start, middle and end (from a scene's camera, in Sol and
// in the quotient) is either refused with InvalidArgument (a path that
// leaves the heights a camera may have) or finite. Anything else is a
// finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string_view>

#include <sol/sol.hpp>

namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::optional<sol::CameraPath> path;
  try {
    path = sol::parse_camera_path(text, "fuzz.json");
  } catch (const sol::InvalidArgument&) {
    return 0;
  }
  const double duration = path->duration();
  if (!std::isfinite(duration) || duration < 0.0) std::abort();
  static const sol::Scene scene = sol::preset_scene("plane");
  static const std::optional<sol::Lattice> golden = sol::Lattice::golden();
  for (const std::optional<sol::Lattice>& lattice : {std::optional<sol::Lattice>(), golden}) {
    for (const double t : {0.0, 0.5 * duration, duration}) {
      try {
        const sol::Camera c = path->at(t, scene.camera, lattice);
        if (!finite(c.position) || !finite(c.forward) || !finite(c.up)) std::abort();
      } catch (const sol::InvalidArgument&) {
      }
    }
  }
  return 0;
}
