// Uses only the installed public API (the example of README.md): flow a
// geodesic and check it lands where left-invariance says it must, measure
// an exact distance, and render a preset from a world prepared once.
#include <cmath>
#include <cstdio>

#include <sol/sol.hpp>

int main() {
  const sol::GeodesicState start{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const sol::GeodesicState end = sol::flow(start, 2.0);
  // The vertical geodesic is the z axis: (0, 0, 2), and it minimises.
  const bool lands = std::abs(end.position.z - 2.0) < 1e-9 && std::abs(end.position.x) < 1e-12;
  const bool minimises = std::abs(sol::distance(start.position, end.position) - 2.0) < 1e-9;
  const sol::Scene scene = sol::preset_scene("sandwich");
  sol::CpuRenderer renderer(scene);
  const sol::RenderResult image = renderer.render(scene.camera, {.width = 16, .height = 12});
  int hits = 0;
  for (float object : image.object) hits += object > 0.0f;
  const bool renders = hits > 0;
  const bool ok = lands && minimises && renders;
  std::printf("libsol %s: flow((0,0,0),(0,0,1), 2) = (%g, %g, %g), distance %s, %d of %zu pixels hit: %s\n",
              SOL_VERSION_STRING, end.position.x, end.position.y, end.position.z, minimises ? "2" : "WRONG", hits,
              image.object.size(), ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
