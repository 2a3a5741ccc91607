// The closed-form flow against the 50-digit reference in every regime, in
// double and float; quasi-periodicity; degenerate regimes; no error bands.
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"
#include "support/sweep.hpp"

namespace {

using glm::dvec3;
using sol::test::scaled_error;

struct Worst {
  double error = 0;
  dvec3 direction{0.0};
  double t = 0;
  void update(double e, const dvec3& d, double at) {
    if (e > error) {
      error = e;
      direction = d;
      t = at;
    }
  }
  std::string describe() const {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%.3e at direction (%.17g, %.17g, %.17g), t = %g", error, direction.x, direction.y,
                  direction.z, t);
    return buf;
  }
};

// Endpoint error of the double and float closed forms against the reference,
// over every stiff direction and random ones, arc lengths up to 50, both signs.
TEST(ClosedForm, MatchesReferenceInEveryRegime) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(24, 77)) dirs.push_back(d);
  Worst worst_double, worst_float;
  for (const dvec3& d : sol::test::sweep(dirs)) {
    const sol::ClosedFormGeodesic<double> g(d);
    const sol::ClosedFormGeodesic<float> gf{glm::vec3(d)};
    // The float direction is d rounded to float: its own reference is needed for a fair figure.
    const dvec3 df = glm::dvec3(gf.direction());
    for (const double sign : {1.0, -1.0}) {
      // The float goal (2e-5) needs far less than 50 digits: a double
      // Bulirsch–Stoer reference at 1e-12 is ~1e-10 accurate and 20x cheaper.
      sol::test::ReferenceGeodesic<> reference(sign * d, false, 1e-24);  // ~1e-16 here: ample for the 1e-10 goal
      sol::test::ReferenceGeodesic<double> reference_f(sign * df, false, 1e-12);
      for (const double t : {0.5, 1.0, 3.0, 10.0, 17.0, 30.0, 50.0}) {
        const sol::test::ReferencePoint r = reference.at(t);
        const auto s = g.at(sign * t);
        const double e = std::max(scaled_error(s.position, r.position), scaled_error(sign * s.direction, r.direction));
        worst_double.update(e, d, sign * t);
        const sol::test::ReferencePoint rf = reference_f.at(t);
        const auto sf = gf.at(static_cast<float>(sign * t));
        const double ef = std::max(scaled_error(glm::dvec3(sf.position), rf.position),
                                   scaled_error(sign * glm::dvec3(sf.direction), rf.direction));
        worst_float.update(ef, d, sign * t);
      }
    }
  }
  std::printf("closed form, worst scaled endpoint error over %zu directions, |t| <= 50:\n  double %s\n  float  %s\n",
              dirs.size(), worst_double.describe().c_str(), worst_float.describe().c_str());
  // Goals of the issue: double 1e-10 * max(1, |coordinate|), float 2e-5.
  EXPECT_LT(worst_double.error, 1e-10) << worst_double.describe();
  EXPECT_LT(worst_float.error, 2e-5) << worst_float.describe();
}

// Sweep |ab| over 30 decades with a and c fixed, and the angle to the
// straight lines over 15 decades: no band of directions where the error jumps.
TEST(ClosedForm, NoErrorBandsAcrossRegimes) {
  Worst worst;
  for (int e = -30; e <= 0; e += sol::test::kSanitizedBuild ? 6 : 2) {
    const dvec3 d = glm::normalize(dvec3(0.6, std::pow(10.0, e), 0.5));
    sol::test::ReferenceGeodesic<> reference(d);
    const sol::test::ReferencePoint r = reference.at(12.0);
    const auto s = sol::ClosedFormGeodesic<double>(d).at(12.0);
    worst.update(std::max(scaled_error(s.position, r.position), scaled_error(s.direction, r.direction)), d, 12.0);
  }
  const double h = 1.0 / std::sqrt(2.0);
  for (int e = -15; e <= -1; ++e) {
    const double eps = std::pow(10.0, e);
    for (const dvec3& raw : {dvec3(h + eps, h, 0.0), dvec3(h, h, eps), dvec3(h, -h, -eps)}) {
      const dvec3 d = glm::normalize(raw);
      sol::test::ReferenceGeodesic<> reference(d);
      const sol::test::ReferencePoint r = reference.at(9.0);
      const auto s = sol::ClosedFormGeodesic<double>(d).at(9.0);
      worst.update(std::max(scaled_error(s.position, r.position), scaled_error(s.direction, r.direction)), d, 9.0);
    }
  }
  std::printf("regime sweeps: worst %s\n", worst.describe().c_str());
  EXPECT_LT(worst.error, 1e-10) << worst.describe();
}

// After one period z and the direction return and the position is the
// period shift: checked against the reference (independent of the closed form).
TEST(ClosedForm, PeriodAndShiftMatchTheReference) {
  for (const dvec3& d : sol::test::random_directions(6, 78)) {
    const sol::ClosedFormGeodesic<double> g(d);
    const double period = g.period();
    ASSERT_TRUE(std::isfinite(period));
    if (period > 60) continue;  // keep the reference cheap
    sol::test::ReferenceGeodesic<> reference(d);
    const sol::test::ReferencePoint r = reference.at(period);
    EXPECT_NEAR(r.position.z, 0.0, 1e-10);
    EXPECT_LT(scaled_error(r.direction, d), 1e-10);
    EXPECT_LT(scaled_error(g.period_shift(), r.position), 1e-10);
  }
}

