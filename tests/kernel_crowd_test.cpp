// The kernel's march through a crowd (a Sol world of more than
// sol::kListedObjects objects, marched through its tree of bounds:
// compute/shaders/march/crowd.glsl) against the CPU reference's
// (march_crowd in libsol/src/render.cpp), on lavapipe.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/vk/march.hpp>

#include "support/crowd.hpp"
#include "support/kernel.hpp"
#include "support/paths.hpp"

namespace {

using sol::test::vk_context;

sol::Scene scene_of(const sol::World& world, const sol::Camera& camera) {
  sol::Scene scene;
  static_cast<sol::World&>(scene) = world;
  scene.camera = camera;
  return scene;
}

// A scene rendered by the kernel and by the CPU reference at one size, and
// the two compared pixel by pixel (colour threshold 2e-3 a channel).
struct AgainstCpu {
  sol::RenderResult gpu, cpu;
  sol::test::ImageComparison c;
};

AgainstCpu against_cpu(sol::vk::MarchRenderer& renderer, const sol::Scene& scene, int width, int height) {
  AgainstCpu r;
  r.gpu = sol::test::render(renderer, scene, width, height);
  sol::RenderOptions options;
  options.width = width;
  options.height = height;
  r.cpu = sol::render_cpu(scene, options);
  r.c = sol::test::compare_images(r.gpu, r.cpu, 2e-3f);
  return r;
}

// Every kind in the crowd's kernel march: planes x, y, z, a cutout
// checkerboard, bound and exact balls, boxes, tubes horizontal and
// vertical, a mirror, a glowing ball, an exact point light with shadows
// (whose rays leave exact balls' spheres). Float against double: a pixel's object may differ on an
// edge, where the two stop within hit_epsilon of different surfaces, and
// its colour where the float march's hit point lies a little off (the
// checkerboard's edges); 1 % of the pixels either way is the budget of the
// other kernel-against-CPU comparisons (MirrorsShowTheReflectedScene...).
TEST(KernelCrowd, EveryKindInACrowdMatchesTheCpuRenderer) {
  sol::World world = sol::test::mixed_world();
  ASSERT_GT(world.objects.size(), sol::kListedObjects);
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(world), "");
  sol::Camera camera;
  camera.position = {3.0, -0.2, 2.0};  // under the cutout, looking down on the grid
  camera.forward = {0.0, 0.0, -1.0};
  camera.up = {1.0, 0.0, 0.0};
  const sol::Scene scene = scene_of(world, camera);
  sol::vk::MarchRenderer renderer(vk_context());
  const auto [gpu, cpu, c] = against_cpu(renderer, scene, 64, 48);
  ASSERT_NE(renderer.world().tree(), nullptr);
  std::printf("every kind in a crowd: %d of %d pixels hit another object, %d differ in colour (worst %.2g), distance %.2g\n",
              c.mask_differs, c.pixels, c.color_differs, c.worst_color, c.distance);
  EXPECT_LE(c.mask_differs, c.pixels / 100);
  EXPECT_LE(c.color_differs, c.pixels / 100);
  // (Distances where both hit one object: the float march's hit_epsilon
  // stop and rounding, far below an object's size.)
  EXPECT_LT(c.distance, 2e-3);
  std::set<float> seen(gpu.object.begin(), gpu.object.end());
  EXPECT_GT(seen.size(), 20u);  // many of the objects, not only the floor
  sol::test::expect_no_validation_errors();
}

// 10,000 small balls seen from outside the crowd and from inside it: the
// kernel and the CPU hit the same object in every pixel but for edges
// (0.5 %), at the same arc length within 1e-3 (each stops within
// hit_epsilon = 5e-5 of the bound's surface; a grazing ray runs on further).
TEST(KernelCrowd, TenThousandBallsAreHitWhereTheCpuHitsThem) {
  sol::World world;
  world.objects = sol::test::scattered_balls(10000);
  sol::vk::MarchRenderer renderer(vk_context());
  for (const sol::Camera& camera : {sol::test::crowd_camera_outside(), sol::test::crowd_camera_inside()}) {
    const sol::Scene scene = scene_of(world, camera);
    const auto [gpu, cpu, c] = against_cpu(renderer, scene, 48, 36);
    std::set<float> seen(cpu.object.begin(), cpu.object.end());
    std::printf("10,000 balls: %d of %d pixels hit another object, distance %.2g, %zu objects seen\n", c.mask_differs,
                c.pixels, c.distance, seen.size());
    EXPECT_LE(c.mask_differs, c.pixels / 200);
    EXPECT_LT(c.distance, 1e-3);
    EXPECT_GT(seen.size(), 30u);
    EXPECT_LE(c.color_differs, c.pixels / 100);
    EXPECT_EQ(gpu.rays_out_of_steps, cpu.rays_out_of_steps);
  }
  sol::test::expect_no_validation_errors();
}

