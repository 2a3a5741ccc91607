// The path tracer's tests on the CPU renderer (tests/render_test.cpp) and
// the kernel (tests/kernel_test.cpp): statistics of path-traced images, and
// the scenes both render.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace sol::test {

/// A mean and its standard error (the spread of the values over √(n − 1)).
struct MeanAndError {
  double mean = 0.0;
  double error = 0.0;
};

/// The red channel's mean over the pixels of an image.
inline MeanAndError red_mean(const sol::RenderResult& r) {
  const std::size_t n = r.rgba.size() / 4;
  double sum = 0.0, squares = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sum += r.rgba[4 * k];
    squares += static_cast<double>(r.rgba[4 * k]) * r.rgba[4 * k];
  }
  const double mean = sum / static_cast<double>(n);
  return {mean, std::sqrt(std::max(0.0, squares / static_cast<double>(n) - mean * mean) / static_cast<double>(n - 1))};
}

/// A furnace's image against its radiance E / (1 − ρ): the red channel's
/// mean within 4 standard errors of `expected` (the error not 0: a noisy
/// estimate), printed as `what` says.
inline void expect_furnace_mean(const sol::RenderResult& r, double expected, const std::string& what) {
  const MeanAndError m = red_mean(r);
  std::printf("%s: %.4f (expected %.4f, standard error %.4f)\n", what.c_str(), m.mean, expected, m.error);
  EXPECT_GT(m.error, 0.0) << what;
  EXPECT_LT(std::abs(m.mean - expected), 4.0 * m.error) << what;
}

/// The pixel-by-pixel difference of the red channels of two images of the
/// same size: its mean over the pixels, 0 for two unbiased estimators of
/// one image (the image's own variation cancels).
inline MeanAndError red_difference(const sol::RenderResult& a, const sol::RenderResult& b) {
  sol::RenderResult d = a;
  for (std::size_t k = 0; k < d.rgba.size(); ++k) d.rgba[k] = a.rgba[k] - b.rgba[k];
  return red_mean(d);
}

/// Two unbiased estimators of one image agree: the mean of their red
/// channels' pixel-by-pixel difference within 3 standard errors of 0,
/// printed as `what` says.
inline void expect_estimators_agree(const sol::RenderResult& a, const sol::RenderResult& b, const std::string& what) {
  const MeanAndError d = red_difference(a, b);
  std::printf("%s: mean difference %.4f, standard error %.4f\n", what.c_str(), d.mean, d.error);
  EXPECT_LT(std::abs(d.mean), 3.0 * d.error) << what;
}

/// The pixels whose three channels agree to `tolerance` (relative above 1).
inline std::size_t pixels_agreeing(const sol::RenderResult& a, const sol::RenderResult& b, float tolerance) {
  std::size_t agree = 0;
  for (std::size_t k = 0; k < a.rgba.size() / 4; ++k) {
    bool same = true;
    for (std::size_t c = 0; c < 3; ++c) {
      same = same && std::abs(a.rgba[4 * k + c] - b.rgba[4 * k + c]) <= tolerance * std::max(1.0f, b.rgba[4 * k + c]);
    }
    agree += same ? 1 : 0;
  }
  return agree;
}

/// The median over the pixels where `reference` shows scene object
/// `object` (1-based, RenderResult::object) of |a - reference| in red: an
/// image's error robust to a path's long tail (a rare path that finds a
/// glow from close by moves an RMS by a factor of 2 between runs).
inline double median_red_error_on(const sol::RenderResult& a, const sol::RenderResult& reference, int object) {
  std::vector<double> errors;
  for (std::size_t k = 0; k < a.object.size(); ++k) {
    if (reference.object[k] == static_cast<float>(object)) errors.push_back(std::abs(a.rgba[4 * k] - reference.rgba[4 * k]));
  }
  if (errors.empty()) return 0.0;
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
  return errors[errors.size() / 2];
}