// γ(t + nT) = (n X_T, n Y_T, 0) * γ(t): far arc lengths cost one evaluation
// and agree with the shift law to rounding.
TEST(ClosedForm, QuasiPeriodicAtLargeArcLength) {
  for (const dvec3& d : sol::test::random_directions(50, 79)) {
    const sol::ClosedFormGeodesic<double> g(d);
    const double period = g.period();
    const double t = 0.37 * period;
    const auto near = g.at(t);
    const auto far = g.at(t + 40 * period);
    const dvec3 expected = sol::multiply(40.0 * g.period_shift(), near.position);
    // Rounding of u = λt + u0 at t ~ 40 T: relative error ~ eps * 40 T * |velocity|.
    EXPECT_LT(scaled_error(far.position, expected), 1e-11 * 40 * period) << d.x << " " << d.y << " " << d.z;
    EXPECT_LT(scaled_error(far.direction, near.direction), 1e-11 * 40 * period);
  }
}

TEST(ClosedForm, ExactDegenerateCases) {
  const double h = 1.0 / std::sqrt(2.0);
  // Straight lines and vertical lines are exact.
  const auto straight = sol::ClosedFormGeodesic<double>({h, -h, 0.0}).at(30.0);
  EXPECT_LT(scaled_error(straight.position, {30 * h, -30 * h, 0.0}), 1e-15);
  const auto vertical = sol::ClosedFormGeodesic<double>({0, 0, -1}).at(7.0);
  EXPECT_EQ(vertical.position, dvec3(0, 0, -7));
  // In the plane x = 0, the explicit hyperbolic-plane geodesic (see geodesic_test).
  const double b = 0.6, c = 0.8, t = 3.0;
  const double s0 = std::atanh(c), r = 1.0 / b;
  const auto inplane = sol::ClosedFormGeodesic<double>({0.0, b, c}).at(t);
  EXPECT_EQ(inplane.position.x, 0.0);
  EXPECT_NEAR(inplane.position.y, r * (std::tanh(t + s0) - std::tanh(s0)), 1e-14);
  EXPECT_NEAR(inplane.position.z, std::log(std::cosh(t + s0) / r), 1e-14);
}

TEST(ClosedForm, FlowAutoUsesIt) {
  const sol::GeodesicState start{{1.0, -2.0, 0.5}, {0.48, 0.6, 0.64}};
  const sol::GeodesicState a = sol::flow(start, 5.0);
  const sol::GeodesicState c = sol::flow(start, 5.0, sol::Method::ClosedForm);
  const auto direct = sol::ClosedFormGeodesic<double>(start.direction).at(5.0);
  EXPECT_EQ(a.position, c.position);
  EXPECT_LT(scaled_error(c.position, sol::multiply(start.position, direct.position)), 1e-15);
}

TEST(ClosedForm, RejectsBadDirections) {
  EXPECT_THROW(sol::ClosedFormGeodesic<double>(dvec3(0.0)), sol::InvalidArgument);
  EXPECT_THROW(sol::ClosedFormGeodesic<double>(dvec3(std::numeric_limits<double>::quiet_NaN(), 0, 0)),
               sol::InvalidArgument);
  EXPECT_THROW(sol::ClosedFormGeodesic<float>(glm::vec3(0, std::numeric_limits<float>::infinity(), 0)),
               sol::InvalidArgument);
}

}  // namespace

namespace {

// The height range against the Dormand–Prince flow sampled over one period
// (independent of the closed form): the extremes agree and nothing leaves it.
TEST(ClosedForm, HeightRangeMatchesTheFlow) {
  sol::FlowOptions dopri;
  dopri.method = sol::Method::DormandPrince;
  int checked = 0;
  for (const dvec3& d : sol::test::random_directions(20, 81)) {
    const sol::ClosedFormGeodesic<double> g(d);
    const double period = g.period();
    if (period > 60) continue;
    ++checked;
    double lo = 1e300, hi = -1e300;
    sol::GeodesicState s{dvec3(0.0), d};
    const int n = 4000;
    for (int i = 0; i <= n; ++i) {
      lo = std::min(lo, s.position.z);
      hi = std::max(hi, s.position.z);
      s = sol::flow(s, period / n, dopri);
    }
    // Sampling misses the extreme by at most ~(period/n)^2 |z''| / 8.
    const double slack = 1e-6;
    EXPECT_LE(g.min_height(), lo + 1e-12) << d.x << " " << d.y << " " << d.z;
    EXPECT_GE(g.max_height(), hi - 1e-12);
    EXPECT_NEAR(g.min_height(), lo, slack);
    EXPECT_NEAR(g.max_height(), hi, slack);
  }
  EXPECT_GE(checked, 10);
  // Degenerate regimes: unbounded or flat.
  EXPECT_EQ(sol::ClosedFormGeodesic<double>(dvec3(0, 0, 1)).min_height(), -std::numeric_limits<double>::infinity());
  const double h = 1.0 / std::sqrt(2.0);
  EXPECT_EQ(sol::ClosedFormGeodesic<double>(dvec3(h, h, 0)).max_height(), 0.0);
  const sol::ClosedFormGeodesic<double> in_plane(dvec3(0.6, 0.0, 0.8));
  EXPECT_EQ(in_plane.min_height(), -std::numeric_limits<double>::infinity());
  EXPECT_NEAR(in_plane.max_height(), std::log(1.0 / 0.6), 1e-15);  // top of the H² geodesic: e^{z} = 1/a
}

}  // namespace