// An eye inside a solid (a box the size of a room, balls in it), in a
// listed world and in a crowd: the kernel's inside clearances (HAS_INSIDE)
// and its walls' normals facing the eye as the CPU's. (The float march's
// last step may end a little beyond a wall, where the bound's sign once
// turned the normal away at random: speckled walls.)
TEST(KernelCrowd, AnEyeInsideABoxSeesWhatTheCpuSees) {
  for (const std::size_t balls : {std::size_t{6}, std::size_t{200}}) {
    sol::World world;
    world.objects = sol::test::scattered_balls(balls, 0.08);
    sol::SceneObject room;
    room.shape = sol::Box{{0.0, 0.0, 0.0}, {3.0, 3.0, 1.4}};
    room.color = {0.8, 0.75, 0.7};
    room.pattern = sol::Pattern::Checker;
    world.objects.push_back(room);
    sol::Light lamp;
    lamp.type = sol::LightType::Point;
    lamp.position = {0.3, 0.1, 0.9};
    lamp.intensity = 2.0;
    world.lights.push_back(lamp);
    const sol::Scene scene = scene_of(world, sol::test::crowd_camera_inside());
    sol::vk::MarchRenderer renderer(vk_context());
    const auto [gpu, cpu, c] = against_cpu(renderer, scene, 48, 36);
    EXPECT_EQ(renderer.world().tree() != nullptr, world.objects.size() > sol::kListedObjects);
    std::printf("inside a room of %zu objects: %d of %d pixels hit another object, %d differ in colour, distance %.2g\n",
                world.objects.size(), c.mask_differs, c.pixels, c.color_differs, c.distance);
    int walls = 0;
    for (float o : cpu.object) walls += o == static_cast<float>(world.objects.size()) ? 1 : 0;
    EXPECT_GT(walls, c.pixels / 4);  // the room's walls seen from inside
    EXPECT_LE(c.mask_differs, c.pixels / 100);
    EXPECT_LE(c.color_differs, c.pixels / 100);
    EXPECT_LT(c.distance, 2e-3);
  }
  sol::test::expect_no_validation_errors();
}

