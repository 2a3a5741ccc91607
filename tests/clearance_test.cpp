// sol/clearance.hpp: the second-order steps of the quotient march. Each
// bound is the maximum of its terms; each term's rate is its derivative
// along the geodesic and its bend bounds its second derivative from below,
// checked by differences along geodesics of the independent integrator
// (tests/support/reference_geodesic.hpp, Bulirsch–Stoer in double here);
// and a clearance never reaches the object: the geodesic, walked by the
// bound itself (sphere tracing, which never passes a surface), comes no
// nearer than the hit tolerance before the clearance's end.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/reference_geodesic.hpp"

namespace {

using glm::dvec3;
using Terms = std::vector<sol::BoundTerm>;
using Reference = sol::test::ReferenceGeodesic<double>;

// An object's bound as sol/distance.hpp writes it, and the clearance's terms.
struct Solid {
  std::string name;
  dvec3 near;  // a point of the object: samples are drawn around it
  std::function<double(const dvec3&)> bound;
  std::function<Terms(const dvec3&, const dvec3&)> terms;
};

template <std::size_t N>
Terms as_terms(const std::array<sol::BoundTerm, N>& terms) {
  return Terms(terms.begin(), terms.end());
}

// sol::clearance of the terms (whatever their number).
double clearance_of(const Terms& terms) {
  switch (terms.size()) {
    case 2:
      return sol::clearance(std::array<sol::BoundTerm, 2>{terms[0], terms[1]});
    case 3:
      return sol::clearance(std::array<sol::BoundTerm, 3>{terms[0], terms[1], terms[2]});
  }
  ADD_FAILURE() << terms.size() << " terms";
  return 0.0;
}

std::vector<Solid> solids() {
  std::vector<Solid> out;
  for (const auto& ball : {std::pair{dvec3(0.3, -0.2, 0.4), 0.25}, std::pair{dvec3(1.0, 2.0, -1.0), 0.6},
                           std::pair{dvec3(-0.5, 0.7, 1.5), 0.05}}) {
    const dvec3 centre = ball.first;  // (a lambda may not capture a structured binding before clang 16)
    const double r = ball.second;
    out.push_back({"ball r " + std::to_string(r), centre, [=](const dvec3& p) { return sol::sdf_ball(p, centre, r); },
                   [=](const dvec3& p, const dvec3& u) { return as_terms(sol::ball_terms(p, u, centre, r)); }});
  }
  const dvec3 through(0.2, 0.1, 0.3);
  out.push_back({"vertical tube", through, [=](const dvec3& p) { return sol::sdf_tube(p, through, 2, 0.06); },
                 [=](const dvec3& p, const dvec3& u) { return as_terms(sol::tube_terms(p, u, through, true, {0, 0}, 0.06)); }});
  const double phi = sol::kernel::kPhi;
  for (const auto& tube : {std::pair{"tube along x", glm::dvec2(1, 0)}, std::pair{"tube along y", glm::dvec2(0, -1)},
                           std::pair{"tube along gamma1", glm::normalize(glm::dvec2(phi, -1))},
                           std::pair{"tube along gamma2", glm::normalize(glm::dvec2(1, phi))}}) {
    const char* name = tube.first;
    const glm::dvec2 h = tube.second;
    for (const double r : {0.06, 0.3}) {
      out.push_back({std::string(name) + " r " + std::to_string(r), through,
                     [=](const dvec3& p) { return sol::sdf_tube_horizontal(p, through, h, r); },
                     [=](const dvec3& p, const dvec3& u) { return as_terms(sol::tube_terms(p, u, through, false, h, r)); }});
    }
  }
  // Boxes: three slabs' terms (sol::Box::clearance_terms), their maximum the
  // bound sol::Box::distance, checked against sol::distance in box_test.cpp.
  for (const sol::Box& box : {sol::Box{through, {0.25, 0.15, 0.2}}, sol::Box{dvec3(1.0, 2.0, -1.2), {0.6, 0.1, 0.35}},
                              sol::Box{dvec3(-0.5, 0.7, 1.5), {0.05, 0.4, 0.1}}}) {
    out.push_back({"box at z " + std::to_string(box.center.z), box.center, [=](const dvec3& p) { return box.distance(p); },
                   [=](const dvec3& p, const dvec3& u) { return as_terms(box.clearance_terms(p, u)); }});
  }
  // Planes: one term each (the second a copy, so the maximum is the same).
  out.push_back({"plane z", through, [=](const dvec3& p) { return sol::sdf_plane_z(p, through.z); },
                 [=](const dvec3& p, const dvec3& u) {
                   const sol::BoundTerm h = sol::plane_z_term(p, u, through.z);
                   return Terms{h, h};
                 }});
  out.push_back({"plane x", through, [=](const dvec3& p) { return sol::sdf_plane_x(p, through.x); },
                 [=](const dvec3& p, const dvec3& u) {
                   const sol::BoundTerm h = sol::slab_x_term(p, u, through.x, 0.0);
                   return Terms{h, h};
                 }});
  out.push_back({"plane y", through, [=](const dvec3& p) { return sol::sdf_plane_y(p, through.y); },
                 [=](const dvec3& p, const dvec3& u) {
                   const sol::BoundTerm h = sol::slab_y_term(p, u, through.y, 0.0);
                   return Terms{h, h};
                 }});
  return out;
}

dvec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(dvec3(n(rng), n(rng), n(rng)));
}

