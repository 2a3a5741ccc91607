// Geodesic flow: first integrals, an independent 50-digit reference,
// left-invariance, the dihedral symmetries, reversibility and exact cases.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"
#include "support/sweep.hpp"

namespace {

using glm::dvec3;
using sol::test::scaled_error;

sol::FlowOptions rk4(double step) {
  sol::FlowOptions o;
  o.method = sol::Method::RK4;
  o.rk4_step = step;
  return o;
}

sol::FlowOptions dopri(double tolerance) {
  sol::FlowOptions o;
  o.method = sol::Method::DormandPrince;
  o.tolerance = tolerance;
  return o;
}

// The first integrals of docs/mathematics.md for a geodesic from the origin with
// unit direction d = (a,b,c): e^{-z}u1 = a, e^{z}u2 = b, |u| = 1, u3 + a x - b y = c.
struct IntegralDrift {
  double i1, i2, norm, i3;
};

IntegralDrift drift(const dvec3& d, const sol::GeodesicState& s) {
  const dvec3 p = s.position, u = s.direction;
  // I3 combines terms of size |a x| and |b y|; scale its drift by them.
  const double scale3 = 1.0 + std::abs(d.x * p.x) + std::abs(d.y * p.y);
  return {std::abs(std::exp(-p.z) * u.x - d.x), std::abs(std::exp(p.z) * u.y - d.y),
          std::abs(glm::length(u) - 1.0), std::abs(u.z + d.x * p.x - d.y * p.y - d.z) / scale3};
}

TEST(Geodesic, FirstIntegralsConservedOverArcLength50) {
  // 1000 random directions and every stiff one, Dormand–Prince at its default tolerance.
  std::vector<dvec3> dirs = sol::test::random_directions(1000, 7);
  for (const dvec3& d : sol::test::stiff_directions()) dirs.push_back(d);
  IntegralDrift worst{0, 0, 0, 0};
  for (const dvec3& d : dirs) {
    for (double t : {10.0, -50.0, 50.0}) {
      const IntegralDrift e = drift(d, sol::flow({dvec3(0.0), d}, t, sol::Method::DormandPrince));
      worst = {std::max(worst.i1, e.i1), std::max(worst.i2, e.i2), std::max(worst.norm, e.norm),
               std::max(worst.i3, e.i3)};
    }
  }
  std::printf("worst drift over t<=50: e^{-z}u1 %.2e, e^{z}u2 %.2e, |u| %.2e, I3 (scaled) %.2e\n", worst.i1,
              worst.i2, worst.norm, worst.i3);
  // Stated bound: the default tolerance 1e-12 keeps every first integral within 1e-9.
  EXPECT_LT(worst.i1, 1e-9);
  EXPECT_LT(worst.i2, 1e-9);
  EXPECT_LT(worst.norm, 1e-9);
  EXPECT_LT(worst.i3, 1e-9);
}

// RK4 and Dormand–Prince against the 50-digit coordinate-form reference.
TEST(Geodesic, MatchesHighPrecisionReference) {
  std::vector<dvec3> dirs = sol::test::random_directions(6, 99);
  const std::vector<dvec3> stiff = sol::test::stiff_directions();
  for (std::size_t i = 0; i < stiff.size(); i += 3) dirs.push_back(stiff[i]);
  double worst_dp = 0, worst_rk4 = 0, worst_rk4_mid = 0, worst_rk4_coarse = 0;
  dvec3 worst_dir(0.0);
  for (const dvec3& d : sol::test::sweep(dirs, 3)) {
    sol::test::ReferenceGeodesic<> reference(d);
    for (double t : {1.0, 10.0, 50.0}) {
      const sol::test::ReferencePoint r = reference.at(t);
      const sol::GeodesicState start{dvec3(0.0), d};
      const double e_dp = std::max(scaled_error(sol::flow(start, t, dopri(1e-12)).position, r.position),
                                   scaled_error(sol::flow(start, t, dopri(1e-12)).direction, r.direction));
      const double e_rk4 = scaled_error(sol::flow(start, t, rk4(1e-3)).position, r.position);
      const double e_mid = scaled_error(sol::flow(start, t, rk4(1e-2)).position, r.position);
      const double e_coarse = scaled_error(sol::flow(start, t, rk4(1e-1)).position, r.position);
      if (e_dp > worst_dp) worst_dir = d;
      worst_dp = std::max(worst_dp, e_dp);
      worst_rk4 = std::max(worst_rk4, e_rk4);
      worst_rk4_mid = std::max(worst_rk4_mid, e_mid);
      worst_rk4_coarse = std::max(worst_rk4_coarse, e_coarse);
    }
  }
  std::printf("worst scaled endpoint error, t<=50: DP(1e-12) %.2e (direction %.3g %.3g %.3g), RK4(h=1e-3) %.2e, "
              "RK4(h=1e-2) %.2e, RK4(h=1e-1) %.2e\n",
              worst_dp, worst_dir.x, worst_dir.y, worst_dir.z, worst_rk4, worst_rk4_mid, worst_rk4_coarse);
  // Measured: DP 3.9e-11, RK4(1e-3) 1.7e-12; the bounds leave a margin of ~25x.
  EXPECT_LT(worst_dp, 1e-9);
  EXPECT_LT(worst_rk4, 5e-11);
  // RK4 is 4th order: ten times the step costs about 10^4 in error (1e-2 -> 1e-1
  // is clear of rounding, which floors h = 1e-3); demand at least 3e3.
  EXPECT_GT(worst_rk4_coarse, 3e3 * worst_rk4_mid);
}

// flow from p against the reference integrated from p itself in coordinates:
// checks the left-invariance convention flow(p, v) = p * flow(0, v).
TEST(Geodesic, LeftInvariantFromAnyStart) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<dvec3> dirs = sol::test::random_directions(6, 5);
  for (const dvec3& d : dirs) {
    const dvec3 p(20 * u(rng), 20 * u(rng), 3 * u(rng));
    sol::test::ReferenceGeodesic<> reference(p, d);
    const sol::test::ReferencePoint r = reference.at(7.0);
    const sol::GeodesicState s = sol::flow({p, d}, 7.0);
    EXPECT_LT(scaled_error(s.position, r.position), 1e-9);
    EXPECT_LT(scaled_error(s.direction, r.direction), 1e-9);
  }
}