// Exact balls in a crowd (the kernel solves the nearest one's exact
// distance near its sphere, march/crowd.glsl) are hit on their true
// spheres: every hit on a ball lies within 2e-4 of radius r from its centre
// by sol::distance (the 50-digit-tested distance, independent of both
// renderers; the kernel's float stop is within hit_epsilon = 5e-5 of the
// sphere, the rest its rounding), on both devices and from outside the
// crowd, from inside it and from inside one of the balls (the sphere seen
// from within), with shadows of an exact point light; and the two devices
// hit the same object but on edges (1 % of the pixels, as above).
TEST(KernelCrowd, ExactBallsInACrowdAreHitOnTheirTrueSpheres) {
  // Balls apart by 0.1 at least (their centres' distance bound above 2r +
  // 0.1: overlapping ones are OverlappingExactBallsAreHitOnTheNearerSphere's),
  // and 0.1 from the eye inside the crowd, at the origin.
  constexpr double radius = 0.25;
  sol::World world;
  for (const sol::SceneObject& o : sol::test::scattered_balls(200, radius)) {
    const auto* b = std::get_if<sol::Ball>(&o.shape);
    const auto apart = [&](const sol::SceneObject& other) {
      const auto* c = std::get_if<sol::Ball>(&other.shape);
      return !c || sol::distance_lower_bound(b->center, c->center) > 2.0 * radius + 0.1;
    };
    if (b && (sol::distance_lower_bound(b->center, glm::dvec3(0.0)) < radius + 0.1 ||
              !std::all_of(world.objects.begin(), world.objects.end(), apart))) {
      continue;
    }
    world.objects.push_back(o);
    if (auto* e = std::get_if<sol::Ball>(&world.objects.back().shape)) e->exact = true;
  }
  ASSERT_GT(world.objects.size(), 30u);
  world.lights.push_back(
      {.type = sol::LightType::Point, .position = {0.0, 0.1, 0.0}, .intensity = 2.0, .exact = true, .shadows = true});
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(world), "");
  sol::Camera in_ball = sol::test::crowd_camera_inside();
  const sol::Ball& first = std::get<sol::Ball>(world.objects[1].shape);
  in_ball.position = first.center + glm::dvec3(0.05, 0.0, 0.0);
  sol::vk::MarchRenderer renderer(vk_context());
  const std::pair<const char*, sol::Camera> views[] = {
      {"outside", sol::test::crowd_camera_outside()}, {"inside the crowd", sol::test::crowd_camera_inside()}, {"inside a ball", in_ball}};
  for (const auto& [name, camera] : views) {
    const sol::Scene scene = scene_of(world, camera);
    const auto [gpu, cpu, c] = against_cpu(renderer, scene, 48, 36);
    ASSERT_NE(renderer.world().tree(), nullptr);
    const auto off_sphere = [&](const sol::RenderResult& r, int& hits) {
      double worst = 0.0;
      for (std::size_t k = 0; k < r.object.size(); ++k) {
        const int o = static_cast<int>(r.object[k]) - 1;
        if (o < 1) continue;  // a miss or the floor
        const auto& ball = std::get<sol::Ball>(world.objects[static_cast<std::size_t>(o)].shape);
        worst = std::max(worst, std::abs(sol::distance({r.px[k], r.py[k], r.pz[k]}, ball.center) - ball.radius));
        ++hits;
      }
      return worst;
    };
    int gpu_hits = 0, cpu_hits = 0;
    const double gpu_off = off_sphere(gpu, gpu_hits), cpu_off = off_sphere(cpu, cpu_hits);
    std::printf("exact balls in a crowd, %s: %d of %d pixels hit another object, %d differ in colour; %d hits on balls, "
                "farthest from the sphere %.2g (CPU %.2g)\n",
                name, c.mask_differs, c.pixels, c.color_differs, gpu_hits, gpu_off, cpu_off);
    EXPECT_GT(gpu_hits, c.pixels / 20) << name;
    EXPECT_LT(gpu_off, 2e-4) << name;
    EXPECT_LT(cpu_off, 1e-4) << name;  // (within hit_epsilon of it)
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
  }
  sol::test::expect_no_validation_errors();
}

