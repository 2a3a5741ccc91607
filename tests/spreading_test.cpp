// sol::sphere_area_density (J, the spreading of light along geodesics)
// against independent references: central differences of the closed-form
// flow, the small-t expansion from Sol's Ricci curvature, the exact fields
// along the z axis and along the straight lines (with their conjugate
// point), Sol's symmetries, and reciprocity.
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>
#include <sol/sol.hpp>

namespace {

using glm::dvec3;

// J by central differences of sol::flow (the closed form) over two
// orthonormal perturbations of the direction, the end points' differences
// measured in the frame at the end (e^{-z} dx, e^{z} dy, dz). Richardson's
// extrapolation from steps h and h/2 cancels the h² error: the flow's
// derivatives grow like e^{t}, so plain differences at t = 9 keep only
// (h e^8)² (1e-5 at h = 1e-6); extrapolated, (h e^8)^4.
double finite_difference_density(const dvec3& direction, double t, double h) {
  const dvec3 v = glm::normalize(direction);
  // A pair built differently from the library's (any orthonormal pair gives the same area).
  const dvec3 w1 = glm::normalize(glm::cross(v, dvec3(0.3, -0.5, 0.8)));
  const dvec3 w2 = glm::cross(v, w1);
  const double z = sol::flow({dvec3(0.0), v}, t).position.z;
  auto central = [&](const dvec3& w, double step) {
    return (sol::flow({dvec3(0.0), v + step * w}, t).position - sol::flow({dvec3(0.0), v - step * w}, t).position) /
           (2.0 * step);
  };
  auto field = [&](const dvec3& w) {
    const dvec3 d = (4.0 * central(w, 0.5 * h) - central(w, h)) / 3.0;
    return dvec3(std::exp(-z) * d.x, std::exp(z) * d.y, d.z);
  };
  return glm::length(glm::cross(field(w1), field(w2)));
}

dvec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return glm::normalize(dvec3(n(rng), n(rng), n(rng)));
}

TEST(Spreading, MatchesFiniteDifferencesOfTheFlow) {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> length(0.05, 10.0);
  int compared = 0;
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const dvec3 v = random_direction(rng);
    const double t = length(rng);
    const double j = sol::sphere_area_density(v, t);
    // Extrapolated differences at h = 1e-5: truncation (h e^{t-1})^4 <= 1e-7,
    // rounding ~1e-16 |P| / h. Near a conjugate point J is small against its
    // neighbourhood, so the error is taken relative to max(J, t²).
    const double fd = finite_difference_density(v, t, 1e-5);
    const double error = std::abs(j - fd) / std::max({j, t * t, 1e-300});
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-8) << "v = (" << v.x << ", " << v.y << ", " << v.z << "), t = " << t << ": J " << j << ", differences " << fd;
    ++compared;
  }
  std::printf("J against central differences: worst relative error %.2e over %d geodesics\n", worst, compared);
}

// J at a looser tolerance (the path tracer's is 1e-6): within ten times
// that tolerance of the default's (1e-12) over random geodesics up to
// length 6 (measured at 1e-6: 1.1e-6); a tolerance outside [1e-14, 1e-4] is
// refused by name.
TEST(Spreading, ALooserToleranceStaysNearTheDefault) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> length(0.05, 6.0);
  for (const double tolerance : {1e-8, 1e-6}) {
    double worst = 0.0;
    for (int k = 0; k < 100; ++k) {
      const dvec3 v = random_direction(rng);
      const double t = length(rng);
      const double j = sol::sphere_area_density(v, t);
      const double error = std::abs(sol::sphere_area_density(v, t, tolerance) - j) / std::max(j, t * t);
      worst = std::max(worst, error);
      EXPECT_LT(error, 10.0 * tolerance) << "t " << t;
    }
    std::printf("J at tolerance %.0e against 1e-12: worst relative difference %.2e\n", tolerance, worst);
  }
  EXPECT_THROW(sol::sphere_area_density(dvec3(1.0, 0.0, 0.0), 1.0, 1e-3), sol::InvalidArgument);
  EXPECT_THROW(sol::sphere_area_density(dvec3(1.0, 0.0, 0.0), 1.0, 0.0), sol::InvalidArgument);
}