// A point near the object: its reference point moved by up to `spread` in
// each coordinate, in frame lengths at that height.
dvec3 random_point(std::mt19937_64& rng, const dvec3& near, double spread) {
  std::uniform_real_distribution<double> o(-spread, spread);
  const double ez = std::exp(near.z);
  return near + dvec3(o(rng) * ez, o(rng) / ez, o(rng));
}

TEST(Clearance, RootIsTheParabolasFirstRoot) {
  for (const double h : {1e-9, 1e-4, 0.1, 0.3}) {
    for (const double slope : {-1.0, -0.3, -1e-5, 0.0, 1e-5, 0.4, 1.0}) {
      for (const double bend : {1.0, 4.5}) {
        const double s = sol::clearance_root({h, slope, bend});
        // The root of the quadratic, from the textbook formula in long double.
        const long double disc = static_cast<long double>(slope) * slope + 2.0L * bend * h;
        const long double expected = (slope + std::sqrt(disc)) / bend;
        EXPECT_NEAR(s, static_cast<double>(expected), 1e-12 * std::max(1.0, s)) << h << " " << slope << " " << bend;
        EXPECT_GT(s, 0.0);
        EXPECT_NEAR(h + slope * s - 0.5 * bend * s * s, 0.0, 1e-12);
      }
    }
  }
  EXPECT_EQ(sol::clearance_root({0.0, 1.0, 1.0}), 0.0);   // on the surface: no second-order step
  EXPECT_EQ(sol::clearance_root({-0.1, 1.0, 1.0}), 0.0);  // inside
}

TEST(Clearance, TermsAreTheBoundWithTheirRatesAndBends) {
  std::mt19937_64 rng(20261126);
  constexpr double kDelta = 1e-4;  // differences: O(δ²) truncation, 1e-16/δ² rounding in the second
  for (const Solid& solid : solids()) {
    double worst_value = 0.0, worst_rate = 0.0, least_bent = 1e30;
    int checked = 0;
    for (int n = 0; n < 400; ++n) {
      const dvec3 p = random_point(rng, solid.near, 0.8), u = random_unit(rng);
      const Terms terms = solid.terms(p, u);
      double largest = terms[0].value;
      for (const sol::BoundTerm& h : terms) largest = std::max(largest, h.value);
      worst_value = std::max(worst_value, std::abs(largest - solid.bound(p)));
      // The terms at ±δ and ±2δ along the reference geodesic through p.
      Reference geodesic(p, u, false, 1e-13);
      std::array<Terms, 5> at;
      for (int k = -2; k <= 2; ++k) at[k + 2] = solid.terms(geodesic.at(k * kDelta).position, u);
      for (std::size_t i = 0; i < terms.size(); ++i) {
        const double m2 = at[0][i].value, m1 = at[1][i].value, c = at[2][i].value, p1 = at[3][i].value,
                     p2 = at[4][i].value;
        // Skip a kink of |.| within the stencil (the two one-sided rates disagree).
        if (std::abs((p1 - c) - (c - m1)) > 1e-3 * kDelta || std::abs((p2 - p1) - (m1 - m2)) > 1e-2 * kDelta) continue;
        if (!(c > 0.0)) continue;  // outside the term's set: where the march steps by it
        ++checked;
        const double rate = (8.0 * (p1 - m1) - (p2 - m2)) / (12.0 * kDelta);  // fourth order
        worst_rate = std::max(worst_rate, std::abs(rate - terms[i].slope));
        {
          const double second = (p1 - 2.0 * c + m1) / (kDelta * kDelta);
          least_bent = std::min(least_bent, second / terms[i].bend);
          EXPECT_GE(second, -terms[i].bend - 1e-5) << solid.name << " term " << i << " at sample " << n;
        }
      }
    }
    std::printf("%s: %d terms checked; value within %.1e of the bound, rate within %.1e, least h''/M %.3f\n",
                solid.name.c_str(), checked, worst_value, worst_rate, least_bent);
    EXPECT_GT(checked, 300) << solid.name;
    EXPECT_LT(worst_value, 1e-12) << solid.name;
    EXPECT_LT(worst_rate, 1e-8) << solid.name;  // the difference's δ⁴ h⁽⁵⁾/30 and rounding 1e-16/δ
  }
}

