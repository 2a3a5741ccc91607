// The exact distance and the connections between two points, checked against
// facts (docs/mathematics.md) and the independent 50-digit reference geodesics, not
// against the solver itself.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sol/closed_form.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/error.hpp"
#include "sol/geodesic.hpp"
#include "sol/group.hpp"
#include "support/directions.hpp"
#include "support/reference_geodesic.hpp"
#include "support/sweep.hpp"
#include "warm_solves.hpp"  // libsol/src: a march's warm starts

namespace {

constexpr double kTol = 1e-9;  // the accuracy on distances
// 50-digit arithmetic at a 1e-20 step tolerance: end points far below kTol, in less time.
const sol::test::Real50 kReferenceTolerance(1e-20);

glm::dvec3 random_point(std::mt19937_64& rng, double xy, double z) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {xy * u(rng), xy * u(rng), z * u(rng)};
}

// Where flow from p along c lands, as its distance-like error in the frame at q.
double landing_error(const glm::dvec3& p, const sol::Connection& c, const glm::dvec3& q) {
  const glm::dvec3 end = sol::flow({p, c.direction}, c.length).position;
  const glm::dvec3 e = sol::multiply(sol::inverse(q), end);
  return glm::length(e);
}

// cosh d = cosh Δz + ½ Δ² e^{±(z1+z2)} (docs/mathematics.md), solved for d without cancellation.
double plane_distance(double delta, double z1, double z2, double sign) {
  const double sh = std::sinh(0.5 * (z2 - z1));
  return 2.0 * std::asinh(std::sqrt(sh * sh + 0.25 * delta * delta * std::exp(sign * (z1 + z2))));
}

TEST(Connection, PlaneAndVerticalPairsHaveTheExactDistances) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 p = random_point(rng, 5.0, 3.0), r = random_point(rng, 5.0, 3.0);
    // In the plane x = p.x: cosh d = cosh Δz + ½Δy² e^{z1+z2}.
    const glm::dvec3 qx(p.x, r.y, r.z);
    const double dx = plane_distance(r.y - p.y, p.z, r.z, 1.0);
    EXPECT_NEAR(sol::distance(p, qx), dx, kTol * std::max(1.0, dx)) << i;
    // In the plane y = p.y: cosh d = cosh Δz + ½Δx² e^{-(z1+z2)}.
    const glm::dvec3 qy(r.x, p.y, r.z);
    const double dy = plane_distance(r.x - p.x, p.z, r.z, -1.0);
    EXPECT_NEAR(sol::distance(p, qy), dy, kTol * std::max(1.0, dy)) << i;
    // Vertical pairs: |Δz|.
    const glm::dvec3 qz(p.x, p.y, r.z);
    EXPECT_NEAR(sol::distance(p, qz), std::abs(r.z - p.z), kTol) << i;
    for (const glm::dvec3& q : {qx, qy, qz}) {
      for (const sol::Connection& c : sol::geodesics_between(p, q, 40.0)) {
        EXPECT_LT(landing_error(p, c, q), 1e-10) << i;
      }
    }
  }
}

TEST(Connection, StraightSegmentsUpToTheirPeriodAreMinimising) {
  // (t/√2, ±t/√2, 0) is the straight line a = ±b = 1/√2, c = 0, whose period
  // is 4K(0)/√2 = √2 π: minimising exactly up to there.
  const glm::dvec3 g(0.3, -1.2, 0.7);
  for (int i = 1; i <= 40; ++i) {
    const double t = std::sqrt(2.0) * std::numbers::pi * i / 40.0;
    for (double sign : {1.0, -1.0}) {
      const glm::dvec3 q(t / std::sqrt(2.0), sign * t / std::sqrt(2.0), 0.0);
      EXPECT_NEAR(sol::distance({0, 0, 0}, q), t, kTol) << t;
      EXPECT_NEAR(sol::distance(g, sol::multiply(g, q)), t, kTol) << t;
    }
  }
}

