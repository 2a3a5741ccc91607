// The objects of a crowd of small balls scattered in a fixed region (the tree of bounds'
// tests and render_bench's objects section): `count` balls of radius
// `radius` at uniform random points of the box [-2, 2] x [-2, 2] x [-1, 1]
// (a fixed seed per count; none within 0.2 of the origin, where
// crowd_camera_inside stands), over a floor z = -1.5, lit by the default light.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <sol/sol.hpp>

namespace sol::test {

inline std::vector<SceneObject> scattered_balls(std::size_t count, double radius = 0.04, std::uint64_t seed = 7) {
  std::vector<SceneObject> objects;
  std::mt19937_64 random(seed + count);
  std::uniform_real_distribution<double> xy(-2.0, 2.0), z(-1.0, 1.0), hue(0.2, 0.9);
  SceneObject floor;
  floor.shape = PlaneZ{-1.5};
  floor.pattern = Pattern::Checker;
  objects.push_back(floor);
  while (objects.size() < count + 1) {
    const glm::dvec3 centre(xy(random), xy(random), z(random));
    if (glm::length(centre) < 0.2) continue;  // room for crowd_camera_inside
    SceneObject ball;
    ball.shape = Ball{centre, radius, false};
    ball.color = {hue(random), hue(random), hue(random)};
    objects.push_back(ball);
  }
  return objects;
}

/// A camera outside the crowd's region, looking at it, and one inside it.
inline Camera crowd_camera_outside() {
  Camera c;
  c.position = {-4.0, 0.0, 0.2};
  c.forward = {1.0, 0.0, 0.0};
  c.up = {0.0, 0.0, 1.0};
  return c;
}

inline Camera crowd_camera_inside() {
  Camera c;
  c.position = {0.0, 0.0, 0.0};
  c.forward = {1.0, 0.0, 0.0};
  c.up = {0.0, 0.0, 1.0};
  return c;
}

}  // namespace sol::test
