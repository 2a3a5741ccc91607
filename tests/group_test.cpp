// Group law, inverse, frame conversions and left-invariance of the metric.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using glm::dvec3;

double rel_diff(const dvec3& a, const dvec3& b) {
  const dvec3 d = glm::abs(a - b);
  const double scale = std::max({1.0, std::abs(b.x), std::abs(b.y), std::abs(b.z)});
  return std::max({d.x, d.y, d.z}) / scale;
}

dvec3 random_point(std::mt19937_64& rng, double xy = 5.0, double z = 3.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {xy * u(rng), xy * u(rng), z * u(rng)};
}

// The metric e^{-2z}dx^2 + e^{2z}dy^2 + dz^2 at p on coordinate vectors.
double metric(const dvec3& p, const dvec3& v, const dvec3& w) {
  return std::exp(-2 * p.z) * v.x * w.x + std::exp(2 * p.z) * v.y * w.y + v.z * w.z;
}

TEST(Group, IdentityAndInverse) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 1000; ++i) {
    const dvec3 p = random_point(rng);
    EXPECT_EQ(sol::multiply(p, dvec3(0.0)), p);
    EXPECT_EQ(sol::multiply(dvec3(0.0), p), p);
    EXPECT_LT(rel_diff(sol::multiply(p, sol::inverse(p)), dvec3(0.0)), 1e-13);
    EXPECT_LT(rel_diff(sol::multiply(sol::inverse(p), p), dvec3(0.0)), 1e-13);
    EXPECT_LT(rel_diff(sol::inverse(sol::inverse(p)), p), 1e-13);
  }
}

TEST(Group, Associative) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 1000; ++i) {
    const dvec3 p = random_point(rng), q = random_point(rng), r = random_point(rng);
    const dvec3 left = sol::multiply(sol::multiply(p, q), r);
    const dvec3 right = sol::multiply(p, sol::multiply(q, r));
    EXPECT_LT(rel_diff(left, right), 1e-12) << "p=" << p.x << "," << p.y << "," << p.z;
  }
}

TEST(Group, NotCommutative) {
  // Sol is not abelian: (0,0,1)*(1,0,0) = (e,0,1) but (1,0,0)*(0,0,1) = (1,0,1).
  const dvec3 a = sol::multiply({0, 0, 1}, {1, 0, 0});
  const dvec3 b = sol::multiply({1, 0, 0}, {0, 0, 1});
  EXPECT_NEAR(a.x, std::exp(1.0), 1e-15);
  EXPECT_NEAR(b.x, 1.0, 1e-15);
}

// Left translation L_g is an isometry: pull the metric back through a
// central-difference Jacobian of L_g (independent of the frame formulas).
TEST(Group, MetricIsLeftInvariant) {
  std::mt19937_64 rng(3);
  const double h = 1e-5;
  for (int i = 0; i < 200; ++i) {
    const dvec3 g = random_point(rng), p = random_point(rng);
    const dvec3 v = random_point(rng, 1.0, 1.0), w = random_point(rng, 1.0, 1.0);
    auto push = [&](const dvec3& u) {
      return (sol::multiply(g, p + h * u) - sol::multiply(g, p - h * u)) / (2 * h);
    };
    const dvec3 gp = sol::multiply(g, p);
    const double before = metric(p, v, w);
    const double after = metric(gp, push(v), push(w));
    // Central differences of an exponential: error ~ h^2 |L'''| ~ 1e-10 relative to the scale.
    const double scale = std::sqrt(metric(p, v, v) * metric(p, w, w));
    EXPECT_NEAR(after, before, 1e-7 * scale) << "i=" << i;
  }
}

TEST(Group, FrameConversionsRoundTripAndAreOrthonormal) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 500; ++i) {
    const dvec3 p = random_point(rng), f = random_point(rng, 1.0, 1.0), g = random_point(rng, 1.0, 1.0);
    const dvec3 vf = sol::velocity_from_frame(p, f), vg = sol::velocity_from_frame(p, g);
    EXPECT_LT(rel_diff(sol::frame_from_velocity(p, vf), f), 1e-14);
    // The frame is orthonormal: the metric of the velocities is the dot product of the components.
    EXPECT_NEAR(metric(p, vf, vg), glm::dot(f, g), 1e-12 * (1 + glm::length(f) * glm::length(g)));
  }
}

