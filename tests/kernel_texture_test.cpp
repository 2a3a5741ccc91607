// Image textures on the kernel against the CPU renderer (the double
// reference, itself checked against the mapping's definition in
// texture_test.cpp): the albedo AOV of textured planes and balls, in Sol
// with the eye far from the origin (the kernel's pattern phase is the eye's
// position modulo sol::kTexturePhase) and in the golden quotient, agrees
// where both devices hit the same object; and a textured world's colour.
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/vk/march.hpp>

#include "support/kernel.hpp"
#include "support/textures.hpp"

namespace {

using sol::test::expect_no_validation_errors;
using sol::test::gradient_texture;
using sol::test::vk_context;

// A floor z = -1 and a ball, both textured (the ball wrapped once: 8 × 4
// cells), seen from `eye`.
sol::Scene textured_world(const glm::dvec3& eye) {
  sol::Scene s = sol::preset_scene("plane");
  s.camera = {eye, glm::normalize(glm::dvec3(0.6, 0.3, -0.5)), {0.0, 0.0, 1.0}, 75.0};
  sol::SceneObject floor{sol::PlaneZ{-1.0}, {0.9, 0.9, 0.9}};
  floor.texture = gradient_texture(8, 8);
  floor.texture_cells = {2.0, 4.0};
  sol::SceneObject ball{sol::Ball{eye + glm::dvec3(1.2, 0.6, -0.7), 0.4}, {1.0, 1.0, 1.0}};
  ball.texture = gradient_texture(16, 8);
  ball.texture_cells = {8.0, 4.0};
  s.objects = {floor, ball};
  return s;
}

void expect_same_albedo(const sol::Scene& scene, const char* name) {
  sol::vk::MarchRenderer kernel(vk_context());
  const sol::RenderResult gpu = sol::test::render(kernel, scene, 48, 36, true);
  const sol::RenderResult cpu = sol::render_cpu(scene, {.width = 48, .height = 36, .guides = true});
  int same = 0, off = 0, hits = 0;
  for (std::size_t k = 0; k < cpu.object.size(); ++k) {
    if (gpu.object[k] != cpu.object[k]) continue;
    ++same;
    hits += cpu.object[k] != 0.0f ? 1 : 0;
    bool differs = false;
    for (int c = 0; c < 3; ++c) differs = differs || std::abs(gpu.albedo[3 * k + c] - cpu.albedo[3 * k + c]) > 2e-3;
    off += differs ? 1 : 0;
  }
  // (A silhouette pixel may hit another object in float; a hit near a
  // texel's edge moves by the float hit point's 1e-5, which changes a
  // bilinear colour by far less than 2e-3: 8 texels a cell at most.)
  EXPECT_GT(same, 0.97 * static_cast<double>(cpu.object.size())) << name;
  EXPECT_GT(hits, 600) << name;
  EXPECT_LE(off, 0.01 * same) << name << ": " << off << " of " << same;
}

TEST(KernelTexture, TexturesLandWhereTheCpuPutsThem) {
  expect_same_albedo(textured_world({0.2, -0.3, 0.1}), "near the origin");
  // Far out, where the eye's position modulo 64 carries the phase.
  expect_same_albedo(textured_world({100.3, -77.9, 0.1}), "far from the origin");
  sol::Scene golden = textured_world({0.4, 0.3, 0.45});
  sol::set_space(golden, sol::GoldenSpace{});
  expect_same_albedo(golden, "golden quotient");
  expect_no_validation_errors();
}

}  // namespace
