// Uses only the installed public API: flow a geodesic and check it lands
// where left-invariance says it must.
#include <cmath>
#include <cstdio>

#include <sol/sol.hpp>

int main() {
  const sol::GeodesicState start{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  const sol::GeodesicState end = sol::flow(start, 2.0);
  // The vertical geodesic is the z axis: (0, 0, 2).
  const bool ok = std::abs(end.position.z - 2.0) < 1e-9 && std::abs(end.position.x) < 1e-12;
  std::printf("libsol %s: flow((0,0,0),(0,0,1), 2) = (%g, %g, %g) %s\n", SOL_VERSION_STRING, end.position.x,
              end.position.y, end.position.z, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