/// Path tracing options: `samples` paths a pixel from `seed`, by `sampling`.
inline sol::RenderOptions path_options(int width, int height, int samples, std::uint64_t seed,
                                       sol::PathSampling sampling = sol::PathSampling::Combined) {
  sol::RenderOptions settings;
  settings.width = width;
  settings.height = height;
  settings.samples = samples;
  settings.transport = sol::Transport::Path;
  settings.path_sampling = sampling;
  settings.seed = seed;
  return settings;
}

/// The three estimators' CPU images of `scene` (width × height, `samples`
/// paths a pixel; combined from seed 1, reflection alone from 2, next-event
/// estimation alone from 3), held to agree pairwise (expect_estimators_agree).
struct ThreeStrategies {
  sol::RenderResult combined, reflection, glow;
};
inline ThreeStrategies three_strategies_agree(const sol::Scene& scene, int width, int height, int samples,
                                              const std::string& where = "") {
  auto render = [&](sol::PathSampling sampling, std::uint64_t seed) {
    return sol::render_cpu(scene, path_options(width, height, samples, seed, sampling));
  };
  ThreeStrategies out{render(sol::PathSampling::Combined, 1), render(sol::PathSampling::ReflectionOnly, 2),
                      render(sol::PathSampling::GlowOnly, 3)};
  expect_estimators_agree(out.combined, out.reflection, where + "combined - reflection");
  expect_estimators_agree(out.combined, out.glow, where + "combined - glow");
  expect_estimators_agree(out.reflection, out.glow, where + "reflection - glow");
  return out;
}

/// That `scene`'s glowing objects are no targets of next-event estimation:
/// alone, it is reflection sampling, path for path (6 × 4, 2 paths, one seed).
inline void expect_no_glow_targets(const sol::Scene& scene, const std::string& where) {
  EXPECT_EQ(sol::render_cpu(scene, path_options(6, 4, 2, 5, sol::PathSampling::GlowOnly)).rgba,
            sol::render_cpu(scene, path_options(6, 4, 2, 5, sol::PathSampling::ReflectionOnly)).rgba)
      << where;
}

/// A small glowing exact ball over a diffuse plane, seen from above.
inline sol::Scene glow_over_plane() {
  sol::Scene s;
  s.camera = {{0.3, 0.2, 1.2}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 70.0};
  sol::SceneObject glow{sol::Ball{{0.0, 0.0, 0.4}, 0.15, true}, {0.5, 0.5, 0.5}};
  glow.emission = {4.0, 3.0, 2.0};
  s.objects = {{sol::PlaneZ{0.0}, {0.7, 0.7, 0.7}}, glow};
  s.lights.clear();
  s.max_distance = 6.0;
  return s;
}

/// The same in the golden quotient: a small glowing exact ball over a
/// diffuse torus fibre z = 0.1, each seen again in its images around D.
inline sol::Scene glow_over_plane_golden() {
  sol::Scene s;
  s.space = sol::GoldenSpace{};
  s.camera = {{0.6, 0.5, 0.85}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 80.0};
  sol::SceneObject glow{sol::Ball{{0.5, 0.4, 0.45}, 0.12, true}, {0.5, 0.5, 0.5}};
  glow.emission = {4.0, 3.0, 2.0};
  s.objects.clear();  // (one by one: GCC's -Wmaybe-uninitialized misreads a list of them here)
  s.objects.push_back({sol::PlaneZ{0.1}, {0.7, 0.7, 0.7}});
  s.objects.push_back(glow);
  s.lights.clear();
  s.max_distance = 6.0;
  return s;
}