// Overlapping exact balls, where one's bound ball reaches past the other's
// sphere: the kernel solves one exact ball a step and takes the others by
// their bounds, so it must not hit a ball by its bound, nor pass a ball's
// sphere while it solves another, nor crawl while a shadow ray leaves one
// sphere inside another's bound (march_exact_step, ExactSeen). Two balls of
// radius 0.3 whose centres are 0.59 apart, in front of the eye, an exact
// point light beside the eye casting one's shadow on the other: listed
// (with a floor), in a crowd (eight more exact balls behind them) and in
// the golden quotient. Every hit on a ball lies on the union's boundary:
// on its own sphere within 2e-4 by sol::distance and outside the other's
// (the CPU's within hit_epsilon = 5e-5, the kernel's float stop and
// rounding the rest), and the two devices agree but on edges (1 % of the
// pixels, the budget of the other comparisons), colours (the shadows) too.
TEST(KernelCrowd, OverlappingExactBallsAreHitOnTheNearerSphere) {
  const glm::dvec3 a_center(0.43, -0.27, 0.07), b_center(0.23, 0.27, -0.06);
  constexpr double radius = 0.3;
  ASSERT_LT(sol::distance(a_center, b_center), 2.0 * radius - 0.01);  // they overlap
  sol::Scene pair;
  pair.camera = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 60.0};
  pair.hit_epsilon = 5e-5;
  pair.objects.push_back({sol::Ball{a_center, radius, true}, {0.4, 0.3, 0.5}});
  pair.objects.push_back({sol::Ball{b_center, radius, true}, {0.5, 0.7, 0.8}});
  pair.lights = {{.type = sol::LightType::Point, .position = {0.0, 0.1, 0.0}, .intensity = 2.0, .exact = true, .shadows = true},
                 {.type = sol::LightType::Directional, .direction = {0.3, 0.5, 1.0}}};
  sol::Scene listed = pair, crowd = pair, quotient = pair;
  listed.objects.push_back({sol::PlaneZ{-1.5}, {0.8, 0.8, 0.8}});
  for (int k = 0; k < 8; ++k) {
    crowd.objects.push_back({sol::Ball{{2.5 + 0.4 * (k % 4), -0.6 + 0.4 * (k / 4), 0.0}, 0.15, true}, {0.8, 0.6, 0.3}});
  }
  ASSERT_GT(crowd.objects.size(), sol::kListedObjects);
  sol::set_space(quotient, sol::GoldenSpace{});
  sol::vk::MarchRenderer renderer(vk_context());
  const std::pair<const char*, const sol::Scene*> worlds[] = {{"listed", &listed}, {"crowd", &crowd}, {"golden", &quotient}};
  for (const auto& [name, scene] : worlds) {
    ASSERT_EQ(sol::vk::MarchRenderer::unsupported(*scene), "") << name;
    const auto [gpu, cpu, c] = against_cpu(renderer, *scene, 48, 36);
    // Off the union's boundary: the hit ball's |d - r|, and how deep the
    // point lies inside the other ball (Sol only: in the quotient the
    // hits are in the domain, among the balls' images).
    const auto off_boundary = [&](const sol::RenderResult& r, int& hits) {
      double worst = 0.0;
      for (std::size_t k = 0; k < r.object.size(); ++k) {
        const int o = static_cast<int>(r.object[k]) - 1;
        if (o != 0 && o != 1) continue;
        const glm::dvec3 p(r.px[k], r.py[k], r.pz[k]);
        const double own = sol::distance(p, o == 0 ? a_center : b_center) - radius;
        const double other = sol::distance(p, o == 0 ? b_center : a_center) - radius;
        worst = std::max({worst, std::abs(own), -other});
        ++hits;
      }
      return worst;
    };
    int gpu_hits = 0, cpu_hits = 0;
    const bool in_sol = scene->quotient() == sol::Quotient::None;
    const double gpu_off = in_sol ? off_boundary(gpu, gpu_hits) : 0.0, cpu_off = in_sol ? off_boundary(cpu, cpu_hits) : 0.0;
    std::printf("overlapping exact balls, %s: %d of %d pixels hit another object, %d differ in colour (worst %.2g); "
                "%d hits on the balls, farthest off the union's boundary %.2g (CPU %.2g)\n",
                name, c.mask_differs, c.pixels, c.color_differs, c.worst_color, gpu_hits, gpu_off, cpu_off);
    if (in_sol) {
      EXPECT_GT(gpu_hits, c.pixels / 2) << name;
      EXPECT_LT(gpu_off, 2e-4) << name;
      EXPECT_LT(cpu_off, 1e-4) << name;
    }
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
    // (No crawl: rays that run out of steps are the CPU's few, grazing the seam.)
    EXPECT_LE(gpu.rays_out_of_steps, cpu.rays_out_of_steps) << name;
    std::printf("  rays out of steps: %llu (CPU %llu)\n", static_cast<unsigned long long>(gpu.rays_out_of_steps),
                static_cast<unsigned long long>(cpu.rays_out_of_steps));
  }
  sol::test::expect_no_validation_errors();
}

