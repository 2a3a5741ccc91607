// Composites (sol::Composite): the union, intersection and difference of
// solids. The CPU renderer's hits lie on the exact boundary of the composed
// set, checked with distances to the parts computed here independently: the
// exact Sol distance to a ball's centre (sol::distance, tested against
// 50-digit references) and the exact distances to a box's three slabs
// (asinh(s e^{∓z}) across the planes x, y = const, |Δz| across z = const);
// in Sol and in the quotient; their scene-file keys and checks; the kernel
// refuses them by name.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/composites.hpp"

namespace {

using glm::dvec3;
using sol::test::hits_on_boundary;
using sol::test::part_distance;
using sol::test::PartHits;

sol::Composite composite(sol::CompositeOp op, const sol::Shape& a, const sol::Shape& b) {
  return sol::Composite(op, sol::CompositeParts{a, b});
}

sol::RenderResult render_small(const sol::Scene& scene) {
  sol::RenderOptions settings;
  settings.width = 48;
  settings.height = 36;
  return sol::render_cpu(scene, settings);
}

// A box with a hollow cut by an exact ball, and a lens of two exact balls,
// over a floor, seen from above and in front of them.
sol::Scene composites_scene() {
  sol::Scene s = sol::preset_scene("plane");
  s.camera = {{0.0, -0.9, 0.9}, {0.0, 0.5, -0.85}, {0.0, 0.85, 0.5}, 60.0};
  const sol::Box box{{-0.5, 0.0, 0.0}, {0.35, 0.35, 0.35}};
  const sol::Ball hollow{{-0.5, -0.3, 0.15}, 0.35, true};
  const sol::Ball left{{0.45, 0.0, 0.0}, 0.4, true}, right{{0.65, 0.0, 0.0}, 0.4, true};
  s.objects = {{sol::PlaneZ{-0.6}, {0.8, 0.8, 0.8}, sol::Pattern::Checker},
               {composite(sol::CompositeOp::Difference, box, hollow), {0.9, 0.5, 0.3}},
               {composite(sol::CompositeOp::Intersection, left, right), {0.3, 0.6, 0.9}}};
  return s;
}

void expect_on_boundary(const PartHits& h, const char* name) {
  std::printf("%s: %d hits on A's surface, %d on B's, farthest from the boundary %.2e\n", name, h.on_a, h.on_b,
              h.farthest);
  EXPECT_GT(h.on_a, 20) << name;
  EXPECT_GT(h.on_b, 20) << name;
  EXPECT_LT(h.farthest, 1e-4) << name;
}

TEST(Composite, CpuHitsLieOnTheExactBoundaryInSol) {
  const sol::Scene scene = composites_scene();
  const sol::RenderResult r = render_small(scene);
  std::vector<std::pair<int, sol::Composite>> composites;
  for (int i : {1, 2}) composites.emplace_back(i, std::get<sol::Composite>(scene.objects[i].shape));
  expect_on_boundary(hits_on_boundary(r, composites, 2), "box minus an exact ball");
  expect_on_boundary(hits_on_boundary(r, composites, 3), "two exact balls intersected");
}

TEST(Composite, CpuHitsOfAUnionNeverLieInsideEitherPart) {
  sol::Scene scene = composites_scene();
  const auto& lens = std::get<sol::Composite>(scene.objects[2].shape);
  const sol::Composite united = composite(sol::CompositeOp::Union, lens.parts->a, lens.parts->b);
  scene.objects = {scene.objects[0], {united, {0.3, 0.6, 0.9}}};
  const sol::RenderResult r = render_small(scene);
  expect_on_boundary(hits_on_boundary(r, {{1, united}}, 2), "two exact balls united");
}

// In the golden quotient the hits lie on the boundary of one of the
// composite's images (sol::quotient_images; each image's parts moved by the
// same element of Γ).
TEST(Composite, CpuHitsLieOnTheExactBoundaryInTheQuotient) {
  sol::Scene scene = sol::preset_scene("lattice-boxes");
  const sol::Box box{{0.3, 0.2, 0.3}, {0.2, 0.12, 0.12}};
  const sol::Ball hollow{{0.3, 0.05, 0.4}, 0.17, true};
  scene.objects = {{composite(sol::CompositeOp::Difference, box, hollow), {0.9, 0.5, 0.3}}};
  sol::validate(scene);
  std::vector<std::pair<int, sol::Composite>> images;
  for (const sol::MarchObject& m : sol::quotient_images(scene)) {
    images.emplace_back(static_cast<int>(m.owner), std::get<sol::Composite>(m.shape));
  }
  ASSERT_GT(images.size(), 4u);
  const PartHits h = hits_on_boundary(render_small(scene), images, 1);
  std::printf("quotient: %zu images, %d hits on A's surface, %d on B's, farthest %.2e\n", images.size(), h.on_a,
              h.on_b, h.farthest);
  EXPECT_GT(h.on_a + h.on_b, 200);
  EXPECT_GT(h.on_b, 0);  // the hollow is seen
  EXPECT_LT(h.farthest, 1e-4);
}

// In a quotient a union is listed as its parts' images, each part moved
// into D by its own anchor (sol::quotient_images): the same images, and the
// same picture to the bit, as the parts given as two objects of the union's
// appearance, although part b lies far from part a (a listing that followed
// part a's images alone would miss b's).
TEST(Composite, AUnionInAQuotientIsItsParts) {
  sol::Scene parts = sol::preset_scene("lattice-boxes");
  const sol::Box box{{0.3, 0.2, 0.3}, {0.2, 0.12, 0.12}};
  const sol::Ball ball{{-0.4, 0.9, 0.75}, 0.3};
  parts.objects = {{box, {0.9, 0.5, 0.3}}, {ball, {0.9, 0.5, 0.3}}};
  sol::Scene united = parts;
  united.objects = {{composite(sol::CompositeOp::Union, box, ball), {0.9, 0.5, 0.3}}};
  sol::validate(united);
  const std::vector<sol::MarchObject> a = sol::quotient_images(parts), b = sol::quotient_images(united);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].shape, b[i].shape) << i;
    EXPECT_EQ(b[i].owner, 0u) << i;
  }
  const sol::RenderResult x = render_small(parts), y = render_small(united);
  EXPECT_EQ(x.rgba, y.rgba);
  // Both parts are in view (the two objects' hits), and each is the union's.
  ASSERT_EQ(x.object.size(), y.object.size());
  int on_box = 0, on_ball = 0, differ = 0;
  for (std::size_t k = 0; k < x.object.size(); ++k) {
    on_box += x.object[k] == 1;
    on_ball += x.object[k] == 2;
    differ += (x.object[k] == 0) != (y.object[k] == 0) || (x.object[k] != 0 && y.object[k] != 1);
  }
  EXPECT_GT(on_box, 50);
  EXPECT_GT(on_ball, 50);
  EXPECT_EQ(differ, 0);
  // Scene files keep it a union and read it back alike.
  EXPECT_EQ(sol::parse_scene(sol::to_json(united)).objects[0].shape, united.objects[0].shape);
}