// The across term of slanted tubes bends by at most 1, far from the tube
// too (|G| up to 1e3, heights where either exponential dominates): its
// second difference along reference geodesics never falls below -1 (the
// proof: scripts/prove_across_bend.py, docs/renderer.md). And 1 is tight:
// along a vertical geodesic at the height where |h_x| e^{-z} = |h_y| e^{z},
// (asinh G)'' = -G/sqrt(1 + G^2) exactly, -0.995 at G = 10.
TEST(Clearance, AcrossTermBendsByOne) {
  constexpr double kDelta = 1e-3;  // second differences: O(δ²) truncation, 1e-16/δ² rounding
  const double phi = sol::kernel::kPhi;
  const dvec3 through(0.2, 0.1, 0.3);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double least = 1e30;
  int checked = 0;
  for (const glm::dvec2 h : {glm::normalize(glm::dvec2(phi, -1)), glm::normalize(glm::dvec2(1, phi)),
                             glm::normalize(glm::dvec2(-0.3, -2.0))}) {
    for (int n = 0; n < 300; ++n) {
      // A point at |G| = g (log-uniform in [1e-2, 1e3]) on either side, at a height in [-3, 3].
      const double g = std::pow(10.0, -2.0 + 5.0 * unit(rng)), z = -3.0 + 6.0 * unit(rng);
      const double D = std::abs(h.x) * std::exp(-z) + std::abs(h.y) * std::exp(z);
      const double side = unit(rng) < 0.5 ? -1.0 : 1.0, along = 4.0 * unit(rng) - 2.0;
      const dvec3 p =
          through + dvec3(side * g * D * h.y + along * h.x, -side * g * D * h.x + along * h.y, z - through.z);
      const dvec3 u = random_unit(rng);
      const sol::BoundTerm term = sol::tube_terms(p, u, through, false, h, 0.06)[0];
      ASSERT_NEAR(term.value, std::asinh(g) - 0.06, 1e-9 * std::max(1.0, g));
      EXPECT_EQ(term.bend, 1.0);
      Reference geodesic(p, u, false, 1e-13);
      double v[3];
      for (int k = -1; k <= 1; ++k) {
        v[k + 1] = sol::tube_terms(geodesic.at(k * kDelta).position, u, through, false, h, 0.06)[0].value;
      }
      const double second = (v[2] - 2.0 * v[1] + v[0]) / (kDelta * kDelta);
      least = std::min(least, second);
      EXPECT_GE(second, -1.0 - 1e-4) << "h = (" << h.x << ", " << h.y << "), G = " << g << ", z = " << z;
      ++checked;
    }
  }
  std::printf("across term: %d points with |G| in [1e-2, 1e3]: least h'' %.4f\n", checked, least);
  // Tight: a vertical geodesic at the balance height, G = 10 there.
  const glm::dvec2 h = glm::normalize(glm::dvec2(phi, -1));
  const double z0 = 0.5 * std::log(std::abs(h.x) / std::abs(h.y)), g = 10.0;
  const double D = std::abs(h.x) * std::exp(-z0) + std::abs(h.y) * std::exp(z0);
  const dvec3 p = through + dvec3(g * D * h.y, -g * D * h.x, z0 - through.z);
  Reference geodesic(p, dvec3(0.0, 0.0, 1.0), false, 1e-13);
  double v[3];
  for (int k = -1; k <= 1; ++k) {
    v[k + 1] = sol::tube_terms(geodesic.at(k * kDelta).position, {0, 0, 1}, through, false, h, 0.06)[0].value;
  }
  const double second = (v[2] - 2.0 * v[1] + v[0]) / (kDelta * kDelta);
  EXPECT_NEAR(second, -g / std::sqrt(1.0 + g * g), 1e-5);
  EXPECT_LT(second, -0.99);
}

