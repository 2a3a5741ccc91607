// Boxes (sol::Box): center · ([-a, a] x [-b, b] x [-c, c]). Their bound is
// held to the exact Sol distance (sol::distance, tested against 50-digit
// references): a lower bound everywhere, equal to the distance to the
// nearest face near the faces (where the perpendicular's foot lies on the
// face); their coordinate box is the left translate's; the CPU renderer's
// hits lie on the faces, in Sol and in the quotient; scene-file keys.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/boxes.hpp"

namespace {

using glm::dvec3;

// Boxes at several heights and of several proportions.
std::vector<sol::Box> boxes() {
  return {sol::Box{{0.3, -0.2, 0.4}, {0.25, 0.15, 0.2}}, sol::Box{{1.0, 2.0, -1.2}, {0.6, 0.1, 0.35}},
          sol::Box{{-0.5, 0.7, 1.5}, {0.05, 0.4, 0.1}}, sol::Box{{0.0, 0.0, 0.0}, {0.15, 0.15, 0.15}}};
}

using sol::test::coordinate_box;
using Interval3 = sol::test::CoordinateBox;

// A point of the box at local coordinates t in [-1, 1]³: center · (t * half_size).
dvec3 box_point(const sol::Box& box, const dvec3& t) { return sol::multiply(box.center, t * box.half_size); }

TEST(Box, IsTheLeftTranslateOfItsCoordinateBox) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const sol::Box& box : boxes()) {
    const Interval3 c = coordinate_box(box);
    for (int n = 0; n < 200; ++n) {
      const dvec3 p = box_point(box, {unit(rng), unit(rng), unit(rng)});
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p[k], c.lo[k] - 1e-12);
        EXPECT_LE(p[k], c.hi[k] + 1e-12);
      }
      EXPECT_LE(box.distance(p), 1e-12);  // inside: the bound is at most 0
    }
    // The corners of the local box are the coordinate box's.
    const dvec3 corner = box_point(box, {1.0, -1.0, 1.0});
    EXPECT_NEAR(corner.x, c.hi.x, 1e-12);
    EXPECT_NEAR(corner.y, c.lo.y, 1e-12);
    EXPECT_NEAR(corner.z, c.hi.z, 1e-12);
  }
}

TEST(Box, BoundNeverExceedsTheDistanceToAnyPointOfTheBox) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), around(-2.5, 2.5);
  for (const sol::Box& box : boxes()) {
    double closest = 1e30;  // the least margin d(q, s) - bound(q) met
    for (int n = 0; n < 300; ++n) {
      const dvec3 q = box_point(box, {around(rng), around(rng), around(rng)});
      const double bound = box.distance(q);
      if (!(bound > 0.0)) continue;
      for (int m = 0; m < 40; ++m) {  // points of the faces
        dvec3 t(unit(rng), unit(rng), unit(rng));
        t[m % 3] = m % 2 == 0 ? 1.0 : -1.0;
        const double d = sol::distance(q, box_point(box, t));
        closest = std::min(closest, d - bound);
        ASSERT_LE(bound, d + 1e-12) << "sample " << n;
      }
    }
    std::printf("box at (%g, %g, %g): bound below the distance to every face point sampled, by at least %.2e\n",
                box.center.x, box.center.y, box.center.z, closest);
  }
}

// The closest point of the plane x = c to q lies in the plane y = q_y (a
// hyperbolic plane, coordinates X = x, Y = e^{z}: the upper half plane),
// where x = c is a vertical line and the geodesic meeting it at right
// angles is the circle about (c, 0) through q: its foot is at height
// e^{2 z_F} = (x - c)² + e^{2z}. For y = c (Y = e^{-z}): e^{-2 z_F} =
// (y - c)² + e^{-2z}. For z = c: straight up or down. Where that foot lies
// on the face, the distance to the face is the distance to its plane, which
// the bound must equal.
TEST(Box, BoundIsTheExactDistanceNearEachFace) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-0.9, 0.9), gap(1e-4, 0.3);
  for (const sol::Box& box : boxes()) {
    const Interval3 c = coordinate_box(box);
    double worst = 0.0;
    int checked = 0;
    for (int n = 0; n < 600; ++n) {
      const int face = n % 6, axis = face / 2;
      const bool high = face % 2 == 0;
      // A point just off the face, over its interior.
      dvec3 t(unit(rng), unit(rng), unit(rng));
      t[axis] = high ? 1.0 : -1.0;
      dvec3 q = box_point(box, t);
      const double g = gap(rng);
      dvec3 foot = q;
      if (axis == 0) {
        q.x += (high ? 1.0 : -1.0) * g * std::exp(q.z);
        const double plane = high ? c.hi.x : c.lo.x;
        foot = {plane, q.y, 0.5 * std::log((q.x - plane) * (q.x - plane) + std::exp(2.0 * q.z))};
      } else if (axis == 1) {
        q.y += (high ? 1.0 : -1.0) * g * std::exp(-q.z);
        const double plane = high ? c.hi.y : c.lo.y;
        foot = {q.x, plane, -0.5 * std::log((q.y - plane) * (q.y - plane) + std::exp(-2.0 * q.z))};
      } else {
        q.z += (high ? 1.0 : -1.0) * g;
        foot = {q.x, q.y, high ? c.hi.z : c.lo.z};
      }
      // Only where the foot is on the face (within its other two ranges).
      bool on_face = true;
      for (int k = 0; k < 3; ++k) on_face = on_face && (k == axis || (foot[k] >= c.lo[k] && foot[k] <= c.hi[k]));
      if (!on_face) continue;
      ++checked;
      const double exact = sol::distance(q, foot);
      worst = std::max(worst, std::abs(box.distance(q) - exact));
    }
    std::printf("box at (%g, %g, %g): %d points near the faces, bound within %.1e of the exact distance\n",
                box.center.x, box.center.y, box.center.z, checked, worst);
    EXPECT_GT(checked, 300);
    EXPECT_LT(worst, 1e-10);
  }
}