/// A glowing lamp (a flat box, or a ball drawn by its bound: the kinds
/// whose points next-event estimation draws by sol/surface_light.h) over a
/// diffuse plane, beside a diffuse ball, seen from above; in the golden
/// quotient (`golden`) the plane is the torus fibre z = 0.1 and every one
/// of them is seen again in its images around D.
inline sol::Shape flat_box_lamp() { return sol::Box{{0.0, 0.1, 0.4}, {0.25, 0.15, 0.04}}; }
inline sol::Shape bound_ball_lamp() { return sol::Ball{{0.0, 0.1, 0.4}, 0.12, false}; }
/// Infinite lamps over the floor: a thin tube along x (y, vertical), a
/// target of next-event estimation over a window about the diffuse point's
/// foot on its axis (sol/surface_light.h); a glowing ceiling z = 1.2 and a
/// wall x = -0.9, found by reflection.
inline sol::Shape tube_lamp(sol::TubeAxis axis) {
  const glm::dvec3 through = axis == sol::TubeAxis::Z ? glm::dvec3(-0.25, 0.35, 0.0) : glm::dvec3(0.0, 0.1, 0.4);
  return sol::make_tube(axis, through, 0.04, sol::Lattice::default_axes());
}
inline sol::Shape ceiling_lamp() { return sol::PlaneZ{1.2}; }
inline sol::Shape wall_lamp() { return sol::PlaneX{-0.9}; }
inline sol::Scene lamp_over_plane(const sol::Shape& shape, bool golden = false) {
  sol::Scene s;
  if (golden) s.space = sol::GoldenSpace{};
  s.camera = {{0.45, 0.2, 0.8}, {-0.3, 0.0, -1.0}, {0.0, 1.0, 0.0}, 70.0};
  sol::SceneObject lamp{shape, {0.5, 0.5, 0.5}};
  lamp.emission = {4.0, 3.0, 2.0};
  s.objects.clear();  // (one by one, as in glow_over_plane_golden)
  s.objects.push_back({sol::PlaneZ{golden ? 0.1 : 0.0}, {0.7, 0.7, 0.7}});
  s.objects.push_back(lamp);
  s.objects.push_back({sol::Ball{{0.55, -0.2, 0.12}, 0.12, false}, {0.6, 0.6, 0.6}});
  s.lights.clear();
  s.max_distance = 6.0;
  return s;
}

/// A glowing exact ball (radius 0.5 at (5, 5, 0)) about 6 from a diffuse
/// ball (radius 0.5 at the origin) seen from between them, with
/// next-event estimation's `reach` (SceneObject::glow_reach). At that
/// distance points have several geodesics between them within 3 of the
/// shortest (sol::geodesics_between), and the longer ones bring most of
/// the glowing ball's light.
inline sol::Scene far_glow(double reach) {
  sol::Scene s;
  s.camera = {{1.2, 1.2, 0.1}, {-1.0, -1.0, -0.1}, {0.0, 0.0, 1.0}, 40.0};
  sol::SceneObject glow{sol::Ball{{5.0, 5.0, 0.0}, 0.5, true}, {0.5, 0.5, 0.5}};
  glow.emission = {40.0, 40.0, 40.0};
  glow.glow_reach = reach;
  s.objects.clear();  // (one by one, as in glow_over_plane_golden)
  s.objects.push_back({sol::Ball{{0.0, 0.0, 0.0}, 0.5, false}, {0.7, 0.7, 0.7}});
  s.objects.push_back(glow);
  s.lights.clear();
  s.max_distance = 12.0;
  return s;
}

/// A camera at the origin inside a solid that emits 0.5 and reflects with
/// albedo 0.6 (a share `mirror` of it specular), nothing else, in Sol or a
/// quotient: every path's expected radiance is 0.5 / (1 - 0.6) = 1.25
/// (2.5 with a mirror share 0.5), whatever the solid's shape. At the
/// world's default limits (max_steps 200): no ray may run out of steps in
/// an enclosure (RenderResult::rays_out_of_steps).
/// The furnace's wall: `solid`, emitting 0.5, albedo 0.6 (a share `mirror` specular).
inline sol::SceneObject furnace_wall(const sol::Shape& solid, double mirror = 0.0) {
  sol::SceneObject wall{solid, {0.6, 0.6, 0.6}};
  wall.emission = {0.5, 0.5, 0.5};
  wall.mirror = mirror;
  return wall;
}