// The first arc length at which the geodesic from p along u comes within
// `tolerance` of the object, walked by the bound (at least `floor` a step),
// up to `limit`; +infinity if it does not.
double first_contact(const std::function<double(const dvec3&)>& bound, const dvec3& p, const dvec3& u, double limit,
                     double tolerance, double floor) {
  Reference geodesic(p, u, false, 1e-13);
  for (double s = 0.0; s <= limit;) {
    const double b = bound(geodesic.at(s).position);
    if (b < tolerance) return s;
    s += std::max(b, floor);
  }
  return std::numeric_limits<double>::infinity();
}

TEST(Clearance, NeverReachesTheObjectAndOutrunsTheBoundBesideIt) {
  std::mt19937_64 rng(7);
  for (const Solid& solid : solids()) {
    int samples = 0, longer = 0, reached = 0;
    double tightest = 0.0;  // the largest clearance / first contact where the geodesic reaches the object
    for (int n = 0; n < 5000 && samples < 150; ++n) {
      const dvec3 p = random_point(rng, solid.near, 0.6);
      const double b = solid.bound(p);
      if (!(b > 1e-6 && b < 0.3)) continue;  // outside, near: where the march uses clearances
      // Half the directions graze: across the bound's gradient (by differences).
      dvec3 u = random_unit(rng);
      if (n % 2 == 0) {
        const double h = 1e-6, ez = std::exp(p.z);
        const dvec3 g((solid.bound(p + dvec3(h * ez, 0, 0)) - b) / h, (solid.bound(p + dvec3(0, h / ez, 0)) - b) / h,
                      (solid.bound(p + dvec3(0, 0, h)) - b) / h);
        if (glm::length(g) > 0.0) u = glm::normalize(u - glm::dot(u, g) / glm::dot(g, g) * g);
      }
      const double clear = clearance_of(solid.terms(p, u));
      ASSERT_GE(clear, b - 1e-15) << solid.name;
      ++samples;
      longer += clear > 2.0 * b;
      // The sphere-traced walk stops within 1e-7 of the surface (its floor
      // step 1e-8 passes at most that far into a thin wedge).
      const double contact = first_contact(solid.bound, p, u, clear + 0.05, 1e-7, 1e-8);
      if (std::isfinite(contact)) {
        ++reached;
        tightest = std::max(tightest, clear / contact);
      }
      EXPECT_GE(contact, clear - 1e-6) << solid.name << ": sample " << n << " bound " << b << " clearance " << clear;
    }
    std::printf("%s: %d samples, clearance above twice the bound at %d; %d reach the object within it + 0.05, "
                "clearance up to %.3f of the way there\n",
                solid.name.c_str(), samples, longer, reached, tightest);
    EXPECT_EQ(samples, 150) << solid.name;
    EXPECT_GT(longer, samples / 4) << solid.name;  // beside the surface it steps much farther than the bound
  }
}

// The march's step where a plane z = c is the nearest object
// (sol::plane_z_step): the geodesic stays more than hit_epsilon from the
// plane up to it, so the hit is taken where the ray first comes within
// hit_epsilon, as by steps of |z - c|; and for a ray leaving the plane
// almost level (a path's next segment or connection from a floor) it is
// far longer than |z - c|, by which such a ray crawled. Checked along the
// independent reference geodesic, sampled densely up to the step (z is
// smooth: a sample within 1e-4 of arc length of the closest approach
// misses it by at most |z''| 1e-8 / 2 <= 1e-8 below the band).
TEST(Clearance, PlaneStepStaysOutOfTheHitBandAndOutrunsTheDistanceOnLeaving) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double eps = 5e-5, c = 0.3;
  int leaving = 0, outrun = 0;
  for (int n = 0; n < 400; ++n) {
    const double h = n % 4 == 0 ? eps * unit(rng) : eps + 0.3 * std::pow(unit(rng), 3.0);
    const double side = n % 2 == 0 ? 1.0 : -1.0;
    const dvec3 p(2.0 * unit(rng) - 1.0, 2.0 * unit(rng) - 1.0, c + side * h);
    dvec3 u = random_unit(rng);
    if (n % 3 != 0) {  // two thirds graze: |u_z| below 0.02, either way
      const double uz = 0.02 * (2.0 * unit(rng) - 1.0), k = std::sqrt((1.0 - uz * uz) / (u.x * u.x + u.y * u.y));
      u = dvec3(u.x * k, u.y * k, uz);
    }
    const double step = sol::plane_z_step(p, u, c, eps);
    if (h <= eps) {
      EXPECT_EQ(step, 0.0) << "within the band: sample " << n;
      continue;
    }
    Reference geodesic(p, u, false, 1e-13);
    double closest = h;
    for (double t = 0.0; t <= step; t += std::min(1e-4, step / 64.0)) {
      closest = std::min(closest, std::abs(geodesic.at(t).position.z - c));
    }
    closest = std::min(closest, std::abs(geodesic.at(step).position.z - c));
    EXPECT_GE(closest, eps - 1e-8) << "sample " << n << ": height " << h << ", u_z " << u.z << ", step " << step;
    if (side * u.z > 0.0 && side * u.z < 0.02 && h > 2.0 * eps && h < 0.01) {  // (then the step >= √h)
      ++leaving;
      outrun += step > 10.0 * h;
    }
  }
  std::printf("plane steps: %d leave almost level near the plane, %d step more than 10 |z - c|\n", leaving, outrun);
  EXPECT_GT(leaving, 20);
  EXPECT_EQ(outrun, leaving);
}