TEST(Connection, GeodesicsShorterThanTheirPeriodHaveTheirLengthAsDistance) {
  // Coiculescu–Schwartz: a geodesic from the origin minimises up to its
  // period T. End points from the 50-digit reference, lengths up to 0.95 T
  // (capped at 16), directions random and stiff (docs/mathematics.md). The straight
  // lines |a| = |b|, c = 0 have T = 4K(0)/√2 = √2π.
  std::vector<glm::dvec3> dirs = sol::test::random_directions(14, 99);
  for (const glm::dvec3& d : sol::test::stiff_directions()) dirs.push_back(d);
  dirs = sol::test::sweep(dirs, 3);
  int checked = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const glm::dvec3 d = dirs[i];
    const bool straight = d.z == 0.0 && std::abs(d.x) == std::abs(d.y);
    const double period = straight ? std::sqrt(2.0) * std::numbers::pi : sol::ClosedFormGeodesic<double>(d).period();
    for (double fraction : {0.1, 0.5, 0.95}) {
      const double t = std::min(16.0, fraction * period);
      if (std::isinf(period) && fraction != 0.5) continue;
      sol::test::ReferenceGeodesic<> reference(d, false, kReferenceTolerance);
      const glm::dvec3 q = reference.at(t).position;
      const double dist = sol::distance({0, 0, 0}, q);
      EXPECT_NEAR(dist, t, kTol * std::max(1.0, t)) << "direction " << i << " t " << t;
      ++checked;
    }
  }
  EXPECT_GT(checked, sol::test::sweep_count(30, 3));
}

TEST(Connection, StiffFarTargetsUpToThirty) {
  // Directions with a tiny |a| or |b| (|ab| -> 0) at lengths 18 to 30: the
  // targets are far and near a plane (y' ~ 1e9 at z' ~ -14). A minimiser is
  // always found (no OutOfRange); its length is never above the generating
  // length t, equals it when t <= T (Coiculescu–Schwartz: the generating
  // geodesic then minimises; past T the minimiser may be quite another
  // direction), it lands on q, and d(p, q) = d(q, p) and left invariance hold
  // for some. End points by the closed-form flow.
  struct Case {
    glm::dvec3 d;
    double t;
  };
  std::vector<Case> cases;
  for (const glm::dvec3& d : sol::test::stiff_directions()) {
    const double small = std::min(std::abs(d.x), std::abs(d.y));
    if (!(small > 0.0) || small > 1e-3 || std::abs(d.z) > 0.99) continue;
    for (double t : {18.0, 24.0, 30.0}) cases.push_back({d, t});
  }
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 120; ++i) {
    const double b = std::pow(10.0, -9.0 + 5.0 * u(rng)), c = 2.0 * u(rng) - 1.0;
    const double a = std::sqrt(std::max(0.0, 1.0 - b * b - c * c));
    const double t = 18.0 + 12.0 * u(rng);
    if (!(a > 0.0)) continue;
    glm::dvec3 d = glm::normalize(glm::dvec3(a, b, c));
    if (i % 2 == 1) d = {-d.y, d.x, -d.z};  // tiny a, other signs
    cases.push_back({d, t});
  }
  int equal_checked = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [d, t] = cases[i];
    const glm::dvec3 q = sol::flow({glm::dvec3(0.0), d}, t).position;
    ASSERT_TRUE(std::isfinite(q.x) && std::isfinite(q.y)) << i;
    std::vector<sol::Connection> cs;
    try {
      cs = sol::minimising_geodesics({0, 0, 0}, q);
    } catch (const sol::OutOfRange& e) {
      ADD_FAILURE() << "case " << i << " direction (" << d.x << ", " << d.y << ", " << d.z << ") t " << t << ": "
                    << e.what();
      continue;
    }
    ASSERT_FALSE(cs.empty()) << i;
    const double dist = cs.front().length;
    EXPECT_LE(dist, t * (1.0 + kTol)) << i;
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    if (t <= period) {
      EXPECT_NEAR(dist, t, kTol * t) << "case " << i << " period " << period;
      ++equal_checked;
    }
    // Landing error relative to the scale of q in the frame (rounding floor of the problem).
    const double scale = std::max({1.0, std::abs(q.x) * std::exp(-q.z), std::abs(q.y) * std::exp(q.z)});
    for (const sol::Connection& c : cs) EXPECT_LT(landing_error({0, 0, 0}, c, q) / scale, 1e-10) << i;
    if (i % 8 == 0) {
      EXPECT_NEAR(sol::distance(q, {0, 0, 0}), dist, kTol * dist) << i;
      const glm::dvec3 g(0.7, -1.3, 0.4);
      EXPECT_NEAR(sol::distance(g, sol::multiply(g, q)), dist, kTol * dist) << i;
    }
  }
  EXPECT_GT(equal_checked, 80);
}

