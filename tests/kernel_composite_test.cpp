// Composites on the kernel (compute/shaders/march/composites.glsl) against
// the CPU renderer's (sol::Composite, the double reference): unions,
// intersections and differences of boxes, balls and tubes in a listed Sol
// world, seen from outside and from inside, in the golden quotient and as
// a crowd (an array of them). The images agree with the CPU's within the
// tolerances of float against double (a silhouette or edge pixel may go
// either way: at most 1 % of the pixels differ in object, and 1 % by more
// than 2e-3 in colour), and the hits on the composites of boxes lie on the
// exact boundary of the composed set (sol::test::hits_on_boundary, from
// the exact distances to the boxes' slabs: within 1e-4, hit_epsilon 5e-5
// and the float rounding of the hit point).
#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/vk/march.hpp>

#include "support/composites.hpp"
#include "support/kernel.hpp"

namespace {

using glm::dvec3;
using sol::test::expect_no_validation_errors;
using sol::test::vk_context;

sol::Composite composite(sol::CompositeOp op, const sol::Shape& a, const sol::Shape& b) {
  return sol::Composite(op, sol::CompositeParts{a, b});
}

// A box with a notch (a box taken from its corner), two boxes intersected,
// a ball united with a box and a box with a ball's hollow, over a floor.
sol::Scene composites_scene() {
  sol::Scene s = sol::preset_scene("plane");
  s.camera = {{0.0, -0.9, 0.9}, {0.0, 0.5, -0.85}, {0.0, 0.85, 0.5}, 70.0};
  const sol::Box block{{-0.5, 0.0, 0.0}, {0.35, 0.35, 0.35}}, notch{{-0.6, -0.3, 0.25}, {0.2, 0.2, 0.2}};
  const sol::Box left{{0.45, 0.0, 0.0}, {0.3, 0.3, 0.3}}, right{{0.6, -0.15, 0.0}, {0.3, 0.3, 0.3}};
  s.objects = {{sol::PlaneZ{-0.6}, {0.8, 0.8, 0.8}, sol::Pattern::Checker},
               {composite(sol::CompositeOp::Difference, block, notch), {0.9, 0.5, 0.3}},
               {composite(sol::CompositeOp::Intersection, left, right), {0.3, 0.6, 0.9}, sol::Pattern::Checker},
               {composite(sol::CompositeOp::Union, sol::Ball{{-0.1, 0.7, 0.1}, 0.25}, sol::Box{{0.15, 0.7, 0.0}, {0.15, 0.15, 0.2}}),
                {0.5, 0.8, 0.4}},
               {composite(sol::CompositeOp::Difference, sol::Box{{0.2, -0.45, -0.4}, {0.2, 0.1, 0.15}},
                          sol::Tube{{0.2, -0.45, -0.25}, {0.0, 0.0, 1.0}, 0.08}),
                {0.8, 0.8, 0.3}}};
  return s;
}

struct Checked {
  const char* name;
  sol::Scene scene;
  std::vector<std::pair<int, sol::Composite>> boxes;  // the composites of boxes to hold to their boundary
};

void expect_kernel_as_cpu(sol::vk::MarchRenderer& renderer, const Checked& c) {
  sol::RenderOptions settings;
  settings.width = 48;
  settings.height = 36;
  const sol::RenderResult cpu = sol::render_cpu(c.scene, settings);
  const sol::RenderResult gpu = sol::test::render(renderer, c.scene, settings.width, settings.height);
  const sol::test::ImageComparison d = sol::test::compare_images(gpu, cpu, 2e-3f);
  std::printf("%s: against the CPU, object differs at %d of %d pixels, colour at %d (worst %.1e)\n", c.name,
              d.mask_differs, d.pixels, d.color_differs, d.worst_color);
  EXPECT_LE(d.mask_differs, d.pixels / 100) << c.name;
  EXPECT_LE(d.color_differs, d.pixels / 100) << c.name;
  std::vector<int> objects;
  for (const auto& [index, composite] : c.boxes) {
    if (std::find(objects.begin(), objects.end(), index) == objects.end()) objects.push_back(index);
  }
  for (int index : objects) {
    for (const auto& [device, image] : {std::pair{"kernel", &gpu}, std::pair{"CPU", &cpu}}) {
      const sol::test::PartHits h = sol::test::hits_on_boundary(*image, c.boxes, index + 1);
      std::printf("  %s, object %d: %d hits on A's surface, %d on B's, farthest from the boundary %.2e\n", device,
                  index, h.on_a, h.on_b, h.farthest);
      EXPECT_GT(h.on_a, 10) << c.name << " " << device << " object " << index;
      EXPECT_GT(h.on_b, 10) << c.name << " " << device << " object " << index;
      EXPECT_LT(h.farthest, 1e-4) << c.name << " " << device << " object " << index;
    }
  }
}

std::pair<int, sol::Composite> composite_of(const sol::Scene& scene, int k) {
  return {k, std::get<sol::Composite>(scene.objects[k].shape)};
}

TEST(KernelComposite, UnionsIntersectionsAndDifferencesAreTheCpus) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene outside = composites_scene();
  expect_kernel_as_cpu(renderer, {"composites", outside, {composite_of(outside, 1)}});
  // The intersection from beside its corner: its front face A's, its side B's.
  sol::Scene corner = outside;
  corner.camera = {{-0.1, -0.9, 0.25}, {0.55, 0.8, -0.25}, {0.0, 0.0, 1.0}, 60.0};
  expect_kernel_as_cpu(renderer, {"two boxes intersected", corner, {composite_of(corner, 2)}});
  // Chains: the notched block with a second notch and a tube through it
  // ((block \ notch) \ notch) \ tube, and a union of three.
  sol::Scene chains = outside;
  const sol::Shape notched = outside.objects[1].shape;
  chains.objects[1].shape = composite(sol::CompositeOp::Difference,
                                      composite(sol::CompositeOp::Difference, notched,
                                                sol::Box{{-0.35, -0.3, 0.25}, {0.1, 0.2, 0.1}}),
                                      sol::Tube{{-0.5, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.1});
  chains.objects[3].shape = composite(sol::CompositeOp::Union, outside.objects[3].shape, sol::Ball{{0.35, 0.7, 0.2}, 0.12});
  ASSERT_EQ(sol::composite_chain(std::get<sol::Composite>(chains.objects[1].shape)).size(), 4u);
  expect_kernel_as_cpu(renderer, {"chains of composites", chains, {}});
  // Unions as parts b: the block less (a notch ∪ the tube), the boxes'
  // overlap intersected with (a slab ∩ a ball), joined to their chains
  // part by part.
  sol::Scene nested = outside;
  nested.objects[1].shape = composite(sol::CompositeOp::Difference, notched,
                                      composite(sol::CompositeOp::Union, sol::Box{{-0.35, -0.3, 0.25}, {0.1, 0.2, 0.1}},
                                                sol::Tube{{-0.5, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.1}));
  nested.objects[2].shape = composite(sol::CompositeOp::Intersection, outside.objects[2].shape,
                                      composite(sol::CompositeOp::Intersection, sol::Box{{0.55, 0.0, 0.0}, {0.5, 0.5, 0.2}},
                                                sol::Ball{{0.55, 0.0, 0.1}, 0.45}));
  ASSERT_EQ(sol::composite_chain(std::get<sol::Composite>(nested.objects[1].shape)).size(), 4u);
  ASSERT_EQ(sol::composite_chain(std::get<sol::Composite>(nested.objects[2].shape)).size(), 4u);
  ASSERT_EQ(sol::vk::MarchRenderer::unsupported(nested), "");
  expect_kernel_as_cpu(renderer, {"unions as parts b", nested, {}});
  // From inside the notched block, facing its notch: its walls and the notch seen from within.
  sol::Scene inside = outside;
  inside.camera = {{-0.45, 0.15, -0.1}, {-0.2, -1.0, 0.35}, {0.0, 0.0, 1.0}, 90.0};
  expect_kernel_as_cpu(renderer, {"from inside the notched block", inside, {composite_of(inside, 1)}});
  expect_no_validation_errors();
}

// In the golden quotient every image of a notched box (each moved whole by
// its element of Γ, sol::quotient_images) and of a union (part by part), and
// as a crowd, twelve notched
// boxes in an array (the tree of bounds, march/crowd.glsl).
TEST(KernelComposite, QuotientsAndCrowdsAreTheCpus) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene lattice = sol::preset_scene("lattice-boxes");
  lattice.objects = {{composite(sol::CompositeOp::Difference, sol::Box{{0.3, 0.2, 0.3}, {0.2, 0.12, 0.12}},
                                sol::Box{{0.38, 0.12, 0.38}, {0.1, 0.08, 0.08}}),
                      {0.9, 0.5, 0.3}}};
  sol::validate(lattice);
  std::vector<std::pair<int, sol::Composite>> images;
  for (const sol::MarchObject& m : sol::quotient_images(lattice)) {
    images.emplace_back(static_cast<int>(m.owner), std::get<sol::Composite>(m.shape));
  }
  expect_kernel_as_cpu(renderer, {"notched boxes in the quotient", lattice, images});
  // A union there is its parts' images, each part moved by its own anchor.
  lattice.objects = {{composite(sol::CompositeOp::Union, sol::Box{{0.3, 0.2, 0.3}, {0.2, 0.12, 0.12}},
                                sol::Ball{{-0.4, 0.9, 0.75}, 0.3}),
                      {0.9, 0.5, 0.3}}};
  expect_kernel_as_cpu(renderer, {"a box and a ball united in the quotient", lattice, {}});

  sol::Scene crowd = sol::parse_scene(R"({"camera": {"position": [0.5, -1.6, 1.2], "forward": [0, 0.6, -0.8], "up": [0, 0.8, 0.6]},
    "objects": [{"type": "plane_z", "c": -0.5, "pattern": "checker"}, {"type": "array", "count": [3, 2, 2], "step": [0.6, 0.7, 0.5],
      "of": {"type": "difference", "color": [0.9, 0.5, 0.3],
             "a": {"type": "box", "center": [0, 0, 0], "half_size": [0.2, 0.2, 0.15]},
             "b": {"type": "box", "center": [-0.1, -0.1, 0.1], "half_size": [0.12, 0.12, 0.1]}}}],
    "lights": [{"type": "directional", "direction": [0.3, -0.5, 1]}]})");
  ASSERT_EQ(crowd.objects.size(), 13u);
  std::vector<std::pair<int, sol::Composite>> boxes;
  for (int k = 1; k < 13; ++k) boxes.push_back(composite_of(crowd, k));
  expect_kernel_as_cpu(renderer, {"a crowd of notched boxes", crowd, {}});
  sol::RenderOptions settings;
  settings.width = 48;
  settings.height = 36;
  const sol::RenderResult gpu = sol::test::render(renderer, crowd, settings.width, settings.height);
  double farthest = 0.0;
  int hits = 0;
  for (int k = 1; k < 13; ++k) {
    const sol::test::PartHits h = sol::test::hits_on_boundary(gpu, boxes, k + 1);
    farthest = std::max(farthest, h.farthest);
    hits += h.on_a + h.on_b;
  }
  std::printf("  crowd on the kernel: %d hits on the notched boxes, farthest from a boundary %.2e\n", hits, farthest);
  EXPECT_GT(hits, 100);
  EXPECT_LT(farthest, 1e-4);
  expect_no_validation_errors();
}