// The composite's distance is a lower bound of the Sol distance to it from
// outside and of the depth from inside: checked against the distances to
// points of its boundary found along geodesics from the point (the
// boundary points the sampled rays meet, by bisection of the parts' exact
// distances along each).
TEST(Composite, DistanceNeverExceedsTheDistanceToTheBoundary) {
  const sol::Box box{{-0.5, 0.0, 0.0}, {0.35, 0.35, 0.35}};
  const sol::Ball hollow{{-0.5, -0.3, 0.15}, 0.35, true};
  const sol::Composite c = composite(sol::CompositeOp::Difference, box, hollow);
  const auto exact_sign = [&](const dvec3& q) {
    return std::max(part_distance(c.parts->a, q), -part_distance(c.parts->b, q));
  };
  std::uint64_t state = 11;
  const auto unit = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  };
  int checked = 0;
  double closest = 1e30;  // the least margin met: the bound is tight somewhere
  for (int n = 0; n < 40; ++n) {
    const dvec3 q = dvec3(-0.5, 0.0, 0.0) + 0.55 * dvec3(unit(), unit(), unit());
    const double d = c.distance(q), s = exact_sign(q);
    EXPECT_EQ(d < 0.0, s < 0.0) << "inside the same set";
    for (int m = 0; m < 8; ++m) {
      const dvec3 u = glm::normalize(dvec3(unit(), unit(), unit()));
      const sol::ClosedFormGeodesic<double> ray(u);
      // The first change of sign along the ray (steps of 0.02, then bisection).
      double lo = 0.0, hi = -1.0;
      for (double t = 0.02; t <= 1.2; t += 0.02) {
        if ((exact_sign(sol::multiply(q, ray.at(t).position)) < 0.0) != (s < 0.0)) {
          hi = t;
          break;
        }
        lo = t;
      }
      if (hi < 0.0) continue;
      for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((exact_sign(sol::multiply(q, ray.at(mid).position)) < 0.0) != (s < 0.0) ? hi : lo) = mid;
      }
      ++checked;
      closest = std::min(closest, hi - std::abs(d));
      EXPECT_LE(std::abs(d), hi + 1e-12) << "a point of the boundary at arc length " << hi;
    }
  }
  std::printf("%d boundary points along rays, the distance below each by at least %.2e\n", checked, closest);
  EXPECT_GT(checked, 100);
}