TEST(Connection, FarPointsUpToThirty) {
  // Directions close to vertical have long periods: far points at lengths 20 to 30.
  int checked = 0;
  for (const glm::dvec3& d : {sol::test::direction_with_c(1.0, 2.0, 0.999), sol::test::direction_with_c(3.0, 1.0, -0.9999),
                              sol::test::direction_with_c(1.0, 1.0, 0.99999), sol::test::direction_with_c(-1.0, 4.0, -0.99995)}) {
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    const double t = std::min(30.0, 0.9 * period);
    if (t < 20.0) continue;
    ++checked;
    sol::test::ReferenceGeodesic<> reference(d, false, kReferenceTolerance);
    const glm::dvec3 q = reference.at(t).position;
    EXPECT_NEAR(sol::distance({0, 0, 0}, q), t, kTol * t) << d.x << " " << d.y << " " << d.z;
  }
  EXPECT_GE(checked, 2);
  // Far targets both of whose horizontal coordinates are large.
  for (const glm::dvec3& q : {glm::dvec3(1e4, 1e4, 0.5), glm::dvec3(1e5, 30.0, 2.0), glm::dvec3(-300.0, 2e3, -1.0)}) {
    const std::vector<sol::Connection> cs = sol::minimising_geodesics({0, 0, 0}, q);
    ASSERT_FALSE(cs.empty());
    EXPECT_GT(cs.front().length, 20.0);
    EXPECT_LE(sol::distance_lower_bound({0, 0, 0}, q), cs.front().length);
    sol::test::ReferenceGeodesic<> reference(cs.front().direction, false, kReferenceTolerance);
    const glm::dvec3 end = reference.at(cs.front().length).position;
    EXPECT_LT(glm::length(sol::multiply(sol::inverse(q), end)), 1e-9) << q.x << " " << q.y << " " << q.z;
  }
}

TEST(Connection, CutLocusHasTwoMinimisers) {
  // At t = T the geodesics (a, b, ±c) meet on z = 0 (the shift of a period
  // depends on a, b only): both minimise, the distance is T.
  for (const glm::dvec3& d : {glm::dvec3(0.6, 0.5, 0.62449979983983983), glm::dvec3(0.3, 0.8, -0.52),
                              sol::test::direction_with_c(1.0, 1.0, 0.2)}) {
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    sol::test::ReferenceGeodesic<> reference(d, false, kReferenceTolerance);
    const glm::dvec3 q = reference.at(period).position;
    EXPECT_NEAR(q.z, 0.0, 1e-12);
    EXPECT_NEAR(sol::distance({0, 0, 0}, q), period, kTol * period);
    const std::vector<sol::Connection> cs = sol::minimising_geodesics({0, 0, 0}, q);
    ASSERT_EQ(cs.size(), 2u);
    const glm::dvec3 n = glm::normalize(d);
    for (const sol::Connection& c : cs) {
      EXPECT_NEAR(c.length, period, kTol * period);
      EXPECT_NEAR(c.direction.x, n.x, 1e-6);
      EXPECT_NEAR(c.direction.y, n.y, 1e-6);
      EXPECT_NEAR(std::abs(c.direction.z), std::abs(n.z), 1e-6);
      EXPECT_LT(landing_error({0, 0, 0}, c, q), 1e-10);
    }
    EXPECT_LT(cs[0].direction.z * cs[1].direction.z, 0.0);
    // Nearby off the plane: one minimiser, the distance continuous.
    const glm::dvec3 q_up(q.x, q.y, 1e-6);
    EXPECT_NEAR(sol::distance({0, 0, 0}, q_up), period, 1e-5);
  }
}

