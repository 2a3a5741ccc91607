#include "sol/shapes.hpp"

#include <cmath>
#include <map>
#include <string>

#include <glm/geometric.hpp>

#include "sol/error.hpp"
#include "sol/geodesic.hpp"

namespace sol {

Mesh geodesic_sphere(const glm::dvec3& center, double radius, int subdivisions) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(center[i])) throw InvalidArgument("sol::geodesic_sphere: center must be finite");
  }
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    throw InvalidArgument("sol::geodesic_sphere: radius must be finite and > 0, got " + std::to_string(radius));
  }
  if (radius >= kSmoothSphereRadius) {
    throw NotImplemented("sol::geodesic_sphere: radius " + std::to_string(radius) +
                         " reaches the cut locus of the centre (from sqrt(2) pi = 4.4429 on): its creases are not built yet");
  }
  if (subdivisions < 1 || subdivisions > 512) {
    throw InvalidArgument("sol::geodesic_sphere: subdivisions must be in [1, 512], got " + std::to_string(subdivisions));
  }
  const int n = subdivisions;
  Mesh mesh;
  // Vertices keyed by their integer point w on the octahedron |x| + |y| + |z| = n,
  // so the faces share their edges' vertices (a closed mesh).
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](const std::array<int, 3>& w) {
    const auto [it, fresh] = index.emplace(w, static_cast<int>(mesh.vertices.size()));
    if (fresh) {
      const glm::dvec3 v = glm::normalize(glm::dvec3(w[0], w[1], w[2]));
      mesh.vertices.push_back(flow({center, v}, radius).position);
    }
    return it->second;
  };
  for (int sx : {1, -1}) {
    for (int sy : {1, -1}) {
      for (int sz : {1, -1}) {
        // Corners A, B, C of the face, ordered counter-clockwise seen from outside.
        std::array<int, 3> a{sx, 0, 0}, b{0, sy, 0}, c{0, 0, sz};
        if (sx * sy * sz < 0) std::swap(b, c);
        auto point = [&](int i, int j) {
          const int k = n - i - j;
          return vertex({k * a[0] + i * b[0] + j * c[0], k * a[1] + i * b[1] + j * c[1], k * a[2] + i * b[2] + j * c[2]});
        };
        for (int i = 0; i < n; ++i) {
          for (int j = 0; i + j < n; ++j) {
            mesh.triangles.push_back({point(i, j), point(i + 1, j), point(i, j + 1)});
            if (i + j < n - 1) mesh.triangles.push_back({point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
          }
        }
      }
    }
  }
  return mesh;
}

}  // namespace sol