// The eight isometries fixing the origin, (±x, ±y, z) and (±y, ±x, -z),
// with their action on frame components.
struct Symmetry {
  int sx, sy;
  bool swap;
  dvec3 point(const dvec3& p) const {
    return swap ? dvec3(sx * p.y, sy * p.x, -p.z) : dvec3(sx * p.x, sy * p.y, p.z);
  }
  // E1 = e^{z}∂x at p maps to e^{z}∂y = e^{-z'}∂y = E2 at the image (z' = -z) when swapping.
  dvec3 frame(const dvec3& f) const {
    return swap ? dvec3(sx * f.y, sy * f.x, -f.z) : dvec3(sx * f.x, sy * f.y, f.z);
  }
};

TEST(Geodesic, DihedralSymmetriesMapGeodesicsToGeodesics) {
  const std::vector<dvec3> dirs = sol::test::random_directions(50, 3);
  for (const bool swap : {false, true}) {
    for (const int sx : {-1, 1}) {
      for (const int sy : {-1, 1}) {
        const Symmetry sigma{sx, sy, swap};
        for (const dvec3& d : dirs) {
          const sol::GeodesicState a = sol::flow({dvec3(0.0), d}, 6.0);
          const sol::GeodesicState b = sol::flow({dvec3(0.0), sigma.frame(d)}, 6.0);
          EXPECT_LT(scaled_error(sigma.point(a.position), b.position), 1e-9);
          EXPECT_LT(scaled_error(sigma.frame(a.direction), b.direction), 1e-9);
        }
      }
    }
  }
}