// Within a detail::WarmSolves scope (a march's: each ray's exact solves
// start from the last one, a repeated target takes the last answer) the
// answers are the cold ones: points 0.05 apart along 50-digit reference
// geodesics from the origin, each shorter than its period, have their
// length as distance (Coiculescu–Schwartz) to kTol, a repeated target the
// same distance bit for bit, and the cut-locus pair after a point near it
// still has two minimisers.
TEST(Connection, WarmSolvesAlongARayKeepTheDistances) {
  const sol::detail::WarmSolves warm;
  int checked = 0;
  for (const glm::dvec3& d : sol::test::random_directions(6, 7)) {
    const double period = sol::ClosedFormGeodesic<double>(d).period();
    sol::test::ReferenceGeodesic<> reference(d, false, kReferenceTolerance);
    for (double t = 0.05; t < std::min(6.0, 0.95 * period); t += 0.05) {
      const glm::dvec3 q = reference.at(t).position;
      const double dist = sol::distance({0, 0, 0}, q);
      EXPECT_NEAR(dist, t, kTol * std::max(1.0, t)) << "t " << t;
      EXPECT_EQ(sol::distance({0, 0, 0}, q), dist);
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  const glm::dvec3 d(0.6, 0.5, 0.62449979983983983);
  const double period = sol::ClosedFormGeodesic<double>(d).period();
  sol::test::ReferenceGeodesic<> reference(d, false, kReferenceTolerance);
  EXPECT_NEAR(sol::distance({0, 0, 0}, reference.at(0.97 * period).position), 0.97 * period, kTol * period);
  EXPECT_EQ(sol::minimising_geodesics({0, 0, 0}, reference.at(period).position).size(), 2u);
}

TEST(Connection, SymmetryInvarianceTriangleAndLowerBound) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 40; ++i) {
    const glm::dvec3 p = random_point(rng, 2.0, 1.5), q = random_point(rng, 2.0, 1.5), r = random_point(rng, 2.0, 1.5);
    const double pq = sol::distance(p, q), qp = sol::distance(q, p);
    EXPECT_NEAR(pq, qp, kTol * std::max(1.0, pq)) << i;
    EXPECT_LE(sol::distance_lower_bound(p, q), pq + 1e-12) << i;
    // Left invariance.
    const glm::dvec3 g = random_point(rng, 3.0, 2.0);
    EXPECT_NEAR(sol::distance(sol::multiply(g, p), sol::multiply(g, q)), pq, kTol * std::max(1.0, pq)) << i;
    // The eight symmetries fixing the origin, applied to both points.
    for (int s = 0; s < 8; ++s) {
      auto sym = [s](glm::dvec3 v) {
        if (s & 1) v.x = -v.x;
        if (s & 2) v.y = -v.y;
        if (s & 4) v = {v.y, v.x, -v.z};
        return v;
      };
      EXPECT_NEAR(sol::distance(sym(p), sym(q)), pq, kTol * std::max(1.0, pq)) << i << " symmetry " << s;
    }
    // Triangle inequality.
    const double pr = sol::distance(p, r), rq = sol::distance(r, q);
    EXPECT_LE(pq, pr + rq + 1e-9) << i;
    // The connections land on q, the first has the distance as length.
    const std::vector<sol::Connection> cs = sol::minimising_geodesics(p, q);
    ASSERT_FALSE(cs.empty());
    EXPECT_NEAR(cs.front().length, pq, 1e-12 * std::max(1.0, pq));
    for (const sol::Connection& c : cs) EXPECT_LT(landing_error(p, c, q), 1e-10) << i;
  }
}

TEST(Connection, EveryConnectionUpToALengthAgainstABruteForceScan) {
  // Longer connections: the default scan and one at four times the
  // resolution find the same set; all land on q, shortest first, the first
  // is the distance; the straight line to (5, 5, 0) (length 5√2, past its
  // period √2π) is among them.
  struct Case {
    glm::dvec3 p, q;
    double max_length;
  };
  const std::vector<Case> cases = {
      {{0, 0, 0}, {5, 5, 0}, 7.2},
      {{0.2, -0.1, 0.3}, {1.5, 2.0, 0.1}, 7.0},
      {{0, 0, 0}, {2.0, 0.5, -0.4}, 8.0},
  };
  sol::ConnectionOptions fine;
  fine.scan_polar *= 4;
  fine.scan_azimuth *= 4;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const std::vector<sol::Connection> found = sol::geodesics_between(c.p, c.q, c.max_length);
    const std::vector<sol::Connection> brute = sol::geodesics_between(c.p, c.q, c.max_length, fine);
    ASSERT_FALSE(found.empty()) << i;
    EXPECT_NEAR(found.front().length, sol::distance(c.p, c.q), 1e-12) << i;
    EXPECT_EQ(found.size(), brute.size()) << i;
    for (std::size_t k = 0; k < found.size(); ++k) {
      EXPECT_LT(landing_error(c.p, found[k], c.q), 1e-10) << i << " " << k;
      EXPECT_LE(found[k].length, c.max_length + 1e-12);
      if (k > 0) {
        EXPECT_LE(found[k - 1].length, found[k].length);
      }
      if (k < brute.size()) {
        EXPECT_NEAR(found[k].length, brute[k].length, 1e-9) << i << " " << k;
      }
    }
    if (i == 0) {
      const bool straight = std::any_of(found.begin(), found.end(), [](const sol::Connection& k) {
        return std::abs(k.length - 5.0 * std::sqrt(2.0)) < 1e-9 && std::abs(k.direction.z) < 1e-9;
      });
      EXPECT_TRUE(straight);
      EXPECT_GE(found.size(), 3u);
    }
  }
  // Below the distance: nothing.
  EXPECT_TRUE(sol::geodesics_between({0, 0, 0}, {5, 5, 0}, 6.0).empty());
}