// The frame is left-invariant: dL_g maps the velocity of frame components f
// at p to the velocity of the same components at g*p.
TEST(Group, FrameIsLeftInvariant) {
  std::mt19937_64 rng(5);
  const double h = 1e-6;
  for (int i = 0; i < 200; ++i) {
    const dvec3 g = random_point(rng), p = random_point(rng), f = random_point(rng, 1.0, 1.0);
    const dvec3 v = sol::velocity_from_frame(p, f);
    const dvec3 pushed = (sol::multiply(g, p + h * v) - sol::multiply(g, p - h * v)) / (2 * h);
    const dvec3 expected = sol::velocity_from_frame(sol::multiply(g, p), f);
    EXPECT_LT(rel_diff(pushed, expected), 1e-7);
  }
}

TEST(Group, RejectsNonFiniteInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(sol::multiply({nan, 0, 0}, {0, 0, 0}), sol::InvalidArgument);
  EXPECT_THROW(sol::multiply({0, 0, 0}, {0, 0, inf}), sol::InvalidArgument);
  EXPECT_THROW(sol::inverse({0, -inf, 0}), sol::InvalidArgument);
  EXPECT_THROW(sol::velocity_from_frame({0, 0, nan}, {1, 0, 0}), sol::InvalidArgument);
  EXPECT_THROW(sol::frame_from_velocity({0, 0, 0}, {nan, 0, 0}), sol::InvalidArgument);
  // The error type is a std::invalid_argument and names the function.
  try {
    sol::inverse({nan, 0, 0});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sol::inverse"), std::string::npos);
  }
}

}  // namespace

// Finite arguments whose result overflows double are refused (OutOfRange,
// naming the function) rather than answered with inf or NaN: the group
// law past e^{709}, a geodesic from a start that far, the connection to a
// point at 1e308, a sphere around a centre at height 1000 and the word of
// a teleport whose integers double cannot hold exactly. Points just
// inside stay answered, finite.
TEST(Group, ResultsThatOverflowDoubleAreRefused) {
  using glm::dvec3;
  EXPECT_THROW(sol::multiply({0, 0, 800}, {1e300, 0, 0}), sol::OutOfRange);
  EXPECT_THROW(sol::inverse({1e300, 0, -800}), sol::OutOfRange);
  EXPECT_THROW(sol::velocity_from_frame({0, 0, 710}, {1, 0, 0}), sol::OutOfRange);
  EXPECT_THROW(sol::frame_from_velocity({0, 0, -710}, {1, 0, 0}), sol::OutOfRange);
  EXPECT_THROW(sol::flow({{0, 0, 1000}, {1, 0, 0}}, 1.0), sol::OutOfRange);
  EXPECT_THROW(sol::minimising_geodesics({0, 0, 0}, {1e308, 0, 0}), sol::OutOfRange);
  EXPECT_THROW(sol::geodesic_sphere({0, 0, 1000}, 1.0, 8), sol::OutOfRange);
  EXPECT_THROW(sol::Lattice::golden().word_of(sol::Lattice::golden().teleport({1e30, 0, 0}).element), sol::OutOfRange);
  try {
    (void)sol::flow({{0, 0, 1000}, {1, 0, 0}}, 1.0);
  } catch (const sol::OutOfRange& e) {
    EXPECT_NE(std::string(e.what()).find("sol::flow"), std::string::npos) << e.what();
  }
  // Inside: finite answers.
  const dvec3 p = sol::multiply({0, 0, 700}, {1, 0, 0});
  EXPECT_TRUE(std::isfinite(p.x) && p.x > 1e303);
  EXPECT_TRUE(std::isfinite(sol::flow({{0, 0, 500}, {1, 0, 0}}, 1.0).position.x));
  for (const sol::Connection& c : sol::minimising_geodesics({0, 0, 0}, {1e6, 0, 0})) EXPECT_TRUE(std::isfinite(c.length));
  const sol::Teleport t = sol::Lattice::golden().teleport({1e12, 0, 0});
  EXPECT_TRUE(sol::Lattice::golden().contains(t.point));
}