// The kernel's exact balls step by the convexity of the distance from the
// centre (march/exact_balls.glsl, exact_ball_clearance): Sol's sectional curvatures are
// at most 1, so by the Hessian comparison theorem d'' >= cot(d) |u⊥|² >=
// min(0, cot d) along any geodesic, where d is below the cut time (at
// least √2 π). Checked with the exact distance (sol::distance) by second
// differences along the reference geodesic, at distances 0.05 to 3 from
// random centres, in random directions (measured: d'' no lower than 0.26 of
// cot d beyond π/2, and positive within it).
TEST(Clearance, DistanceFromAPointBendsNoMoreThanCurvatureOneAllows) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-1.5, 1.5), radius(0.05, 3.0);
  constexpr double kDelta = 1e-3;  // sol::distance to ~1e-15: second differences to ~1e-9
  double tightest = 0.0, least_convex = 1e30;
  int beyond = 0;
  for (int n = 0; n < 400; ++n) {
    const dvec3 centre(coord(rng), coord(rng), coord(rng));
    const dvec3 p = sol::flow({centre, random_unit(rng)}, radius(rng)).position;
    const double d = sol::distance(centre, p);
    if (!(d < 3.0)) continue;  // a flow past its cut time: farther than it went
    const dvec3 u = random_unit(rng);
    Reference geodesic(p, u, false, 1e-14);
    const double before = sol::distance(centre, geodesic.at(-kDelta).position);
    const double after = sol::distance(centre, geodesic.at(kDelta).position);
    const double second = (after - 2.0 * d + before) / (kDelta * kDelta);
    const double floor = std::min(0.0, std::cos(d) / std::sin(d));
    EXPECT_GE(second, floor - 1e-5) << "d = " << d << " at sample " << n;
    if (floor < 0.0) {
      ++beyond;
      tightest = std::max(tightest, second / floor);
    } else {
      least_convex = std::min(least_convex, second);
    }
  }
  std::printf("distance from a point: least d'' within π/2 %.3e; beyond it (%d samples) d'' reaches %.3f of cot d\n",
              least_convex, beyond, tightest);
  EXPECT_GT(beyond, 50);
  EXPECT_GE(least_convex, -1e-5);
}

// sol::shape_clearances gives, from one evaluation of a shape's terms, its
// clearance ahead along u and back along -u (the over-relaxed quotient
// march's check): each the clearance along that tangent evaluated on its
// own (sol::shape_clearance with u and with -u), to the bit, since a term's
// rate is linear in the tangent (negating it negates every product of its
// sum exactly) and its value and bend do not depend on it.
TEST(Clearance, BothWaysAreTheClearancesAlongTheTangentAndItsReverse) {
  std::mt19937_64 rng(11);
  const dvec3 through(0.2, 0.1, 0.3);
  const std::vector<std::pair<std::string, sol::Shape>> shapes = {
      {"plane x", sol::PlaneX{0.4}},
      {"plane y", sol::PlaneY{-0.3}},
      {"plane z", sol::PlaneZ{0.2}},
      {"ball", sol::Ball{through, 0.25}},
      {"vertical tube", sol::make_tube(sol::TubeAxis::Z, through, 0.06, sol::Lattice::golden())},
      {"tube along gamma1", sol::make_tube(sol::TubeAxis::Gamma1, through, 0.06, sol::Lattice::golden())},
      {"tube along x", sol::make_tube(sol::TubeAxis::X, through, 0.3, sol::Lattice::golden())},
      {"box", sol::Box{through, {0.25, 0.15, 0.2}}},
  };
  for (const auto& [name, shape] : shapes) {
    int differ = 0;  // back and ahead differ: the test sees two directions
    for (int n = 0; n < 500; ++n) {
      const dvec3 p = random_point(rng, through, 0.8), u = random_unit(rng);
      const sol::Clearances both = sol::shape_clearances(shape, p, u);
      ASSERT_EQ(both.ahead, sol::shape_clearance(shape, p, u)) << name << " sample " << n;
      ASSERT_EQ(both.back, sol::shape_clearance(shape, p, -u)) << name << " sample " << n;
      differ += both.ahead != both.back ? 1 : 0;
    }
    EXPECT_GT(differ, 100) << name;
  }
}

}  // namespace