TEST(Connection, RandomPairsNearAndFar) {
  // Random pairs with |x|, |y| up to 1, 5, 20, 100 and |z| <= 3: a minimiser
  // is always found (no OutOfRange), certified by t <= T, lands on q, and is
  // never below the lower bound. (630.73, 5.49, -0.107) is near the cut locus
  // far away: there the first branch found arrives past its period and the
  // minimiser is next to its mirror.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> pairs = {{{0, 0, 0}, {630.730995, 5.494016, -0.107253}}};
  for (double r : {1.0, 5.0, 20.0, 100.0}) {
    for (int i = 0; i < 40; ++i) pairs.push_back({{r * u(rng), r * u(rng), 3 * u(rng)}, {r * u(rng), r * u(rng), 3 * u(rng)}});
  }
  for (const auto& [p, q] : pairs) {
    const std::vector<sol::Connection> cs = sol::minimising_geodesics(p, q);
    ASSERT_FALSE(cs.empty());
    const sol::Connection& c = cs.front();
    EXPECT_LE(sol::distance_lower_bound(p, q), c.length + 1e-12);
    EXPECT_LT(landing_error(p, c, q), 1e-10) << q.x << " " << q.y << " " << q.z;
    const bool straight = c.direction.z == 0.0 && std::abs(std::abs(c.direction.x) - std::abs(c.direction.y)) < 1e-15;
    const double period = straight ? std::sqrt(2.0) * std::numbers::pi : sol::ClosedFormGeodesic<double>(c.direction).period();
    EXPECT_LE(c.length, period * (1.0 + 1e-9));
  }
}

TEST(Connection, LogSeriesInvertsTheExponentialMap) {
  // The logarithm's Taylor series (sol/log_series.h, derived from the
  // geodesic equations by scripts/log_series.py) against the double closed
  // form: for v = t·d, w = exp(v) = flow from the origin along d for t,
  // log_series(w) is v. Within the series' reach (|w| < kLogSeriesReach) it
  // is within 5e-5 (what header and docs/exact.md promise); for t <= 0.2,
  // where the truncation (|w|/R)^12 is near double rounding, within 1e-11,
  // so that a wrong coefficient of any order shows (one off by 1e-3 at
  // degree 11 adds 2e-11 at t = 0.2). Directions random and stiff, lengths
  // up to where w leaves the reach.
  std::vector<glm::dvec3> dirs = sol::test::random_directions(3000, 31);
  for (const glm::dvec3& d : sol::test::stiff_directions()) dirs.push_back(d);
  double worst = 0.0, worst_near = 0.0;
  int checked = 0;
  for (const glm::dvec3& d : dirs) {
    for (int i = 1; i <= 40; ++i) {
      const double t = 0.025 * i;
      const glm::dvec3 w = sol::flow({{0.0, 0.0, 0.0}, d}, t).position;
      if (!(glm::length(w) < sol::kernel::kLogSeriesReach)) break;
      const double error = glm::length(sol::log_series(w) - t * d);
      worst = std::max(worst, error);
      if (t <= 0.2) worst_near = std::max(worst_near, error);
      ++checked;
    }
  }
  EXPECT_GT(checked, 60000);
  EXPECT_LT(worst, 5e-5);  // measured 3.8e-5
  EXPECT_LT(worst_near, 1e-11);
  EXPECT_THROW(sol::log_series({0.9, 0.0, 0.0}), sol::InvalidArgument);
  EXPECT_THROW(sol::log_series({std::nan(""), 0.0, 0.0}), sol::InvalidArgument);
  std::printf("log_series: %d points, worst |log_series(exp v) - v| %.2e, for |v| <= 0.2 %.2e\n", checked, worst,
              worst_near);
}

TEST(Connection, RejectsNonFiniteInput) {
  const double nan = std::nan("");
  EXPECT_THROW(sol::distance({nan, 0, 0}, {1, 1, 1}), sol::InvalidArgument);
  EXPECT_THROW(sol::distance({0, 0, 0}, {1, INFINITY, 1}), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesics_between({0, 0, 0}, {1, 1, 1}, nan), sol::InvalidArgument);
  EXPECT_THROW(sol::geodesics_between({0, 0, 0}, {1, 1, 1}, -1.0), sol::InvalidArgument);
  EXPECT_EQ(sol::distance({1, 2, 3}, {1, 2, 3}), 0.0);
}

}  // namespace
