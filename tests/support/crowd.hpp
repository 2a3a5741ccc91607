// The objects of a crowd of small balls scattered in a fixed region (the tree of bounds'
// tests and render_bench's objects section): `count` balls of radius
// `radius` at uniform random points of the box [-2, 2] x [-2, 2] x [-1, 1]
// (a fixed seed per count; none within 0.2 of the origin, where
// crowd_camera_inside stands), over a floor z = -1.5, lit by the default light;
// and a world of every kind (mixed_world), the two marches' and devices' comparison.
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

// A world of every kind the list march takes, under MarchWorld::kMostListed objects:
// bound and exact balls (bound balls in their place without `exact_balls`), boxes, tubes horizontal and vertical, planes x, y,
// z, a cutout checkerboard, a mirror and a glowing ball.
inline World mixed_world(bool exact_balls = true) {
  World w;
  const auto add = [&](Shape shape, glm::dvec3 color) {
    SceneObject o;
    o.shape = shape;
    o.color = color;
    w.objects.push_back(o);
    return w.objects.size() - 1;
  };
  add(PlaneZ{-1.5}, {0.7, 0.7, 0.7});
  w.objects.back().pattern = Pattern::Checker;
  add(PlaneX{6.0}, {0.5, 0.6, 0.8});
  add(PlaneY{-4.0}, {0.8, 0.6, 0.5});
  add(PlaneZ{2.5}, {0.6, 0.8, 0.6});
  w.objects.back().pattern = Pattern::Checker;
  w.objects.back().cutout = true;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 5; ++j) {
      const glm::dvec3 c(1.0 + 0.8 * i, -2.0 + 0.9 * j, -0.6 + 0.25 * ((i + j) % 4));
      switch ((i + 2 * j) % 4) {
        case 0: add(Ball{c, 0.25, false}, {0.9, 0.3, 0.2}); break;
        case 1: add(Box{c, {0.15, 0.2, 0.25}}, {0.2, 0.8, 0.3}); break;
        case 2: add(Ball{c, 0.2, exact_balls}, {0.3, 0.4, 0.9}); break;
        default: add(Box{c, {0.25, 0.1, 0.1}}, {0.9, 0.9, 0.2}); break;
      }
    }
  }
  add(Tube{{0.0, 1.8, 0.9}, {1.0, 0.0, 0.0}, 0.15}, {0.8, 0.2, 0.8});
  add(Tube{{2.5, 2.5, 0.0}, {0.0, 0.0, 1.0}, 0.2}, {0.2, 0.8, 0.8});
  w.objects[add(Ball{{3.0, 0.3, 1.2}, 0.4, false}, {0.9, 0.9, 0.9})].mirror = 0.8;
  w.objects[add(Ball{{2.0, -0.8, 1.4}, 0.3, false}, {1.0, 0.9, 0.7})].emission = {2.0, 1.6, 1.0};
  Light lamp;
  lamp.type = LightType::Point;
  lamp.position = {1.5, 0.0, 2.0};
  lamp.intensity = 3.0;
  lamp.exact = true;
  lamp.shadows = true;
  w.lights.push_back(lamp);
  return w;
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