// Every hit of the CPU renderer on a box lies on a face of its coordinate
// box: within 1e-4 in Sol distance of the box (hit_epsilon 5e-5, and near
// an edge up to √3 times that), and on its boundary (not deeper inside
// than that): sol::test::distance_from_faces.
void expect_hits_on_faces(const sol::RenderResult& r, const std::vector<sol::Box>& boxes, const char* name) {
  const sol::test::FaceHits f = sol::test::hits_on_faces(r, boxes);
  std::printf("%s: %d box hits, farthest from a face %.2e\n", name, f.hits, f.farthest);
  EXPECT_GT(f.hits, static_cast<int>(r.object.size()) / 20) << name;
  EXPECT_LT(f.farthest, 1e-4) << name;
}

sol::RenderResult render_small(const sol::Scene& scene) {
  sol::RenderOptions settings;
  settings.width = 40;
  settings.height = 30;
  return sol::render_cpu(scene, settings);
}

TEST(Box, CpuHitsLieOnTheFacesInSol) {
  const sol::Scene beside = sol::test::box_scene(), from_slab = sol::test::box_scene_from_its_slab();
  const std::vector<sol::Box> box = {std::get<sol::Box>(beside.objects[0].shape)};
  expect_hits_on_faces(render_small(beside), box, "box in Sol");
  expect_hits_on_faces(render_small(from_slab), box, "box from inside its x slab");
}

TEST(Box, CpuHitsLieOnTheFacesInTheQuotient) {
  const sol::Scene scene = sol::preset_scene("lattice-boxes");
  expect_hits_on_faces(render_small(scene), sol::test::box_images(scene), "lattice-boxes");
}

TEST(Box, SceneKeysRoundTripAndAreChecked) {
  const sol::Scene s = sol::parse_scene(
      R"({"objects": [{"type": "box", "center": [1, 2, 0.5], "half_size": [0.3, 0.2, 0.1], "pattern": "checker"}]})");
  const sol::Box& b = std::get<sol::Box>(s.objects[0].shape);
  EXPECT_EQ(b.center, dvec3(1, 2, 0.5));
  EXPECT_EQ(b.half_size, dvec3(0.3, 0.2, 0.1));
  EXPECT_EQ(std::get<sol::Box>(sol::parse_scene(sol::to_json(s)).objects[0].shape), b);
  const std::pair<const char*, const char*> bad[] = {
      {R"({"objects": [{"type": "box", "center": [0, 0, 0]}]})", "'half_size'"},
      {R"({"objects": [{"type": "box", "half_size": [1, 1, 1]}]})", "'center'"},
      {R"({"objects": [{"type": "box", "center": [0, 0, 0], "half_size": [0.1, -0.1, 0.1]}]})", "objects[0].half_size must be finite and > 0"},
      {R"({"objects": [{"type": "box", "center": [0, 0, 0], "half_size": [0.1, 0.1, 0.1], "radius": 1}]})", "unknown key 'radius'"},
      {R"({"objects": [{"type": "box", "center": [0, 0, 100], "half_size": [0.1, 0.1, 0.1]}]})", "objects[0].center"},
      {R"({"quotient": "golden", "objects": [{"type": "box", "center": [0, 0, 0], "half_size": [0.2, 0.2, 0.2]}]})",
       "objects[0].half_size: its components must add up to at most 0.45 in the quotient"},
      {R"({"objects": [{"type": "box", "center": [0, 0, 0], "half_size": [0.1, 0.1, 0.1], "cutout": true}]})", "unknown key 'cutout'"},
  };
  for (const auto& [text, words] : bad) {
    try {
      (void)sol::parse_scene(text, "bad.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
  sol::Scene cut = s;
  cut.objects[0].cutout = true;
  EXPECT_THROW(sol::validate(cut), sol::InvalidArgument);  // cutouts are planes'
}

}  // namespace