// Directions near the axes and the hyperbolic planes x = 0, y = 0 (a or b
// tiny: the closed form's stiff cases), and inside them.
TEST(Spreading, StiffDirectionsMatchFiniteDifferences) {
  const double tiny[] = {0.0, 1e-9, 1e-6, 1e-3};
  for (double e : tiny) {
    for (const dvec3& v : {dvec3(e, 0.6, 0.8), dvec3(0.6, e, -0.8), dvec3(e, e, 1.0), dvec3(1.0, e, 0.1), dvec3(e, 1.0, e)}) {
      for (double t : {0.5, 2.0, 5.0, 9.0}) {
        const double j = sol::sphere_area_density(v, t);
        const double fd = finite_difference_density(v, t, 1e-5);
        // The differences' own error (h e^{t-1})^4 dominates at t = 9 (8e-6 as a
        // bound, 3e-7 measured; J along the z axis is sinh² t to 1e-10 there).
        EXPECT_LT(std::abs(j - fd) / std::max(j, t * t), std::max(1e-8, std::pow(1e-5 * std::exp(t - 1.0), 4)))
            << "v = (" << v.x << ", " << v.y << ", " << v.z << "), t = " << t << ": J " << j << ", differences " << fd;
      }
    }
  }
}

// J = t² (1 − Ric(v, v) t²/6 + O(t³)) with Ric(v, v) = −2 v3² in Sol.
TEST(Spreading, SmallLengthsFollowTheRicciExpansion) {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 20; ++k) {
    const dvec3 v = random_direction(rng);
    for (double t : {1e-3, 1e-2, 5e-2}) {
      const double j = sol::sphere_area_density(v, t);
      const double expansion = t * t * (1.0 + v.z * v.z * t * t / 3.0);
      // The next term is O(t⁵) (t² times t³ of the curvature's derivative,
      // of size 1 in Sol): 2 t⁵ bounds it; 1e-13 t² for the integration.
      EXPECT_LT(std::abs(j - expansion), 2.0 * std::pow(t, 5) + 1e-13 * t * t) << t;
      // And the t⁴ term is really there: without it the error is of its size.
      if (std::abs(v.z) > 0.5 && t >= 1e-2) {
        EXPECT_GT(std::abs(j - t * t), 0.5 * v.z * v.z * std::pow(t, 4) / 3.0);
      }
    }
  }
  EXPECT_EQ(sol::sphere_area_density(dvec3(0.2, 0.3, 0.4), 0.0), 0.0);
}

// Along the z axis both fields grow in planes of curvature −1: J = sinh² t.
// Along the straight lines (1, ±1, 0)/√2 (u constant) the Jacobi equation
// has constant coefficients; solved by hand (docs/lighting.md):
// det = tS/√2 − 2(1 − C), C = cos √2t, S = sin √2t, conjugate at t = √2π.
TEST(Spreading, ExactFieldsAlongTheAxisAndTheStraightLines) {
  for (double t : {0.1, 1.0, 3.0, 6.0, 10.0}) {
    const double s = std::sinh(t);
    EXPECT_NEAR(sol::sphere_area_density(dvec3(0, 0, 1), t) / (s * s), 1.0, 1e-10) << t;
    EXPECT_NEAR(sol::sphere_area_density(dvec3(0, 0, -1), t) / (s * s), 1.0, 1e-10) << t;
  }
  const double r2 = std::sqrt(2.0), period = r2 * std::numbers::pi;
  auto exact = [&](double t) { return t * std::sin(r2 * t) / r2 - 2.0 * (1.0 - std::cos(r2 * t)); };
  for (const dvec3& v : {dvec3(1, 1, 0), dvec3(1, -1, 0), dvec3(-1, 1, 0)}) {
    for (double t : {0.3, 1.0, 2.0, 3.0, 4.0, period - 0.1, period + 0.1, 6.0, 8.0}) {
      const double j = sol::sphere_area_density(v, t);
      EXPECT_NEAR(j, std::abs(exact(t)), 1e-10 * std::max(1.0, t * t)) << t;
    }
    // The conjugate point: J vanishes there and the determinant changes sign.
    EXPECT_LT(sol::sphere_area_density(v, period), 1e-9);
    EXPECT_GT(sol::jacobi_determinant(v, period - 0.01), 0.0);
    EXPECT_LT(sol::jacobi_determinant(v, period + 0.01), 0.0);
  }
}

