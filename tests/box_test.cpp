// Boxes (sol::Box): center · ([-a, a] x [-b, b] x [-c, c]). Their bound is
// held to the exact Sol distance (sol::distance, tested against 50-digit
// references): a lower bound everywhere, equal to the distance to the
// nearest face near the faces (where the perpendicular's foot lies on the
// face); their coordinate box is the left translate's; the CPU renderer's
// hits lie on the faces, in Sol and in the quotient; scene-file keys; a
// glowing box's light points (sol/box_light.h) are uniform by area.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/box_light.h>

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

// A glowing box's light points (sol/box_light.h) are uniform by Sol's area:
// on each face the map (u1, u2) -> centre · sol_box_light_point has, by
// central differences, an area element in the metric (frame components
// e^{-z}dx, e^{z}dy, dz) equal to the face's share of the total area
// times the total (so the density is 1 / area everywhere); u0 picks each
// face with that share (counted over a fine grid of u0); every point lies
// on the box's surface (its bound 0), and the normal is the face's: unit,
// orthogonal to both tangents in the metric, and outward (a step along it
// leaves the box by that step's length).
TEST(Box, LightPointsAreUniformByArea) {
  for (const sol::Box& box : boxes()) {
    const dvec3 h = box.half_size;
    const double area = sol::kernel::sol_box_light_area(h);
    // The faces' areas from the metric, integrated numerically (midpoint rule in z).
    double side_x = 0.0, side_y = 0.0;
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
      const double z = -h.z + (k + 0.5) * 2.0 * h.z / n;
      side_x += 2.0 * h.y * std::exp(z) * 2.0 * h.z / n;   // x = ±a: e^{z} dy dz
      side_y += 2.0 * h.x * std::exp(-z) * 2.0 * h.z / n;  // y = ±b: e^{-z} dx dz
    }
    const double top = 4.0 * h.x * h.y;
    EXPECT_NEAR(area, 2.0 * (top + side_x + side_y), 1e-6 * area);
    // The faces u0 picks, in their order (z = +c, -c, x = +a, -a, y = +b, -b).
    const std::array<double, 6> face_area = {top, top, side_x, side_x, side_y, side_y};
    std::array<int, 6> counted{};
    auto face_of = [&](const dvec3& w) {
      const dvec3 v = sol::kernel::sol_box_light_normal(w, h);
      return v.z > 0.5 ? 0 : v.z < -0.5 ? 1 : v.x > 0.5 ? 2 : v.x < -0.5 ? 3 : v.y > 0.5 ? 4 : 5;
    };
    const int grid = 100000;
    for (int k = 0; k < grid; ++k) ++counted[face_of(sol::kernel::sol_box_light_point(h, (k + 0.5) / grid, 0.3, 0.6))];
    double before = 0.0;
    for (int f = 0; f < 6; ++f) {
      EXPECT_NEAR(counted[f], grid * face_area[f] / area, 2.0) << "face " << f;
      // The area element on face f, at a few (u1, u2).
      const double u0 = (before + 0.5 * face_area[f]) / area;
      before += face_area[f];
      for (const double u1 : {0.1, 0.5, 0.93}) {
        for (const double u2 : {0.05, 0.4, 0.8}) {
          auto at = [&](double a, double b) { return sol::multiply(box.center, sol::kernel::sol_box_light_point(h, u0, a, b)); };
          const dvec3 p = at(u1, u2);
          const double e = 1e-6;
          auto frame = [&](const dvec3& d) { return dvec3(std::exp(-p.z) * d.x, std::exp(p.z) * d.y, d.z); };
          const dvec3 t1 = frame((at(u1 + e, u2) - at(u1 - e, u2)) / (2.0 * e));
          const dvec3 t2 = frame((at(u1, u2 + e) - at(u1, u2 - e)) / (2.0 * e));
          EXPECT_NEAR(glm::length(glm::cross(t1, t2)), face_area[f], 1e-6 * area) << "face " << f;
          EXPECT_NEAR(box.distance(p), 0.0, 1e-12) << "face " << f;
          const dvec3 w = sol::kernel::sol_box_light_point(h, u0, u1, u2);
          const dvec3 normal = sol::kernel::sol_box_light_normal(w, h);
          EXPECT_EQ(face_of(w), f);
          EXPECT_DOUBLE_EQ(glm::length(normal), 1.0);
          EXPECT_NEAR(glm::dot(normal, t1), 0.0, 1e-6 * glm::length(t1));
          EXPECT_NEAR(glm::dot(normal, t2), 0.0, 1e-6 * glm::length(t2));
          const double step = 1e-4;
          EXPECT_NEAR(box.distance(sol::multiply(p, sol::ClosedFormGeodesic<double>(normal).at(step).position)), step, 1e-6) << "face " << f;
        }
      }
    }
  }
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