// Paths through a crowd of exact balls (their camera ray the path's first
// segment, through the crowd's march and its exact solves) are the CPU's
// for the same seed, as Kernel.PathsAreTheCpuPathsForTheSameSeed holds a
// listed world's: every value finite, 80 % of the pixels within 1e-3 (paths
// that part by float rounding make the rest), the mean difference within 3
// standard errors. A floor, ten exact balls, a glowing bound ball (found by
// reflection sampling) and an exact point light with shadows.
TEST(KernelCrowd, PathsThroughExactBallsAreTheCpus) {
  sol::Scene scene;
  scene.camera = {{0.0, 0.0, 0.0}, {0.0, 1.0, -0.25}, {0.0, 0.0, 1.0}, 80.0};
  scene.objects.push_back({sol::PlaneZ{-0.6}, {0.7, 0.6, 0.5}});
  for (int k = 0; k < 10; ++k) {
    const glm::dvec3 c(-1.2 + 0.6 * (k % 5), 1.6 + 0.7 * (k / 5), -0.35 + 0.1 * (k % 3));
    scene.objects.push_back({sol::Ball{c, 0.2, true}, {0.3 + 0.06 * k, 0.6, 0.8 - 0.05 * k}});
  }
  sol::SceneObject glow{sol::Ball{{0.3, 1.2, 0.3}, 0.2, false}, {0.5, 0.5, 0.5}};
  glow.emission = {2.0, 1.5, 1.0};
  scene.objects.push_back(glow);
  scene.lights = {
      {.type = sol::LightType::Point, .position = {0.0, 1.0, 1.5}, .intensity = 2.0, .exact = true, .shadows = true}};
  scene.max_distance = 8.0;
  ASSERT_EQ(sol::vk::MarchRenderer::unsupported(scene, sol::Transport::Path), "");
  const sol::RenderOptions settings{.width = 20, .height = 14, .samples = 6, .transport = sol::Transport::Path, .seed = 11};
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings), cpu = sol::render_cpu(scene, settings);
  ASSERT_NE(renderer.world().tree(), nullptr);
  for (float v : gpu.rgba) ASSERT_TRUE(std::isfinite(v));
  const std::size_t n = cpu.rgba.size() / 4, agree = sol::test::pixels_agreeing(gpu, cpu, 1e-3f);
  const sol::test::MeanAndError d = sol::test::red_difference(gpu, cpu);
  int balls = 0;
  double red = 0.0;
  for (float o : cpu.object) balls += o >= 2.0f && o <= 11.0f;
  for (std::size_t k = 0; k < n; ++k) red += cpu.rgba[4 * k] / static_cast<double>(n);
  std::printf("paths through exact balls in a crowd: %zu of %zu pixels agree to 1e-3; mean difference %.4f, standard "
              "error %.4f; %d pixels on the balls, CPU mean red %.4f\n",
              agree, n, d.mean, d.error, balls, red);
  EXPECT_GT(red, 0.02);  // lit by the light and the glowing ball
  EXPECT_GT(balls, static_cast<int>(n / 10));
  EXPECT_GE(agree, n * 8 / 10);
  EXPECT_LE(std::abs(d.mean), 3.0 * d.error + 1e-6);
  sol::test::expect_no_validation_errors();
}

}  // namespace

// Arrays of objects (the scene file's "array": left translates of one
// object) on the kernel as on the CPU: in Sol a street of boxes and a
// lattice of balls (a crowd: 2 + 40 + 36 objects), in the golden quotient a
// 2 × 2 array of balls (listed with its images). The budgets are the other
// kernel-against-CPU comparisons' (1 % of the pixels on edges).
TEST(KernelCrowd, ArraysOfObjectsMatchTheCpuRenderer) {
  const char* sol_street = R"({"camera": {"position": [-1, -2.5, 0.6], "forward": [0.6, 1, -0.25], "up": [0, 0, 1]},
    "objects": [{"type": "plane_z", "c": -0.5, "pattern": "checker"},
      {"type": "array", "count": [10, 2, 2], "step": [0.8, 1.6, 0.5],
       "of": {"type": "box", "center": [0, 0, -0.3], "half_size": [0.2, 0.2, 0.15], "color": [0.9, 0.5, 0.3]}},
      {"type": "array", "count": [6, 3, 2], "step": [0.5, 0.5, 0.4],
       "of": {"type": "ball", "center": [0.5, 0.8, 0.4], "radius": 0.12, "color": [0.3, 0.6, 0.9]}},
      {"type": "plane_y", "c": 4}],
    "lights": [{"type": "point", "position": [1, 0, 2], "intensity": 3}]})";
  const char* golden = R"({"quotient": "golden", "camera": {"position": [0.1, 0.1, 0.2], "forward": [1, 0.3, 0.1]},
    "objects": [{"type": "plane_z", "c": 0.05, "pattern": "circles"},
      {"type": "array", "count": [2, 2, 1], "step": [0.5, 0.5, 0.3],
       "of": {"type": "ball", "center": [0.4, 0.3, 0.5], "radius": 0.1, "color": [0.9, 0.3, 0.3]}}]})";
  for (const char* text : {sol_street, golden}) {
    const sol::Scene scene = sol::parse_scene(text);
    sol::vk::MarchRenderer renderer(vk_context());
    const auto [gpu, cpu, c] = against_cpu(renderer, scene, 48, 36);
    std::set<float> seen(cpu.object.begin(), cpu.object.end());
    std::printf("arrays (%zu objects): %d of %d pixels hit another object, %d differ in colour, distance %.2g, %zu objects seen\n",
                scene.objects.size(), c.mask_differs, c.pixels, c.color_differs, c.distance, seen.size());
    EXPECT_LE(c.mask_differs, c.pixels / 100);
    EXPECT_LE(c.color_differs, c.pixels / 100);
    EXPECT_LT(c.distance, 2e-3);
    EXPECT_GE(seen.size(), scene.quotient() == sol::Quotient::None ? 20u : 3u);  // the copies, not the floor alone
  }
  sol::test::expect_no_validation_errors();
}