TEST(Geodesic, ForwardThenBackwardReturns) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<dvec3> dirs = sol::test::random_directions(100, 4);
  for (const dvec3& d : sol::test::stiff_directions()) dirs.push_back(d);
  for (const dvec3& d : dirs) {
    const sol::GeodesicState s{{5 * u(rng), 5 * u(rng), u(rng)}, d};
    for (const sol::FlowOptions& o : {dopri(1e-12), rk4(1e-3)}) {
      // Nearby Sol geodesics separate like e^{t}, so the round trip amplifies the
      // forward error by up to e^{2t}; t = 5 keeps that below 1e5.
      const sol::GeodesicState there = sol::flow(s, 5.0, o);
      const sol::GeodesicState back = sol::flow(there, -5.0, o);
      EXPECT_LT(scaled_error(back.position, s.position), 1e-8) << d.x << " " << d.y << " " << d.z;
      EXPECT_LT(scaled_error(back.direction, d), 1e-8);
    }
  }
}

TEST(Geodesic, VerticalLines) {
  for (const double sign : {1.0, -1.0}) {
    for (const sol::FlowOptions& o : {dopri(1e-12), rk4(1e-2)}) {
      const sol::GeodesicState s = sol::flow({{1.5, -2.0, 0.3}, {0, 0, sign}}, 37.0, o);
      EXPECT_DOUBLE_EQ(s.position.x, 1.5);
      EXPECT_DOUBLE_EQ(s.position.y, -2.0);
      // Summing 3700 RK4 steps of size 1e-2 into |z| ~ 37 rounds by up to ~3700 * 37 * eps ~ 3e-11.
      EXPECT_NEAR(s.position.z, 0.3 + sign * 37.0, 1e-10);
      EXPECT_EQ(s.direction, dvec3(0, 0, sign));
    }
  }
}

TEST(Geodesic, StraightLinesInThePlaneZ0) {
  const double s2 = std::sqrt(2.0);
  for (const double sy : {1.0, -1.0}) {
    for (const double t : {0.5, 3.0, s2 * M_PI, 40.0}) {
      const sol::GeodesicState s = sol::flow({dvec3(0.0), {1 / s2, sy / s2, 0}}, t);
      EXPECT_LT(scaled_error(s.position, {t / s2, sy * t / s2, 0.0}), 1e-12);
    }
  }
}

// In the plane x = 0 the metric is e^{2z}dy^2 + dz^2 = (dy^2 + dw^2)/w^2 with
// w = e^{-z}: the upper half-plane, whose unit-speed geodesics are
// y = y_c + R tanh(t + s0), w = R sech(t + s0). From (0,0,0) with frame
// direction (0, b, c), b > 0: tanh s0 = c, R = 1/b.
dvec3 hyperbolic_plane_x0(double b, double c, double t) {
  const double s0 = std::atanh(c), r = 1.0 / std::abs(b);
  const double y = std::copysign(r * (std::tanh(t + s0) - std::tanh(s0)), b);
  const double w = r / std::cosh(t + s0);
  return {0.0, y, -std::log(w)};
}

TEST(Geodesic, PlanesX0AndY0AreHyperbolicPlanes) {
  for (const double angle : {0.1, 0.7, 1.3, 1.5707, 2.2, 3.0}) {
    for (const double sign : {1.0, -1.0}) {
      const double b = sign * std::sin(angle), c = std::cos(angle);
      for (const double t : {0.5, 2.0, 8.0}) {
        const dvec3 expected = hyperbolic_plane_x0(b, c, t);
        const sol::GeodesicState s = sol::flow({dvec3(0.0), {0.0, b, c}}, t);
        EXPECT_EQ(s.position.x, 0.0);
        EXPECT_LT(scaled_error(s.position, expected), 1e-9) << angle << " " << t;
        // The plane y = 0 is its mirror image under (x,y,z) -> (y,x,-z).
        const sol::GeodesicState m = sol::flow({dvec3(0.0), {b, 0.0, -c}}, t);
        EXPECT_EQ(m.position.y, 0.0);
        EXPECT_LT(scaled_error(m.position, {expected.y, 0.0, -expected.z}), 1e-9);
      }
    }
  }
}