namespace {

// The solids seen from inside (sol::shape_inside_clearances): boxes, balls
// drawn by their bound, vertical and horizontal tubes; each with a point
// inside it, about which samples are drawn.
struct InsideSolid {
  std::string name;
  sol::Shape shape;
  dvec3 centre;
};

std::vector<InsideSolid> inside_solids() {
  const dvec3 through(0.2, 0.1, 0.3);
  return {{"box", sol::Box{through, {0.25, 0.15, 0.2}}, through},
          {"flat box", sol::Box{dvec3(1.0, 2.0, -1.2), {0.6, 0.1, 0.35}}, dvec3(1.0, 2.0, -1.2)},
          {"ball", sol::Ball{dvec3(0.3, -0.2, 0.4), 0.5, false}, dvec3(0.3, -0.2, 0.4)},
          {"large ball", sol::Ball{dvec3(1.0, 2.0, -1.0), 1.5, false}, dvec3(1.0, 2.0, -1.0)},
          {"vertical tube", sol::make_tube(sol::TubeAxis::Z, through, 0.3, sol::Lattice::golden()), through},
          {"tube along x", sol::make_tube(sol::TubeAxis::X, through, 0.3, sol::Lattice::golden()), through},
          {"tube along gamma1", sol::make_tube(sol::TubeAxis::Gamma1, through, 0.3, sol::Lattice::golden()), through}};
}

}  // namespace

// Seen from inside a solid, a clearance never leaves it: from random points
// inside each solid, along random directions, the geodesic (the
// independent integrator) stays inside (the bound at most 1e-9) for the
// whole of the inside clearance sol::shape_inside_clearances gives ahead,
// and, walked back along −u, for the clearance back. And the clearances
// are worth having: their mean over the samples is above the mean bound
// (|d|) by the factor printed (the chord against the distance to the
// nearest wall).
TEST(Clearance, InsideClearancesNeverLeaveTheSolid) {
  std::mt19937_64 rng(5);
  for (const auto& [name, shape, centre] : inside_solids()) {
    int samples = 0, worse = 0;
    double sum_clearance = 0.0, sum_bound = 0.0;
    for (int n = 0; n < 40000 && samples < 300; ++n) {
      const dvec3 p = random_point(rng, centre, 0.8);
      const double d = sol::shape_distance(shape, p);
      if (!(d < 0.0)) continue;
      ++samples;
      const dvec3 u = random_unit(rng);
      const sol::InsideClearances both = sol::shape_inside_clearances(shape, p, u);
      EXPECT_GE(both.ahead, -d * (1.0 - 1e-12)) << name << " sample " << n;
      sum_clearance += both.ahead;
      sum_bound += -d;
      for (const double way : {1.0, -1.0}) {
        const double s = way > 0.0 ? both.ahead : both.back;
        Reference geodesic(p, way * u, false, 1e-13);
        double most = -1e30;
        for (int k = 1; k <= 64; ++k) most = std::max(most, sol::shape_distance(shape, geodesic.at(s * k / 64.0).position));
        if (most > 1e-9) {
          ++worse;
          ADD_FAILURE() << name << " sample " << n << (way > 0.0 ? " ahead" : " back") << ": the geodesic leaves the solid "
                        << "within the clearance " << s << " (the bound reaches " << most << "; at p " << d << ")";
        }
      }
      if (worse > 5) break;
    }
    std::printf("inside a %s: %d samples, the clearance ahead %.2f times the bound on the mean\n", name.c_str(), samples,
                sum_clearance / sum_bound);
    EXPECT_GE(samples, 150) << name;
  }
}
