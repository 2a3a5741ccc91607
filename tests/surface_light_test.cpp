// Glowing boxes', bound balls' and tubes' light points (sol/surface_light.h):
// each drawn with the density per unit of Sol's area the header claims,
// checked against the area element of the sampler's own map by central
// differences in the metric (frame components e^{-z}dx, e^{z}dy, dz); on
// the surface the renderers draw (the objects' own bounds: sol::Box,
// sol::sdf_ball, sol::Tube); with the outward unit normal of that surface.
#include <array>
#include <cmath>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/surface_light.h>

namespace {

using glm::dvec3;

// The frame components at p of a coordinate displacement d.
dvec3 frame_at(const dvec3& p, const dvec3& d) { return {std::exp(-p.z) * d.x, std::exp(p.z) * d.y, d.z}; }

// A glowing box's light points (sol/surface_light.h) are uniform by Sol's area:
// on each face the map (u1, u2) -> centre · sol_box_light_point has, by
// central differences, an area element in the metric (frame components
// e^{-z}dx, e^{z}dy, dz) equal to the face's share of the total area
// times the total (so the density is 1 / area everywhere); u0 picks each
// face with that share (counted over a fine grid of u0); every point lies
// on the box's surface (its bound 0), and the normal is the face's: unit,
// orthogonal to both tangents in the metric, and outward (a step along it
// leaves the box by that step's length).
TEST(SurfaceLight, BoxPointsAreUniformByArea) {
  for (const sol::Box& box : {sol::Box{{0.3, -0.2, 0.4}, {0.25, 0.15, 0.2}}, sol::Box{{1.0, 2.0, -1.2}, {0.6, 0.1, 0.35}},
                              sol::Box{{-0.5, 0.7, 1.5}, {0.05, 0.4, 0.1}}, sol::Box{{0.0, 0.0, 0.0}, {0.15, 0.15, 0.15}}}) {
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

// A bound ball's light points: for each piece (u0 below and above 1/2) and
// a grid of (u1, u2) away from the rim, the density times the map's area
// element (by central differences) is the piece's probability 1/2; each
// point lies on the bound's zero set (sol::sdf_ball, to 1e-12), on the
// piece u0 chose; its normal is unit, orthogonal to the two tangents, the
// bound's own gradient (sol::Ball::normal, by central differences of step
// kernel::kNormalStep, to 1e-4: measured 1.3e-5 at radius 0.1) and outward
// (a step along it raises the bound by that step).
TEST(SurfaceLight, BoundBallPointsHaveTheirDensity) {
  for (const sol::Ball& ball : {sol::Ball{{0.3, -0.2, 0.4}, 0.1, false}, sol::Ball{{1.0, 2.0, -1.2}, 0.5, false},
                                sol::Ball{{-0.5, 0.7, 1.5}, 1.0, false}, sol::Ball{{0.0, 0.0, 0.0}, 2.0, false}}) {
    const double r = ball.radius;
    for (const double u0 : {0.25, 0.75}) {
      for (const double u1 : {0.05, 0.3, 0.45, 0.6, 0.9}) {
        for (const double u2 : {0.05, 0.5, 0.93}) {
          auto at = [&](double a, double b) { return sol::multiply(ball.center, sol::kernel::sol_ball_light_point(r, u0, a, b)); };
          const dvec3 w = sol::kernel::sol_ball_light_point(r, u0, u1, u2), p = at(u1, u2);
          const double e = 1e-6;
          const dvec3 t1 = frame_at(p, (at(u1 + e, u2) - at(u1 - e, u2)) / (2.0 * e));
          const dvec3 t2 = frame_at(p, (at(u1, u2 + e) - at(u1, u2 - e)) / (2.0 * e));
          const std::string where = "r " + std::to_string(r) + ", u " + std::to_string(u0) + " " +
                                    std::to_string(u1) + " " + std::to_string(u2);
          EXPECT_NEAR(sol::kernel::sol_ball_light_density(w, r) * glm::length(glm::cross(t1, t2)), 0.5, 1e-5) << where;
          EXPECT_NEAR(sol::sdf_ball(p, ball.center, r), 0.0, 1e-12) << where;
          EXPECT_EQ(sol::kernel::sol_ball_light_piece_a(w), u0 < 0.5) << where;
          const dvec3 normal = sol::kernel::sol_ball_light_normal(w);
          EXPECT_NEAR(glm::length(normal), 1.0, 1e-12) << where;
          EXPECT_NEAR(glm::dot(normal, t1), 0.0, 1e-6 * glm::length(t1)) << where;
          EXPECT_NEAR(glm::dot(normal, t2), 0.0, 1e-6 * glm::length(t2)) << where;
          EXPECT_LT(glm::length(normal - ball.normal(p)), 1e-4) << where;
          const double step = 1e-4;
          const dvec3 out = sol::multiply(p, sol::ClosedFormGeodesic<double>(normal).at(step).position);
          EXPECT_NEAR(sol::sdf_ball(out, ball.center, r), step, 1e-6) << where;
          EXPECT_NEAR(sol::kernel::sol_ball_light_bound(w, r), 0.0, 1e-12) << where;
        }
      }
    }
  }
}

// A tube's light points over a window about a foot on its axis: for each
// axis (x, y, vertical), radius and diffuse point's distance h, u0 picks
// faces with shares counted over a fine grid, and on each face the density
// times the area element of (u1, u2) -> foot · sol_tube_light_point
// (central differences in the metric) is the face's share: the density
// the header claims. Every point lies on sol::Tube's surface (its bound 0
// to 1e-12) within the window, its normal is unit, orthogonal to both
// tangents, sol::Tube's own (by differences, to 1e-4) and outward; the
// density is 0 beyond the window; the foot lies on the axis with x's
// coordinate along it.
TEST(SurfaceLight, TubePointsHaveTheirDensityOverTheirWindow) {
  const sol::Lattice axes = sol::Lattice::default_axes();
  for (const sol::TubeAxis named : {sol::TubeAxis::X, sol::TubeAxis::Y, sol::TubeAxis::Z}) {
    for (const double r : {0.05, 0.3, 1.0}) {
      const sol::Tube tube = sol::make_tube(named, {0.3, -0.4, 0.25}, r, axes);
      const int axis = named == sol::TubeAxis::X ? 0 : named == sol::TubeAxis::Y ? 1 : 2;
      const dvec3 x(1.1, 0.7, -0.6);
      const dvec3 foot = sol::kernel::sol_tube_light_foot(axis, tube.through, x);
      EXPECT_NEAR(tube.distance(foot), -r, 1e-12);
      EXPECT_NEAR(sol::multiply(sol::inverse(foot), x)[axis], 0.0, 1e-12) << "the foot has x's coordinate along the axis";
      for (const double h : {0.0, 0.4, 3.0}) {
        const std::string where = "axis " + std::to_string(axis) + ", r " + std::to_string(r) + ", h " + std::to_string(h);
        auto face_of = [&](const dvec3& w) {
          const dvec3 n = sol::kernel::sol_tube_light_normal(axis, w, r);
          return (n.x > 0.5 ? 0 : n.x < -0.5 ? 1 : n.y > 0.5 ? 2 : n.y < -0.5 ? 3 : n.z > 0.0 ? 4 : 5);
        };
        std::array<int, 6> counted{};
        const int grid = 40000;
        for (int k = 0; k < grid; ++k) ++counted[face_of(sol::kernel::sol_tube_light_point(axis, r, h, (k + 0.5) / grid, 0.3, 0.6))];
        for (int k = 0; k < grid; k += 97) {
          const double u0 = (k + 0.5) / grid;
          const double share = static_cast<double>(counted[face_of(sol::kernel::sol_tube_light_point(axis, r, h, u0, 0.5, 0.5))]) / grid;
          for (const double u1 : {0.02, 0.5, 0.97}) {
            for (const double u2 : {0.1, 0.6}) {
              auto at = [&](double a, double b) { return sol::multiply(foot, sol::kernel::sol_tube_light_point(axis, r, h, u0, a, b)); };
              const dvec3 w = sol::kernel::sol_tube_light_point(axis, r, h, u0, u1, u2), p = at(u1, u2);
              const double e = 1e-6;
              const dvec3 t1 = frame_at(p, (at(u1 + e, u2) - at(u1 - e, u2)) / (2.0 * e));
              const dvec3 t2 = frame_at(p, (at(u1, u2 + e) - at(u1, u2 - e)) / (2.0 * e));
              const double density = sol::kernel::sol_tube_light_density(axis, w, r, h);
              ASSERT_NEAR(density * glm::length(glm::cross(t1, t2)), share, 2e-3 + 1e-5 * share) << where << " u0 " << u0;
              EXPECT_NEAR(tube.distance(p), 0.0, 1e-12) << where;
              EXPECT_NEAR(sol::kernel::sol_tube_light_bound(axis, w, r), 0.0, 1e-12) << where;
              const dvec3 normal = sol::kernel::sol_tube_light_normal(axis, w, r);
              EXPECT_NEAR(glm::length(normal), 1.0, 1e-12) << where;
              EXPECT_NEAR(glm::dot(normal, t1), 0.0, 1e-6 * glm::length(t1)) << where;
              EXPECT_NEAR(glm::dot(normal, t2), 0.0, 1e-6 * glm::length(t2)) << where;
              EXPECT_LT(glm::length(normal - tube.normal(p)), 1e-4) << where;
              const double step = 1e-4;
              EXPECT_NEAR(tube.distance(sol::multiply(p, sol::ClosedFormGeodesic<double>(normal).at(step).position)), step, 1e-6) << where;
            }
          }
        }
        // Beyond the window along the axis: density 0.
        dvec3 beyond = sol::kernel::sol_tube_light_point(axis, r, h, 0.9, 0.5, 0.5);
        beyond[axis] = 1.01 * sol::kernel::sol_light_window(h);
        EXPECT_EQ(sol::kernel::sol_tube_light_density(axis, beyond, r, h), 0.0) << where;
      }
    }
  }
}

// A tube's light point at the ends of u1's range (0, and the largest
// double below 1) stays in its window, where its density is positive: t =
// a tan(θ) with θ = ±atan(W / a) rounds above W for about one distance h in
// six, and a point there has density 0, by which the renderers' next-event
// estimation divided (a NaN pixel on the kernel, whose float rounds so for
// a u1 within about 1e-7 of its ends: one pixel in 3072 at 768 paths).
TEST(SurfaceLight, TubePointsAtTheEndsOfTheirRangeStayInTheirWindow) {
  const double below_one = std::nextafter(1.0, 0.0);
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 1; i <= 400; ++i) {
      const double h = 0.003 * i, radius = 0.04;
      for (const double u1 : {0.0, below_one}) {
        const dvec3 w = sol::kernel::sol_tube_light_point(axis, radius, h, 0.6, u1, 0.3);
        EXPECT_LE(std::abs(sol::kernel::sol_tube_light_along(axis, w)), sol::kernel::sol_light_window(h)) << axis << " " << h;
        EXPECT_GT(sol::kernel::sol_tube_light_density(axis, w, radius, h), 0.0) << axis << " " << h << " " << u1;
      }
    }
  }
}

TEST(SurfaceLight, TheWindowGrowsWithTheDistanceUpToItsMost) {
  EXPECT_DOUBLE_EQ(sol::kernel::sol_light_window(0.0), sol::kernel::kLightWindowBase);
  EXPECT_DOUBLE_EQ(sol::kernel::sol_light_window(0.5), sol::kernel::kLightWindowBase + 0.5 * sol::kernel::kLightWindowSlope);
  EXPECT_DOUBLE_EQ(sol::kernel::sol_light_window(100.0), sol::kernel::kLightWindowMost);
}

// Tubes along a coordinate axis are targets (their axis as the sampler's
// frames number them: 0 x, 1 y, 2 vertical); along a lattice's direction
// (both horizontal components) none.
TEST(SurfaceLight, OnlyTubesAlongACoordinateAxisAreTargets) {
  EXPECT_EQ(sol::kernel::sol_tube_light_axis(true, 0.0, 0.0), 2);
  EXPECT_EQ(sol::kernel::sol_tube_light_axis(false, -1.0, 0.0), 0);
  EXPECT_EQ(sol::kernel::sol_tube_light_axis(false, 0.0, 1.0), 1);
  EXPECT_EQ(sol::kernel::sol_tube_light_axis(false, 0.6, 0.8), -1);
}

}  // namespace