TEST(Geodesic, NormalisesDirectionAndZeroTIsIdentity) {
  const sol::GeodesicState a = sol::flow({{1, 2, 3}, {3, 4, 12}}, 2.0);
  const sol::GeodesicState b = sol::flow({{1, 2, 3}, {3.0 / 13, 4.0 / 13, 12.0 / 13}}, 2.0);
  EXPECT_LT(scaled_error(a.position, b.position), 1e-14);
  const sol::GeodesicState same = sol::flow({{1, 2, 3}, {0, 3, 4}}, 0.0);
  EXPECT_EQ(same.position, dvec3(1, 2, 3));
  EXPECT_LT(scaled_error(same.direction, {0, 0.6, 0.8}), 1e-15);
}

TEST(Geodesic, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const sol::GeodesicState good{dvec3(0.0), {1, 0, 0}};
  EXPECT_THROW(sol::flow(good, nan), sol::InvalidArgument);
  EXPECT_THROW(sol::flow(good, inf), sol::InvalidArgument);
  EXPECT_THROW(sol::flow({{nan, 0, 0}, {1, 0, 0}}, 1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::flow({dvec3(0.0), {0, inf, 0}}, 1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::flow({dvec3(0.0), dvec3(0.0)}, 1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::flow(good, 1.0, rk4(0.0)), sol::InvalidArgument);
  EXPECT_THROW(sol::flow(good, 1.0, rk4(nan)), sol::InvalidArgument);
  EXPECT_THROW(sol::flow(good, 1.0, dopri(-1.0)), sol::InvalidArgument);
  EXPECT_THROW(sol::transport({dvec3(0.0), {nan, 0, 0}}, 1.0), sol::InvalidArgument);
  // Integrating a vertical geodesic of length 1000 overflows e^{z} in the
  // ODE: a clear error, not inf or NaN. The closed form reaches it exactly.
  EXPECT_THROW(sol::flow({{1, 1, 0}, {0, 0, 1}}, 1000.0, sol::Method::DormandPrince), sol::OutOfRange);
  EXPECT_EQ(sol::flow({{1, 1, 0}, {0, 0, 1}}, 1000.0).position, dvec3(1, 1, 1000));
  // An arc length beyond double's resolution of the period: a clear error.
  EXPECT_THROW(sol::flow({dvec3(0.0), {0.48, 0.6, 0.64}}, 1e300), sol::OutOfRange);
}

// An arc length that would take the integrators minutes, or forever (a
// step below the rounding of s never advances it), is refused with the
// function named and the step limit, at once for RK4 (whose count is known
// before it starts) and after the limit's steps for Dormand–Prince.
TEST(Geodesic, IntegrationsBeyondTheStepLimitAreRefused) {
  auto refused = [](auto&& call, const char* function) {
    try {
      call();
      ADD_FAILURE() << function << " answered";
    } catch (const sol::OutOfRange& e) {
      EXPECT_NE(std::string(e.what()).find(function), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("integration steps"), std::string::npos) << e.what();
    }
  };
  const sol::GeodesicState start{dvec3(0.0), {1.0, 0.2, 0.3}};
  refused([&] { sol::flow(start, 1e5, rk4(1e-3)); }, "sol::flow");  // 1e8 steps
  refused([&] { sol::flow(start, 1e300, rk4(1e-3)); }, "sol::flow");
  refused([&] { sol::transport(start, 1e9); }, "sol::transport");
  refused([&] { sol::sphere_area_density(dvec3(1, 0, 0), 1e9); }, "sol::sphere_area_density");
  refused([&] { sol::sphere_area_density(dvec3(1, 0, 0), 1e308); }, "sol::sphere_area_density");
  refused([&] { sol::sphere_area_density(glm::vec3(1, 0, 0), 1e30f); }, "sol::sphere_area_density");
  // Within the limits, as before.
  EXPECT_NO_THROW(sol::flow(start, 100.0, rk4(1e-3)));
  EXPECT_NO_THROW(sol::transport(start, 50.0));
}

}  // namespace