// Conjugate points of general geodesics: where the determinant changes
// sign, the differences of the flow too find the area gone (J is 1e-6 of
// its size around it), and on either side they agree with J again.
TEST(Spreading, ConjugatePointsOfGeneralGeodesics) {
  std::mt19937_64 rng(3);
  int found = 0;
  for (int k = 0; k < 40 && found < 8; ++k) {
    const dvec3 v = random_direction(rng);
    double previous = sol::jacobi_determinant(v, 0.05);
    for (double t = 0.1; t <= 10.0; t += 0.05) {
      const double d = sol::jacobi_determinant(v, t);
      if ((d > 0) != (previous > 0)) {
        double lo = t - 0.05, hi = t;  // bisection for the zero
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (lo + hi);
          ((sol::jacobi_determinant(v, mid) > 0) == (previous > 0) ? lo : hi) = mid;
        }
        const double root = 0.5 * (lo + hi);
        const double scale = std::max(sol::sphere_area_density(v, root - 0.05), sol::sphere_area_density(v, root + 0.05));
        EXPECT_LT(finite_difference_density(v, root, 1e-5), 1e-6 * scale) << "t = " << root;
        EXPECT_NEAR(finite_difference_density(v, root + 0.02, 1e-5) / sol::sphere_area_density(v, root + 0.02), 1.0, 1e-6);
        ++found;
        break;
      }
      previous = d;
    }
  }
  EXPECT_GE(found, 4);  // geodesics with u3 oscillating far enough have them within 10
}

// Sol's isometries fixing the origin (x, y, z) → (±x, ±y, z), (±y, ±x, −z)
// act on directions as (±a, ±b, c), (±b, ±a, −c) and leave J unchanged.
// Reciprocity: the same geodesic walked back from its end (direction −u(t)
// there, left-translated to the origin) has the same J.
TEST(Spreading, SymmetriesAndReciprocity) {
  std::mt19937_64 rng(11);
  for (int k = 0; k < 30; ++k) {
    const dvec3 v = random_direction(rng);
    const double t = 0.2 + 7.0 * (k / 30.0);
    const double j = sol::sphere_area_density(v, t);
    for (const dvec3& image : {dvec3(-v.x, v.y, v.z), dvec3(v.x, -v.y, v.z), dvec3(-v.x, -v.y, v.z), dvec3(v.y, v.x, -v.z),
                               dvec3(-v.y, v.x, -v.z), dvec3(v.y, -v.x, -v.z), dvec3(-v.y, -v.x, -v.z)}) {
      EXPECT_NEAR(sol::sphere_area_density(image, t) / j, 1.0, 1e-9) << k;
    }
    const dvec3 back = -sol::flow({dvec3(0.0), v}, t).direction;
    EXPECT_NEAR(sol::sphere_area_density(back, t) / j, 1.0, 1e-8) << k;
  }
}

// The float method (the kernel's RK4 in steps of kSpreadingStep) against
// double: relative 1e-4 of max(J, t²) up to t = 6 (RK4's error h⁴ = 1e-4
// times the fields' fifth derivatives over their size, of order 1, and
// float rounding over 60 steps; measured 1.1e-5).
TEST(Spreading, FloatMethodAgreesWithDouble) {
  std::mt19937_64 rng(5);
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    const dvec3 v = random_direction(rng);
    const double t = 0.01 + 6.0 * (k % 100) / 100.0;
    const double j = sol::sphere_area_density(v, t);
    const float f = sol::sphere_area_density(glm::vec3(v), static_cast<float>(t));
    const double error = std::abs(f - j) / std::max(j, t * t);
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-4) << t;
  }
  std::printf("float J against double: worst relative error %.2e\n", worst);
}

TEST(Spreading, BadInputIsRefused) {
  EXPECT_THROW(sol::sphere_area_density(dvec3(0.0), 1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::sphere_area_density(dvec3(1.0, 0.0, std::nan("")), 1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::sphere_area_density(dvec3(1.0, 0.0, 0.0), -1.0), sol::InvalidArgument);
  EXPECT_THROW(sol::sphere_area_density(dvec3(1.0, 0.0, 0.0), std::numeric_limits<double>::infinity()), sol::InvalidArgument);
  EXPECT_THROW(sol::sphere_area_density(glm::vec3(0.0f), 1.0f), sol::InvalidArgument);
  EXPECT_EQ(sol::clamped_spreading(0.0), sol::kernel::kMinSpreading);
  EXPECT_EQ(sol::clamped_spreading(2.0), 2.0);
}

}  // namespace