// The panel's controls (visit_fields): a composite lists its parts' fields,
// prefixed by the part, nested composites by both; an edit through them
// moves the surface (the distance at a point where the ball is the active
// part changes by the radius's change, exactly: a ball's bound is the
// bound of the distance to its centre less the radius) and leaves another composite that shared the parts as
// it was.
TEST(Composite, ThePanelEditsItsPartsByName) {
  const sol::Ball ball{{0.0, 0.0, 0.0}, 0.5}, hole{{0.3, 0.0, 0.0}, 0.2};
  const sol::Box box{{0.0, 0.0, 1.0}, {0.2, 0.2, 0.2}};
  sol::Composite inner = composite(sol::CompositeOp::Difference, ball, hole);
  sol::Composite outer = composite(sol::CompositeOp::Union, inner, box);
  const sol::Composite shared = outer;
  std::vector<std::string> names;
  struct Lister {
    std::vector<std::string>& names;
    void operator()(const char* name, dvec3&) { names.emplace_back(name); }
    void operator()(const char* name, double&, const sol::FieldRange&) { names.emplace_back(name); }
    void operator()(const char* name, bool&) { names.emplace_back(name); }
  };
  outer.visit_fields(Lister{names});
  const std::vector<std::string> expected = {"a: a: centre", "a: a: radius", "a: a: exact (the true geodesic sphere)",
                                             "a: b: centre", "a: b: radius", "a: b: exact (the true geodesic sphere)",
                                             "b: centre",    "b: half size"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(outer.parts, shared.parts) << "listing the fields copied the parts";

  // Grow the outer ball by 0.1 through its control.
  struct Grow {
    void operator()(const char*, dvec3&) {}
    void operator()(const char* name, double& v, const sol::FieldRange&) {
      if (std::string(name) == "a: a: radius") v += 0.1;
    }
    void operator()(const char*, bool&) {}
  };
  outer.visit_fields(Grow{});
  const dvec3 far_side{-0.45, 0.0, 0.0};  // inside the ball, where it is the composite's nearest part
  const double before = sol::distance_lower_bound(far_side, ball.center) - 0.5;  // the ball's bound
  EXPECT_NEAR(shared.distance(far_side), before, 1e-12);
  EXPECT_NEAR(outer.distance(far_side), before - 0.1, 1e-12);
  EXPECT_NE(outer.parts, shared.parts);
}

TEST(Composite, SceneKeysRoundTripAndAreChecked) {
  const sol::Scene s = sol::parse_scene(R"({"objects": [{"type": "difference", "color": [0.9, 0.5, 0.3],
      "a": {"type": "box", "center": [0, 0, 0], "half_size": [0.3, 0.3, 0.3]},
      "b": {"type": "intersection", "a": {"type": "ball", "center": [0, 0, 0.3], "radius": 0.2, "exact": true},
                                    "b": {"type": "tube", "axis": "x", "through": [0, 0, 0.3], "radius": 0.1}}}]})");
  const auto& c = std::get<sol::Composite>(s.objects[0].shape);
  EXPECT_EQ(c.op, sol::CompositeOp::Difference);
  EXPECT_EQ(std::get<sol::Box>(c.parts->a).half_size, dvec3(0.3));
  const auto& inner = std::get<sol::Composite>(c.parts->b);
  EXPECT_EQ(inner.op, sol::CompositeOp::Intersection);
  EXPECT_TRUE(std::get<sol::Ball>(inner.parts->a).exact);
  EXPECT_EQ(sol::kind_name(s.objects[0].shape), "difference");
  EXPECT_EQ(std::get<sol::Composite>(sol::parse_scene(sol::to_json(s)).objects[0].shape), c);
  // Arrays of composites are left translates of the composite: each part moved alike.
  const sol::Scene row = sol::parse_scene(R"({"objects": [{"type": "array", "count": [2, 1, 1], "step": [1, 0, 0],
      "of": {"type": "union", "a": {"type": "ball", "center": [0, 0, 0.5], "radius": 0.2},
                              "b": {"type": "box", "center": [0.2, 0, 0.5], "half_size": [0.1, 0.1, 0.1]}}}]})");
  ASSERT_EQ(row.objects.size(), 2u);
  const auto& second = std::get<sol::Composite>(row.objects[1].shape);
  EXPECT_NEAR(std::get<sol::Ball>(second.parts->a).center.x, 1.0, 1e-12);
  EXPECT_NEAR(std::get<sol::Box>(second.parts->b).center.x, 1.0 + 0.2, 1e-12);
  const std::pair<const char*, const char*> bad[] = {
      {R"({"objects": [{"type": "union", "a": {"type": "ball", "center": [0, 0, 0], "radius": 0.2}}]})", "a part 'b'"},
      {R"({"objects": [{"type": "union", "a": {"type": "ball", "center": [0, 0, 0], "radius": 0.2, "color": [1, 0, 0]},
          "b": {"type": "ball", "center": [0, 0, 0], "radius": 0.2}}]})",
       "objects[0].a: a part takes its kind's keys alone"},
      {R"({"objects": [{"type": "difference", "a": {"type": "ball", "center": [0, 0, 0], "radius": 0.2},
          "b": {"type": "plane_z", "c": 0}}]})",
       "objects[0].b must be a solid"},
      {R"({"objects": [{"type": "difference", "a": {"type": "ball", "center": [0, 0, 0], "radius": -1},
          "b": {"type": "ball", "center": [0, 0, 0], "radius": 0.1}}]})",
       "objects[0].a.radius must be finite and > 0"},
      {R"({"objects": [{"type": "union", "a": {"type": "cone"}, "b": {"type": "ball", "center": [0, 0, 0], "radius": 0.1}}]})",
       "'objects[0].a.type' must be one of plane_x, plane_y, plane_z, ball, tube, box, union, intersection, difference, got"},
      {R"({"objects": [{"type": "intersection", "a": {"type": "ball", "center": [0, 0, 0], "radius": 0.2},
          "b": {"type": "ball", "center": [0, 0, 0], "radius": 0.1}, "radius": 2}]})",
       "unknown key 'radius'"},
      {R"({"quotient": "golden", "objects": [{"type": "difference", "b": {"type": "ball", "center": [0, 0, 0], "radius": 0.2},
          "a": {"type": "union", "a": {"type": "ball", "center": [0.1, 0, 0], "radius": 0.2},
                                 "b": {"type": "ball", "center": [0.3, 0, 0], "radius": 0.2}}}]})",
       "objects[0].a.type: a union as part a of a difference in a quotient"},
      {R"({"quotient": "golden", "objects": [{"type": "difference", "a": {"type": "ball", "center": [0, 0, 0], "radius": 0.5},
          "b": {"type": "ball", "center": [0.1, 0, 0], "radius": 0.2}}]})",
       "objects[0].a.radius must be <= 0.45 in the quotient"},
  };
  for (const auto& [text, words] : bad) {
    try {
      (void)sol::parse_scene(text, "bad.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
}

}  // namespace