inline sol::Scene furnace_in(const sol::Shape& solid, sol::Quotient quotient = sol::Quotient::None, double mirror = 0.0) {
  sol::Scene s;
  s.space = sol::default_space(quotient);
  s.camera = {{0.0, 0.0, 0.0}, {1.0, 0.2, 0.1}, {0.0, 0.0, 1.0}, 90.0};
  s.objects = {furnace_wall(solid, mirror)};
  s.lights.clear();
  return s;
}

/// The furnace in an exact ball of radius 1 about the camera.
inline sol::Scene furnace(double mirror) {
  return furnace_in(sol::Ball{{0.0, 0.0, 0.0}, 1.0, true}, sol::Quotient::None, mirror);
}

/// A room inside a glowing exact ball (radius 1 about the origin, emission
/// 0.5, a checkered albedo 0.6) holding a grey box near its wall and a
/// small glowing bound ball, seen from inside: next-event estimation from
/// the box finds the sphere along geodesics the box shadows, from the wall
/// the lamp alone (the ball whose inner wall it is no target from there),
/// and every path's exit from the wall lands where the checker says (the
/// march's exit search, MarchResume::exit_k).
inline sol::Scene room_in_a_glowing_ball() {
  sol::Scene s = furnace(0.0);
  s.objects[0].pattern = sol::Pattern::Checker;
  sol::SceneObject box{sol::Box{{0.45, 0.0, -0.1}, {0.15, 0.35, 0.3}}, {0.5, 0.5, 0.5}};
  s.objects.push_back(box);
  sol::SceneObject lamp{sol::Ball{{-0.1, -0.4, 0.35}, 0.08, false}, {0.5, 0.5, 0.5}};
  lamp.emission = {2.0, 2.0, 2.0};
  s.objects.push_back(lamp);
  s.camera = {{-0.4, 0.05, 0.0}, {1.0, 0.0, 0.05}, {0.0, 0.0, 1.0}, 90.0};
  return s;
}

/// Lossless glass in a furnace: a clear glass ball (index 1.5, white, drawn
/// by its bound) inside a box that emits 0.5 with albedo 0.6, seen from
/// inside the box: every pixel still holds E / (1 - ρ) = 1.25.
inline sol::Scene glass_furnace() {
  sol::Scene s = furnace_in(sol::Box{{0.0, 0.0, 0.0}, {0.9, 0.9, 0.9}});
  s.camera = {{-0.3, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 60.0};
  sol::SceneObject glass{sol::Ball{{0.45, 0.0, 0.0}, 0.3, false}, {1.0, 1.0, 1.0}};
  glass.material = sol::Material::Glass;
  glass.ior = 1.5;
  s.objects.push_back(glass);
  return s;
}

/// A checkered floor, a patterned ball and a glowing one, lit by ambient
/// light alone (no shadow ray to stop at glass), in `quotient` ("none",
/// "golden"); with `ior`, seen through a white glass ball of that index in
/// front of them (the last object).
inline sol::Scene behind_glass(std::optional<double> ior, const std::string& quotient = "none") {
  std::string text = R"({"quotient": ")" + quotient + R"(",
    "camera": {"position": [0, 0, 0.4], "look_at": [2, 0, 0.3], "up": [0, 0, 1], "fov": 50},
    "lights": [], "ambient": 1.0, "max_distance": 8,
    "objects": [{"type": "plane_z", "c": 0, "color": [0.8, 0.8, 0.8], "pattern": "checker"},
                {"type": "ball", "center": [2.5, 0.2, 0.3], "radius": 0.3, "color": [0.9, 0.3, 0.2], "pattern": "circles"},
                {"type": "ball", "center": [2.5, -0.6, 0.5], "radius": 0.2, "color": [1, 1, 1], "emission": [2, 2, 1]})";
  if (ior) {
    text += R"(, {"type": "ball", "center": [1.5, 0, 0.35], "radius": 0.3, "material": "glass", "ior": )" +
            std::to_string(*ior) + R"(, "color": [1, 1, 1]})";
  }
  return sol::parse_scene(text + "]}");
}

}  // namespace sol::test