// Composites the kernel does not draw (of exact balls, with a composite
// other than a union as their part b, of more than kMaxCompositeParts parts)
// are refused by name, and render on the CPU under --device auto.
TEST(KernelComposite, CompositesOfExactBallsOrCompositesAreTheCpus) {
  sol::Scene scene = composites_scene();
  scene.objects[2].shape = composite(sol::CompositeOp::Intersection, sol::Ball{{0.45, 0.0, 0.0}, 0.4, true},
                                     sol::Ball{{0.65, 0.0, 0.0}, 0.4, true});
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene), "objects[2].b: composites of exact balls render on the CPU only");
  scene.objects[2].shape = composite(sol::CompositeOp::Union, sol::Ball{}, scene.objects[1].shape);
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene),
            "objects[2].b: a composite as a part b renders on the CPU only unless it is a union (an intersection under "
            "an intersection): nest it as part a");
  scene.objects[2].shape = composite(sol::CompositeOp::Difference, sol::Ball{},
                                     composite(sol::CompositeOp::Union, sol::Ball{}, sol::Ball{{0.1, 0.0, 0.0}, 0.4, true}));
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene), "objects[2].b.b: composites of exact balls render on the CPU only");
  sol::Shape chain = sol::Box{};
  for (int k = 0; k < 8; ++k) chain = composite(sol::CompositeOp::Difference, chain, sol::Ball{{0.1 * k, 0.0, 0.0}, 0.1});
  scene.objects[2].shape = chain;
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene), "objects[2]: composites of more than 8 parts render on the CPU only");
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(composites_scene()), "");
}

}  // namespace
