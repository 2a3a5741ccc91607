// The Vulkan kernels on lavapipe against libsol: the kernel's float closed
// form against the double closed form (itself tested against a 50-digit
// reference), and every preset's image and AOVs against the CPU reference
// renderer. Runs with validation on; any validation error fails.
#include <algorithm>
#include <functional>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <sol/sol.hpp>
#include <sol/vk/context.hpp>
#include <sol/vk/image.hpp>
#include <sol/vk/kernel_probes.hpp>
#include <sol/vk/march.hpp>
#include <sol/vk/march_interface.h>
#include <sol/vk/pipeline.hpp>

#include "srgb.hpp"
#include "support/boxes.hpp"
#include "support/directions.hpp"
#include "support/extremes.hpp"
#include "support/kernel.hpp"
#include "support/loops.hpp"
#include "support/mirrors.hpp"
#include "support/paths.hpp"
#include "support/sweep.hpp"

namespace {

using glm::dvec3;
using sol::test::expect_no_validation_errors;
using sol::test::vk_context;

// μ = |ab| of the unit direction along f, as the kernel's sol_ray takes it
// (the quotient march's choice of positions: kZetaLeastMu).
double mu_of(const glm::vec3& f) {
  const dvec3 d = glm::normalize(dvec3(f));
  return std::abs(d.x * d.y);
}

// 10^5 (direction, arc length) pairs: random directions and the stiff set,
// |t| <= 50; the reference is the double closed form for the float-rounded
// direction and arc length.
TEST(Kernel, FlowMatchesTheDoubleClosedForm) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(2000, 31)) dirs.push_back(d);
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> arc(-50.0, 50.0);
  std::vector<glm::vec4> queries;
  while (queries.size() < 100000) {
    for (const dvec3& d : dirs) {
      if (queries.size() == 100000) break;
      queries.emplace_back(glm::vec3(d), static_cast<float>(arc(rng)));
    }
  }
  const std::vector<glm::vec4> results = sol::vk::evaluate_kernel_flow(vk_context(), queries);
  double worst = 0, worst_height = 0;
  std::size_t worst_at = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const dvec3 d(queries[i].x, queries[i].y, queries[i].z);
    const double t = queries[i].w;
    const dvec3 ref = sol::ClosedFormGeodesic<double>(d).at(t).position;
    const dvec3 got(results[i].x, results[i].y, results[i].z);
    const double e = sol::test::scaled_error(got, ref);
    if (!(e <= worst)) {
      worst = e;
      worst_at = i;
    }
    worst_height = std::max(worst_height, std::abs(results[i].w - ref.z) / std::max(1.0, std::abs(ref.z)));
  }
  const glm::vec4 q = queries[worst_at];
  std::printf("kernel flow (float) vs double closed form, 1e5 queries, |t| <= 50: worst %.3e at (%.9g, %.9g, %.9g), "
              "t = %g; height-only path %.3e\n",
              worst, q.x, q.y, q.z, q.w, worst_height);
  // Float rounding of u = λt + u0 at |t| = 50 alone is ~50·6e-8 relative in
  // the phase; 5e-5 leaves room for the float AGM and Carlson pieces.
  EXPECT_LT(worst, 5e-5);
  EXPECT_LT(worst_height, 5e-5);
  expect_no_validation_errors();
}

// The quotient march restarts its ray at every teleport by advancing it
// along the same geodesic (sol_ray_advanced): walked in 2, 5 and 20
// segments, the composed positions stay on the double closed form's
// geodesic as the direct evaluation does (|t| <= 12, the quotient presets'
// max_distance; random and stiff directions).
TEST(Kernel, FlowWalkedInSegmentsStaysOnTheGeodesic) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(1000, 33)) dirs.push_back(d);
  std::mt19937_64 rng(34);
  std::uniform_real_distribution<double> arc(-12.0, 12.0);
  std::vector<glm::vec4> queries;
  for (const dvec3& d : dirs) queries.emplace_back(glm::vec3(d), static_cast<float>(arc(rng)));
  // Steep rays (|a|, |b| below 2e-3) restarted before and after they cross
  // the middle of their oscillation (e^{w} = 1, z' = ±kλ ≈ ±1, at
  // z = -w0 = ½ ln(|b/a|): ±0.58 for |a| : |b| = 0.3 : 0.95), where the
  // restarted ray's coordinate taken by Carlson changes (sol_ray_restarted
  // then uses the other coordinate's piece, from the first integral).
  for (double c : {1.0 - 1e-6, 1.0 - 1e-12, -(1.0 - 1e-6), -(1.0 - 1e-12)}) {
    for (const glm::dvec2 ab : {glm::dvec2(0.3, 0.95), glm::dvec2(-0.95, 0.3), glm::dvec2(0.95, -0.3)}) {
      for (double t : {0.05, 0.1, 0.2, 0.4, 0.8, 1.6, 3.2}) {
        queries.emplace_back(glm::vec3(sol::test::direction_with_c(ab.x, ab.y, c)), static_cast<float>(t));
      }
    }
  }
  for (int segments : {2, 5, 20}) {
    const std::vector<glm::vec4> results = sol::vk::evaluate_kernel_flow(vk_context(), queries, segments);
    double worst = 0, worst_forward = 0;  // forward: restarted by sol_ray_restarted, backward by sol_ray_advanced
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const dvec3 d(queries[i].x, queries[i].y, queries[i].z);
      const dvec3 ref = sol::ClosedFormGeodesic<double>(d).at(queries[i].w).position;
      const double e = sol::test::scaled_error(dvec3(results[i].x, results[i].y, results[i].z), ref);
      worst = std::max(worst, e);
      if (queries[i].w >= 0) worst_forward = std::max(worst_forward, e);
    }
    std::printf("kernel flow in %d segments, %zu queries, |t| <= 12: worst %.3e (forward, sol_ray_restarted: %.3e)\n",
                segments, queries.size(), worst, worst_forward);
    EXPECT_LT(worst, 5e-5) << segments << " segments";
    EXPECT_LT(worst_forward, 5e-5) << segments << " segments";
  }
  expect_no_validation_errors();
}

// The quotient march's first pass takes its positions from Jacobi's zeta
// function (sol_forward_zeta) for rays of μ = |ab| >= kZetaLeastMu, walked
// in segments as it restarts its rays at teleports (sol_ray_restarted_zeta):
// against the double closed form. Directions: random ones of μ >=
// kZetaLeastMu, μ just above it at several c, μ on both sides of 1/6 (m =
// (1 - 2μ)/(1 + 2μ) = 1/2, where the descent's modulus and its
// complement's cross), the straight lines (μ = 1/2) and a ≈ ±b with c ≈ 0
// (m near 0); arc lengths up to 12, the quotient presets' max_distance,
// with short ones, whose segments take the trapezoid rule. The float
// rounding of the integrals is about 2e-7/μ relative a segment (measured,
// worst at μ near 0.01: 5.8e-6 in one segment, 3.3e-5 in 20); 5e-5 is the
// Carlson flow's goal (FlowWalkedInSegmentsStaysOnTheGeodesic).
TEST(Kernel, FlowByZetaMatchesTheDoubleClosedFormAboveItsLeastMu) {
  const double least = sol::vk::kernel::kZetaLeastMu;
  const auto direction_with_mu = [](double mu, double c, double sign_a, double sign_b) {
    const double h2 = (1.0 - c) * (1.0 + c), half = 0.5 * std::asin(std::min(1.0, 2.0 * mu / h2));
    const double h = std::sqrt(h2);
    return dvec3(sign_a * h * std::cos(half), sign_b * h * std::sin(half), c);
  };
  std::vector<dvec3> dirs;
  for (const dvec3& d : sol::test::stiff_directions()) {
    if (mu_of(glm::vec3(d)) >= least) dirs.push_back(d);
  }
  for (const dvec3& d : sol::test::random_directions(3000, 43)) {
    if (mu_of(glm::vec3(d)) >= least) dirs.push_back(d);
  }
  for (double c : {-0.95, -0.6, -0.2, 0.0, 0.3, 0.7, 0.97}) {
    for (double mu : {least * 1.0001, 1.0 / 6.0 - 1e-4, 1.0 / 6.0 + 1e-4}) {
      if (2.0 * mu > (1.0 - c) * (1.0 + c)) continue;
      dirs.push_back(direction_with_mu(mu, c, 1.0, 1.0));
      dirs.push_back(direction_with_mu(mu, c, -1.0, 1.0));
      dirs.push_back(direction_with_mu(mu, c, 1.0, -1.0));
    }
  }
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> arc(0.0, 12.0);
  std::vector<glm::vec4> queries;
  for (const dvec3& d : dirs) {
    if (mu_of(glm::vec3(d)) < least) continue;  // (rounded below it)
    for (const double t : {0.0, 1e-3, 0.05, 1.0, 12.0, arc(rng), arc(rng)}) queries.emplace_back(glm::vec3(d), static_cast<float>(t));
  }
  for (int segments : {1, 2, 5, 20}) {
    const std::vector<glm::vec4> results = sol::vk::evaluate_kernel_flow_by_zeta(vk_context(), queries, segments);
    double worst = 0;
    std::size_t worst_at = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const dvec3 d(queries[i].x, queries[i].y, queries[i].z);
      const dvec3 ref = sol::ClosedFormGeodesic<double>(d).at(queries[i].w).position;
      const double e = sol::test::scaled_error(dvec3(results[i].x, results[i].y, results[i].z), ref);
      if (!(e <= worst)) {
        worst = e;
        worst_at = i;
      }
    }
    const glm::vec4 q = queries[worst_at];
    std::printf("kernel flow by the zeta function in %d segments, %zu queries (mu >= %g), t <= 12: worst %.3e at mu %.3g, t = %g\n",
                segments, queries.size(), least, worst, mu_of(glm::vec3(q)), q.w);
    EXPECT_LT(worst, 5e-5) << segments << " segments";
  }
  EXPECT_THROW(sol::vk::evaluate_kernel_flow_by_zeta(vk_context(), {glm::vec4(0.6f, 0.8f, 0, -1)}), sol::InvalidArgument);
  EXPECT_THROW(sol::vk::evaluate_kernel_flow_by_zeta(vk_context(), queries, 0), sol::InvalidArgument);
  expect_no_validation_errors();
}

// The tangent the quotient march takes for its clearances (sol_forward's
// direction; sol_forward_zeta's where μ >= kZetaLeastMu, below) against
// the double closed form's, in every regime: random
// and stiff directions, the planes x = 0 and y = 0 (a or b zero), the
// vertical and the straight lines, t in [0, 12] (the quotient presets'
// max_distance). The tangent's float error follows the phase's, like the
// position's (5e-5 at t = 50 in FlowMatchesTheDoubleClosedForm).
TEST(Kernel, TangentsMatchTheDoubleClosedForm) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(1000, 35)) dirs.push_back(d);
  for (const dvec3& d : {dvec3(0, 0.6, 0.8), dvec3(0, -0.6, -0.8), dvec3(0.28, 0, 0.96), dvec3(-1, 0, 0), dvec3(0, 0, 1),
                         dvec3(0, 0, -1), glm::normalize(dvec3(1, 1, 0)), glm::normalize(dvec3(-1, 1, 0))}) {
    dirs.push_back(d);
  }
  std::vector<glm::vec4> queries;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    for (const double t : {0.0, 0.05, 0.4, 1.7, 12.0 * static_cast<double>(i % 41) / 40.0}) {
      queries.emplace_back(glm::vec3(dirs[i]), static_cast<float>(t));
    }
  }
  const std::vector<glm::vec4> results = sol::vk::evaluate_kernel_tangents(vk_context(), queries);
  double worst = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const dvec3 d(queries[i].x, queries[i].y, queries[i].z);
    const dvec3 ref = sol::ClosedFormGeodesic<double>(d).direction_at(queries[i].w);
    const double error = glm::length(dvec3(results[i]) - ref);
    worst = std::max(worst, error);
    EXPECT_LT(error, 5e-5) << "(" << d.x << ", " << d.y << ", " << d.z << "), t = " << queries[i].w;
  }
  std::printf("kernel tangents (float) against double, %zu queries, t <= 12: worst %.2e\n", queries.size(), worst);
  EXPECT_THROW(sol::vk::evaluate_kernel_tangents(vk_context(), {glm::vec4(1, 0, 0, -1)}), sol::InvalidArgument);
  // The quotient march's first pass: the tangent by the zeta function's
  // descent (five levels, dn from its last level) for the directions of
  // μ >= kZetaLeastMu, to the same bound.
  std::vector<glm::vec4> steep;
  for (const glm::vec4& q : queries) {
    if (mu_of(glm::vec3(q)) >= sol::vk::kernel::kZetaLeastMu) steep.push_back(q);
  }
  const std::vector<glm::vec4> by_zeta = sol::vk::evaluate_kernel_tangents_by_zeta(vk_context(), steep);
  double worst_zeta = 0.0;
  for (std::size_t i = 0; i < steep.size(); ++i) {
    const dvec3 d(steep[i].x, steep[i].y, steep[i].z);
    const double error = glm::length(dvec3(by_zeta[i]) - sol::ClosedFormGeodesic<double>(d).direction_at(steep[i].w));
    worst_zeta = std::max(worst_zeta, error);
    EXPECT_LT(error, 5e-5) << "by the zeta function: (" << d.x << ", " << d.y << ", " << d.z << "), t = " << steep[i].w;
  }
  std::printf("kernel tangents by the zeta function, %zu queries (mu >= %g): worst %.2e\n", steep.size(),
              static_cast<double>(sol::vk::kernel::kZetaLeastMu), worst_zeta);
  EXPECT_THROW(sol::vk::evaluate_kernel_tangents_by_zeta(vk_context(), {glm::vec4(0.6f, 0.8f, 0, -1)}), sol::InvalidArgument);
  expect_no_validation_errors();
}

// The cut time that certifies the exact lights' minimisers (sol_cut_time)
// against libsol's sol::cut_time (itself tested against where a geodesic
// and its mirror meet): random and stiff directions, the straight lines
// (√2 π) and, where ab = 0, infinite (1e30 in the kernel).
TEST(Kernel, CutTimesMatchLibsol) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(2000, 37)) dirs.push_back(d);
  for (const dvec3& d : {glm::normalize(dvec3(1, 1, 0)), dvec3(0, 0.6, 0.8), dvec3(1, 0, 0), dvec3(0, 0, -1)}) dirs.push_back(d);
  std::vector<glm::vec3> queries;
  for (const dvec3& d : dirs) queries.emplace_back(d);
  const std::vector<float> got = sol::vk::evaluate_kernel_cut_times(vk_context(), queries);
  double worst = 0.0;
  int infinite = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const double ref = sol::cut_time(dvec3(queries[i]));
    if (std::isinf(ref)) {
      ++infinite;
      EXPECT_GE(got[i], 1e30f) << i;
      continue;
    }
    // Float: the AGM's K to a few ulps, and K grows like log(1/|ab|) where
    // |ab| is small (the stiff set down to 1e-12).
    const double error = std::abs(got[i] - ref) / ref;
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-5) << "(" << dirs[i].x << ", " << dirs[i].y << ", " << dirs[i].z << "): " << got[i] << " vs " << ref;
  }
  std::printf("kernel cut times against libsol, %zu directions (%d infinite): worst relative error %.2e\n", dirs.size(),
              infinite, worst);
  EXPECT_GE(infinite, 3);
  EXPECT_THROW(sol::vk::evaluate_kernel_cut_times(vk_context(), {glm::vec3(0.0f)}), sol::InvalidArgument);
  expect_no_validation_errors();
}

// The kernel's J (sol_spreading.glsl) against libsol's double
// sphere_area_density for random and stiff directions, t in (0, 6]: the
// float method's tolerance (relative 1e-4 of max(J, t²),
// Spreading.FloatMethodAgreesWithDouble), doubled for the device's own
// float rounding (fused multiply-adds, reassociation).
TEST(Kernel, SpreadingMatchesTheDoubleReference) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(300, 41)) dirs.push_back(d);
  std::vector<glm::vec4> queries;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    queries.emplace_back(glm::vec3(dirs[i]), static_cast<float>(0.01 + 6.0 * static_cast<double>(i % 97) / 97.0));
  }
  const std::vector<float> results = sol::vk::evaluate_kernel_spreading(vk_context(), queries);
  double worst = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const dvec3 d(queries[i].x, queries[i].y, queries[i].z);
    const double t = queries[i].w;
    const double j = sol::sphere_area_density(d, t);
    const double error = std::abs(results[i] - j) / std::max(j, t * t);
    worst = std::max(worst, error);
    EXPECT_LT(error, 2e-4) << "(" << d.x << ", " << d.y << ", " << d.z << "), t = " << t << ": kernel " << results[i]
                           << ", libsol " << j;
  }
  std::printf("kernel J (float) against double, %zu queries, t <= 6: worst relative error %.2e\n", queries.size(), worst);
  expect_no_validation_errors();
}

// The kernel's Jacobian of the exponential map (sol_exp_jacobian: Jacobi
// fields by RK4, the connection solver's Newton steps) against central
// differences of libsol's double flow (h = 1e-4: truncation ~1e-8, rounding
// ~1e-12), in frame components at the end point, for random and stiff
// directions, t in (0, 4]. Newton's steps need it only approximately (an
// error ε slows quadratic convergence to a rate of about ε; the connections'
// accuracy is Kernel.ConnectionsMatchTheMinimisers'), but an error here
// beyond RK4's own would be a wrong equation: the bound is about 3x the
// worst measured, relative to max(1, |J|).
TEST(Kernel, ExpJacobianMatchesDifferences) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(300, 43)) dirs.push_back(d);
  std::vector<glm::vec4> queries;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    queries.emplace_back(glm::vec3(dirs[i]), static_cast<float>(0.01 + 4.0 * static_cast<double>(i % 89) / 89.0));
  }
  const std::vector<glm::mat3> got = sol::vk::evaluate_kernel_exp_jacobians(vk_context(), queries);
  ASSERT_EQ(got.size(), queries.size());
  const auto exp_map = [](const dvec3& v) { return sol::flow({dvec3(0.0), glm::normalize(v)}, glm::length(v)).position; };
  double worst = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const dvec3 v = glm::normalize(dvec3(glm::vec3(queries[i]))) * static_cast<double>(queries[i].w);
    const dvec3 end = exp_map(v);
    const dvec3 to_frame(std::exp(-end.z), std::exp(end.z), 1.0);
    const double h = 1e-4;
    glm::dmat3 ref;
    for (int c = 0; c < 3; ++c) {
      dvec3 e(0.0);
      e[c] = h;
      ref[c] = (exp_map(v + e) - exp_map(v - e)) / (2.0 * h) * to_frame;
    }
    double size = 1.0, error = 0.0;
    for (int c = 0; c < 3; ++c) {
      size = std::max(size, glm::length(ref[c]));
      error = std::max(error, glm::length(dvec3(got[i][c]) - ref[c]));
    }
    worst = std::max(worst, error / size);
    EXPECT_LT(error / size, 2e-3) << "v = (" << v.x << ", " << v.y << ", " << v.z << ")";
  }
  std::printf("kernel exp Jacobian (float, RK4) against double differences, %zu queries, t <= 4: worst relative error %.2e\n",
              queries.size(), worst);
  EXPECT_THROW(sol::vk::evaluate_kernel_exp_jacobians(vk_context(), {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)}),
               sol::InvalidArgument);
  expect_no_validation_errors();
}

// The end point and tangent that the kernel's RK4 carries along with J
// (sol_spread: where a glowing ball's sampled point lies and its normal)
// against the double closed form (sol::flow), for random and stiff
// directions, t in (0, 6]. RK4 in float, steps of at most kSpreadingStep:
// measured worst 5.4e-6 of max(1, |position|) for positions and 8.9e-6
// for unit tangents on lavapipe; the bound 3e-5 leaves room for another
// device's rounding and is far below what the path kernel's checks of a
// sampled point allow (1e-3 of the length), while an equation wrong in any
// term (a sign, a frame factor) misses by O(t).
TEST(Kernel, SpreadEndsMatchTheClosedForm) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(300, 47)) dirs.push_back(d);
  std::vector<glm::vec4> queries;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    queries.emplace_back(glm::vec3(dirs[i]), static_cast<float>(0.01 + 6.0 * static_cast<double>(i % 89) / 89.0));
  }
  const auto got = sol::vk::evaluate_kernel_spread_ends(vk_context(), queries);
  double worst_position = 0.0, worst_direction = 0.0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const dvec3 d = glm::normalize(dvec3(glm::vec3(queries[i])));
    const sol::GeodesicState end = sol::flow({dvec3(0.0), d}, static_cast<double>(queries[i].w));
    const double position = glm::length(dvec3(got[i].first) - end.position) / std::max(1.0, glm::length(end.position));
    const double direction = glm::length(dvec3(got[i].second) - end.direction);
    worst_position = std::max(worst_position, position);
    worst_direction = std::max(worst_direction, direction);
    EXPECT_LT(position, 3e-5) << "d = (" << d.x << ", " << d.y << ", " << d.z << "), t = " << queries[i].w;
    EXPECT_LT(direction, 3e-5) << "d = (" << d.x << ", " << d.y << ", " << d.z << "), t = " << queries[i].w;
  }
  std::printf("kernel spread ends (float, RK4) against the double closed form, %zu queries, t <= 6: worst position %.2e, "
              "tangent %.2e\n",
              queries.size(), worst_position, worst_direction);
  EXPECT_THROW(sol::vk::evaluate_kernel_spread_ends(vk_context(), {glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)}), sol::InvalidArgument);
  expect_no_validation_errors();
}

// The kernel's series of the logarithm (sol_log_series in float, where its
// exact balls' Newton solves start) at w = exp(v), the double flow from the
// origin along random and stiff directions for lengths up to where w
// leaves the series' reach: v again within the series' own 5e-5
// (Connection.LogSeriesInvertsTheExponentialMap, in double) and the float
// rounding of w and of about 250 products (1e-6), and within that rounding
// of libsol's double evaluation of the same header.
TEST(Kernel, LogSeriesInvertsTheExponentialMap) {
  std::vector<dvec3> dirs = sol::test::stiff_directions();
  for (const dvec3& d : sol::test::random_directions(400, 47)) dirs.push_back(d);
  std::vector<glm::vec3> targets;
  std::vector<dvec3> starts;
  for (const dvec3& d : dirs) {
    for (int i = 1; i <= 16; ++i) {
      const double t = 0.05 * i;
      const glm::vec3 w(sol::flow({dvec3(0.0), d}, t).position);  // (the reach holds for the float target too)
      if (!(glm::length(dvec3(w)) < sol::kernel::kLogSeriesReach)) break;
      targets.push_back(w);
      starts.push_back(t * d);
    }
  }
  ASSERT_GT(targets.size(), 4000u);
  const std::vector<glm::vec3> got = sol::vk::evaluate_kernel_log_series(vk_context(), targets);
  ASSERT_EQ(got.size(), targets.size());
  double worst = 0.0, worst_rounding = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const double error = glm::length(dvec3(got[i]) - starts[i]);
    const double rounding = glm::length(dvec3(got[i]) - sol::log_series(dvec3(targets[i])));
    worst = std::max(worst, error);
    worst_rounding = std::max(worst_rounding, rounding);
    EXPECT_LT(error, 5e-5 + 1e-6) << "v = (" << starts[i].x << ", " << starts[i].y << ", " << starts[i].z << ")";
    EXPECT_LT(rounding, 1e-6) << i;
  }
  std::printf("kernel log series (float) at exp(v), %zu targets: worst |log - v| %.2e, against the double series %.2e\n",
              targets.size(), worst, worst_rounding);
  expect_no_validation_errors();
}

// The kernel against the CPU renderer (or another kernel render): colours
// count as different beyond 2e-3 per channel.
using Comparison = sol::test::ImageComparison;
Comparison compare(const sol::RenderResult& gpu, const sol::RenderResult& cpu) {
  return sol::test::compare_images(gpu, cpu, 2e-3f);
}

// The least distance bound from p (a hit point as the renderers report it:
// world coordinates, in D for the quotient) to the object `object`
// (1-based) of the prepared world, by the double bounds.
double surface_gap(const sol::MarchWorld& world, int object, const dvec3& p) {
  double least = 1e300;
  for (const sol::MarchObject& m : world.objects()) {
    if (static_cast<int>(m.owner) == object - 1) least = std::min(least, sol::object_distance(m, p));
  }
  return least;
}

TEST(Kernel, PresetsMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const std::string& name : sol::preset_names()) {
    const sol::Scene scene = sol::preset_scene(name);
    // Exact balls (the kernel's table) and lights: tests ExactBalls* and ExactLights*.
    if (sol::uses_exact(scene)) continue;
    sol::RenderOptions settings;
    settings.width = 48;
    settings.height = 32;
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const sol::RenderResult gpu = sol::test::render(renderer, scene, settings.width, settings.height);
    for (float v : gpu.rgba) ASSERT_TRUE(std::isfinite(v)) << name;
    const Comparison c = compare(gpu, cpu);
    std::printf("%s: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n",
                name.c_str(), c.mask_differs, c.pixels, c.color_differs, c.distance);
    // Float against double: a ray grazing an object or a disc edge may go
    // either way (at most 1% of pixels); where both hit, the arc lengths agree
    // to the hit epsilon (5e-5) plus float rounding of t (~30·6e-8), and the
    // colours to 2e-3 (fog and Lambert change by less for such a distance).
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
    // Where the arc lengths differ by more (a ray meeting a surface at a
    // grazing angle is within hit_epsilon of it over a longer stretch, and
    // float and double may stop at different steps of it; seen in
    // lattice-balls: 1.2e-3 at an angle of about 2 degrees), the kernel's
    // hit point must still lie within hit_epsilon of the object's surface by
    // the double bounds (less float rounding of the point, 1e-5), at no more
    // than 1% of the pixels.
    const sol::MarchWorld world(scene);
    int grazing = 0;
    for (int k = 0; k < c.pixels; ++k) {
      const auto i = static_cast<std::size_t>(k);
      if (gpu.object[i] == 0 || gpu.object[i] != cpu.object[i] || std::abs(gpu.distance[i] - cpu.distance[i]) < 1e-3) {
        continue;
      }
      ++grazing;
      const double gap = surface_gap(world, static_cast<int>(gpu.object[i]), dvec3(gpu.px[i], gpu.py[i], gpu.pz[i]));
      EXPECT_GT(gap, -1e-5) << name << " pixel " << k;
      EXPECT_LT(gap, scene.hit_epsilon + 1e-5) << name << " pixel " << k;
      EXPECT_LT(std::abs(gpu.distance[i] - cpu.distance[i]), 0.05) << name << " pixel " << k;
    }
    EXPECT_LE(grazing, c.pixels / 100) << name;
    if (scene.quotient() != sol::Quotient::None) {
      // The kernel marches as the CPU does, by the same field and the same
      // clearances (sol/clearance.hpp): its mean steps per ray within 2 %
      // of the CPU's (float rounding moves a few steps; measured: equal to
      // two decimals; with the kernel's ball clearance cut to the bound,
      // lattice-balls took 1.37 times as many).
      double cpu_steps = 0.0, gpu_steps = 0.0;
      for (std::size_t k = 0; k < cpu.steps.size(); ++k) {
        cpu_steps += cpu.steps[k];
        gpu_steps += gpu.steps[k];
      }
      std::printf("%s: %.2f steps per ray on the kernel, %.2f on the CPU\n", name.c_str(),
                  gpu_steps / static_cast<double>(cpu.steps.size()), cpu_steps / static_cast<double>(cpu.steps.size()));
      EXPECT_NEAR(gpu_steps / cpu_steps, 1.0, 0.02) << name;
    }
  }
  expect_no_validation_errors();
}

TEST(Kernel, BallsMatchTheCpuRenderer) {
  sol::Scene scene;
  scene.camera = {{0.3, -0.2, 0.1}, {1, 0.2, 0.1}, {0, 0, 1}, 70.0};
  const sol::SceneObject ball{sol::Ball{{2.0, 0.5, 0.2}, 0.6}, {0.3, 0.8, 0.4}, sol::Pattern::Circles};
  const sol::SceneObject floor{sol::PlaneZ{-0.8}, {0.8, 0.8, 0.8}, sol::Pattern::Checker};
  const sol::SceneObject tube{sol::make_tube(sol::TubeAxis::Z, {1.5, -0.8, 0.0}, 0.2, sol::Lattice::golden()), {0.8, 0.3, 0.8}, sol::Pattern::Checker};
  // A tube along γ1 (a horizontal line of irrational slope), patterned.
  const sol::SceneObject slanted{sol::make_tube(sol::TubeAxis::Gamma1, {2.4, 0.3, -0.35}, 0.15, sol::Lattice::golden()), {0.9, 0.8, 0.2},
                                 sol::Pattern::Checker};
  scene.objects = {ball, floor, tube, slanted};
  // A point light and coloured fog: shading as sol::light_at on both sides.
  sol::Light point;
  point.type = sol::LightType::Point;
  point.position = {1.2, -0.5, 0.9};
  point.color = {1.0, 0.9, 0.7};
  point.intensity = 3.0;
  scene.lights.push_back(point);
  scene.fog_color = {0.2, 0.25, 0.3};
  scene.fog_density = 0.08;
  sol::RenderOptions settings;
  settings.width = 40;
  settings.height = 30;
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::test::render(renderer, scene, settings.width, settings.height);
  const Comparison c = compare(gpu, cpu);
  int tubes = 0;
  for (float o : gpu.object) tubes += o == 3.0f;
  EXPECT_GT(tubes, 10);
  std::printf("ball scene: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n",
              c.mask_differs, c.pixels, c.color_differs, c.distance);
  // Same tolerances as the presets (float against double, edges may flip).
  EXPECT_LE(c.mask_differs, c.pixels / 100);
  EXPECT_LE(c.color_differs, c.pixels / 100);
  EXPECT_LT(c.distance, 1e-3);
  // Both step by the nearest ball's or tube's clearance (sol/clearance.hpp):
  // the same steps within float rounding (measured: equal to two decimals).
  double cpu_steps = 0.0, gpu_steps = 0.0;
  for (std::size_t k = 0; k < cpu.steps.size(); ++k) {
    cpu_steps += cpu.steps[k];
    gpu_steps += gpu.steps[k];
  }
  std::printf("ball scene: %.2f steps per ray on the kernel, %.2f on the CPU\n",
              gpu_steps / static_cast<double>(cpu.steps.size()), cpu_steps / static_cast<double>(cpu.steps.size()));
  EXPECT_NEAR(gpu_steps / cpu_steps, 1.0, 0.02);
  int balls = 0;
  for (float o : gpu.object) balls += o == 1.0f;
  EXPECT_GT(balls, 30);
  int slanted_hits = 0;
  for (float o : gpu.object) slanted_hits += o == 4.0f;
  EXPECT_GT(slanted_hits, 10);
  expect_no_validation_errors();
}

// The kernel's specialisation constants folded into its SPIR-V or handed
// to the driver (MarchOptions::specialization_folding; by default folded on
// a CPU device): the same program. lavapipe's compiler then sees the same
// live code either way, so the images are equal to the bit there; a GPU's
// compiler may schedule the two modules differently (its contractions are
// its own), so there they are held to the tolerances of the specialised
// kernel against the general one (float rounding; edges may flip). One
// world, plane: the driver's specialisation compiles every feature's code
// before it drops what the world does not use, on lavapipe 19 s for plane,
// 25 s for lattice-balls, 36 s for spheres, and the folding is the same
// code for every world.
TEST(Kernel, FoldedSpecialisationRendersTheDriversImage) {
  using sol::vk::SpecializationFolding;
  const bool cpu = vk_context().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  // (On lavapipe the driver's compile alone takes 19 s: opt-in there, as the
  // long sweeps; VkPipeline.FoldedSpecialisationIsTheDriversAndDropsDeadCode
  // holds the folding to the driver's on a small shader every run.)
  if (cpu && !sol::test::full_sweeps()) GTEST_SKIP() << "the driver's compile on lavapipe: SOL_FULL_SWEEPS=1 runs it";
  sol::vk::MarchRenderer folded(vk_context(), {.specialization_folding = SpecializationFolding::Folded});
  sol::vk::MarchRenderer by_driver(vk_context(), {.specialization_folding = SpecializationFolding::Driver});
  for (const std::string name : {"plane"}) {
    const sol::Scene scene = sol::preset_scene(name);
    const auto start = std::chrono::steady_clock::now();
    const sol::RenderResult a = sol::test::render(folded, scene, 40, 28);
    const auto middle = std::chrono::steady_clock::now();
    const sol::RenderResult b = sol::test::render(by_driver, scene, 40, 28);
    std::printf("%s: folded %.1f s, the driver's %.1f s (pipelines built and one frame)\n", name.c_str(),
                std::chrono::duration<double>(middle - start).count(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - middle).count());
    if (cpu) {
      EXPECT_EQ(a.object, b.object) << name;
      EXPECT_EQ(a.distance, b.distance) << name;
      EXPECT_EQ(a.steps, b.steps) << name;
      EXPECT_EQ(a.px, b.px) << name;
      EXPECT_EQ(a.rgba, b.rgba) << name;
    } else {
      const Comparison c = compare(a, b);
      std::printf("%s: folded against the driver's: mask differs at %d of %d pixels, colour at %d, worst distance %.2e\n",
                  name.c_str(), c.mask_differs, c.pixels, c.color_differs, c.distance);
      EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
      EXPECT_LE(c.color_differs, c.pixels / 100) << name;
      EXPECT_LT(c.distance, 1e-3) << name;
    }
    int hits = 0;
    for (float o : a.object) hits += o > 0.0f;
    EXPECT_GT(hits, static_cast<int>(a.object.size()) / 10) << name << ": a picture to compare";
  }
  expect_no_validation_errors();
}

// Boxes (sol::Box) in the kernel: in Sol (seen from beside the box and
// from inside the slab of its x faces) and in the quotient (lattice-boxes),
// every hit lies on a face of the coordinate box [x0 ± a e^{z0}] x
// [y0 ± b e^{-z0}] x [z0 ± c] within 1e-4 in Sol distance (hit_epsilon
// 5e-5, up to √3 times that near an edge, and float rounding of the hit
// point), and the kernel's image is the CPU renderer's within the
// tolerances of float against double (a silhouette or pattern-edge pixel
// may go either way: at most 1% of pixels).
TEST(Kernel, BoxesLieOnTheirFacesAndMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene lattice = sol::preset_scene("lattice-boxes");
  const struct {
    const char* name;
    sol::Scene scene;
    std::vector<sol::Box> boxes;
  } cases[] = {
      {"box", sol::test::box_scene(), {std::get<sol::Box>(sol::test::box_scene().objects[0].shape)}},
      {"box from its slab", sol::test::box_scene_from_its_slab(),
       {std::get<sol::Box>(sol::test::box_scene_from_its_slab().objects[0].shape)}},
      {"lattice-boxes", lattice, sol::test::box_images(lattice)},
  };
  for (const auto& [name, scene, boxes] : cases) {
    sol::RenderOptions settings;
    settings.width = 40;
    settings.height = 30;
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const sol::RenderResult gpu = sol::test::render(renderer, scene, settings.width, settings.height);
    const sol::test::FaceHits f = sol::test::hits_on_faces(gpu, boxes);
    const Comparison c = compare(gpu, cpu);
    std::printf("%s: kernel hits %d, farthest from a face %.2e; against the CPU: mask differs at %d of %d, colour at %d\n",
                name, f.hits, f.farthest, c.mask_differs, c.pixels, c.color_differs);
    EXPECT_GT(f.hits, c.pixels / 20) << name;
    EXPECT_LT(f.farthest, 1e-4) << name;
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
  }
  expect_no_validation_errors();
}

// camera.look_at on the kernel: a small ball at the point, seen from where
// geodesics bend (sol_tests' Aim.TheLookAtPointIsAtTheCentrePixel on the
// CPU): the centre pixel of a 9 x 9 image hits it in Sol and in the golden
// quotient (there through the point's nearest image).
TEST(Kernel, TheLookAtPointIsAtTheCentrePixel) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* quotient : {"none", "golden"}) {
    const sol::Scene scene = sol::parse_scene(std::string(R"({"quotient": ")") + quotient + R"(",
        "camera": {"position": [0.4, 0.3, 0.2], "look_at": [2.6, -1.9, 1.1], "up": [0, 0, 1], "fov": 12},
        "objects": [{"type": "ball", "center": [2.6, -1.9, 1.1], "radius": 0.05}]})");
    const sol::RenderResult gpu = sol::test::render(renderer, scene, 9, 9);
    EXPECT_EQ(gpu.object[4 * 9 + 4], 1.0f) << quotient;
  }
  expect_no_validation_errors();
}

// Depth of field (sol/lens.hpp): the kernel's lens rays (float, two chord
// steps of Newton's method) render the CPU's image (double, Newton to
// 1e-12), both taking sol::lens_sample(k) for sample k: a sharp ball at the
// focus, a blurred one before it, a checkered floor behind, 16 samples, at
// the scene defaults, in Sol and the golden quotient (the lens point
// teleported into D). Sample 0 (the AOVs) is the pinhole's ray on both.
// Float against double: a ray that grazes a silhouette may go either way,
// and in the quotient the far images of the floor are reached along
// geodesics whose neighbours part exponentially (the flow is Anosov), so
// the pinhole's kernel image already differs from the CPU's there (6 % of
// the pixels by over 0.02). The lens may add its float rounding to that,
// not more: its pixels differing by over 0.02 at most 1.5 times the
// pinhole's plus 2 % of the image, its mean difference at most 1.5 times
// the pinhole's plus 2e-3; and without the lens (the pinhole's image) a
// fifth of the pixels differ, so the lens is seen.
TEST(Kernel, ALensRendersAsTheCpu) {
  sol::vk::MarchRenderer renderer(vk_context());
  auto differing = [](const sol::RenderResult& a, const sol::RenderResult& b, double& mean) {
    int n = 0;
    mean = 0.0;
    for (int k = 0; k < a.width * a.height; ++k) {
      float e = 0.0f;
      for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(a.rgba[4 * k + ch] - b.rgba[4 * k + ch]));
      n += e > 0.02f;
      mean += static_cast<double>(e) / (a.width * a.height);
    }
    return n;
  };
  for (const char* quotient : {"none", "golden"}) {
    const sol::Scene scene = sol::parse_scene(std::string(R"({"quotient": ")") + quotient + R"(",
        "camera": {"position": [0.05, 0.1, 0.3], "look_at": [1.6, 0.2, 0.35], "up": [0, 0, 1], "fov": 50,
                   "aperture": 0.12},
        "objects": [{"type": "plane_z", "c": 0, "color": [0.8, 0.8, 0.8], "pattern": "checker"},
                    {"type": "ball", "center": [1.6, 0.2, 0.35], "radius": 0.2, "color": [0.2, 0.8, 0.3]},
                    {"type": "ball", "center": [0.7, -0.25, 0.3], "radius": 0.1, "color": [0.9, 0.3, 0.2]}]})");
    sol::Scene pinhole = scene;
    pinhole.camera.aperture = 0.0;
    const sol::RenderOptions settings{.width = 32, .height = 24, .samples = 16};
    const int pixels = settings.width * settings.height;
    renderer.set_world(scene);
    const sol::RenderResult gpu = renderer.render(scene.camera, settings);
    const sol::RenderResult sharp_gpu = renderer.render(pinhole.camera, settings);
    const sol::RenderResult cpu = sol::render_cpu(scene, settings), sharp = sol::render_cpu(pinhole, settings);
    double mean = 0.0, mean_pinhole = 0.0, blur = 0.0;
    const int differ = differing(gpu, cpu, mean), differ_pinhole = differing(sharp_gpu, sharp, mean_pinhole);
    const int blurred = differing(sharp, cpu, blur);
    std::printf("lens, %s: %d of %d pixels differ by over 0.02 from the CPU (mean %.2e; the pinhole's %d, %.2e); "
                "from the pinhole's image %d (mean %.2e)\n",
                quotient, differ, pixels, mean, differ_pinhole, mean_pinhole, blurred, blur);
    EXPECT_LE(differ, 1.5 * differ_pinhole + pixels / 50) << quotient;
    EXPECT_LT(mean, 1.5 * mean_pinhole + 2e-3) << quotient;
    EXPECT_GE(blurred, pixels / 5) << quotient;
    EXPECT_EQ(gpu.object, cpu.object) << quotient;  // sample 0: the pinhole's hits
  }
  expect_no_validation_errors();
}

TEST(Kernel, SpecialisedKernelRendersTheImageOfTheGeneralOne) {
  // The kernel specialised to a scene's features and the one with every
  // feature compiled in compute the same march (the general one evaluates
  // full positions where the specialised one needs heights only, so float
  // rounding differs: same tolerances as against the CPU).
  sol::vk::MarchRenderer specialised(vk_context()), general(vk_context(), {.all_features = true});
  for (const std::string& name : sol::preset_names()) {
    const sol::Scene scene = sol::preset_scene(name);
    if (sol::uses_exact(scene)) continue;  // exact scenes: tests ExactBalls* and ExactLights*
    const Comparison c = compare(sol::test::render(specialised, scene, 40, 30), sol::test::render(general, scene, 40, 30));
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
    EXPECT_LT(c.distance, 1e-3) << name;
  }
  expect_no_validation_errors();
}

// The deferred passes (MarchOptions::deferred: the resume pass goes on with
// the rays that reach an exact ball, in the quotient marches the rays of μ
// below kZetaLeastMu; the shade pass shades the hits of exact lights)
// render the image of the one dispatch. The march is the same (the resume
// pass starts from the arc length, step and cutout state the march pass
// left; in the quotient one dispatch takes each ray's positions as its
// pass would), so on a CPU device (lavapipe) the AOVs are equal to the bit
// (a GPU: tolerances, below); the colour within
// 1e-5: the normal travels through the list as its octahedral code, exact up
// to float rounding (1e-7), which the shading carries into the colour; a
// hit shaded with another point, normal, eye or object changes it by 1e-2
// and more. Mono and side-by-side stereo (the second eye's pixels), whole
// and in 8 x 8 tiles with 3 samples (each tile's lists; the running mean),
// spheres with shadows, a cutout plane through an exact ball, the
// quotient with an exact light (6.6 % of
// lattice-balls' rays have μ < kZetaLeastMu: resumed; its hits shaded
// deferred), and record() (the cutout plane). Spheres with shadows take no
// pass: their camera ray is radiance's first (DIRECT_FROM_EYE), which
// renders the one dispatch's image as well.
TEST(Kernel, DeferredPassesRenderTheOneDispatchImage) {
  sol::vk::MarchRenderer deferred(vk_context()), single(vk_context(), {.deferred = false});
  const bool cpu = vk_context().properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  struct Case {
    std::string name;
    sol::Scene scene;
    int passes;  // deferred passes the world takes
  };
  std::vector<Case> cases;
  // (Exact balls with shadows take none: the camera ray is the first ray
  // of radiance's own march, DIRECT_FROM_EYE, the same march to the bit.)
  sol::Scene shadows = sol::preset_scene("spheres");
  shadows.lights[0].shadows = true;
  cases.push_back({"spheres with shadows, from the eye", shadows, 0});
  // A cutout checkerboard in the plane z = 1 through the ball centred at
  // (1, 1, 1): rays reach its shell through the dark squares. (The march
  // pass hands the resume pass the cutout planes a ray is passing, those
  // within 2 hit_epsilon behind it where it came within hit_epsilon of a
  // light square; no ray of this image reaches a shell while passing one,
  // a case no test pins.)
  sol::Scene cutout = sol::preset_scene("spheres");
  cutout.objects.push_back({sol::PlaneZ{1.0}, {0.8, 0.8, 0.8}, sol::Pattern::Checker, true});
  cases.push_back({"spheres and a cutout plane", cutout, 2});
  sol::Scene lattice = sol::preset_scene("lattice-balls");
  sol::Light light;
  light.type = sol::LightType::Point;
  light.exact = true;
  light.position = {0.5, 0.4, 0.2};
  light.intensity = 3.0;
  lattice.lights = {light};
  cases.push_back({"lattice-balls, exact light", lattice, 2});
  for (const Case& c : cases) {
    const int w = 40, h = 28;
    deferred.set_world(c.scene);
    single.set_world(c.scene);
    EXPECT_EQ(deferred.deferred_passes(), c.passes) << c.name;
    EXPECT_EQ(single.deferred_passes(), 0) << c.name;
    const sol::Camera eyes[] = {c.scene.camera, sol::stereo_eyes(c.scene.camera, 0.1).right};
    for (int n : {1, 2}) {
      for (int samples : {1, 3}) {
        sol::RenderOptions options{.width = w, .height = h, .samples = samples};
        if (samples > 1) options.max_dispatch_ms = 1e-6;  // tiles of 8 x 8 pixels
        const sol::RenderResult a = deferred.render(std::span(eyes, static_cast<std::size_t>(n)), options);
        const sol::RenderResult b = single.render(std::span(eyes, static_cast<std::size_t>(n)), options);
        const std::string what = c.name + ", " + std::to_string(n) + " eyes, " + std::to_string(samples) + " samples";
        // On a failure, how far apart (a GPU compiles the two pipelines
        // with its own contractions; lavapipe's are bitwise equal).
        struct Apart {
          int differ = 0;
          float worst = 0.0f;
        };
        const auto apart = [](const std::vector<float>& x, const std::vector<float>& y) {
          Apart d;
          for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
            d.worst = std::max(d.worst, std::abs(x[i] - y[i]));
            d.differ += x[i] != y[i];
          }
          return d;
        };
        const auto told = [&](const std::vector<float>& x, const std::vector<float>& y) {
          const Apart d = apart(x, y);
          char text[64];
          std::snprintf(text, sizeof text, ": %d pixels differ, worst by %.2e", d.differ, static_cast<double>(d.worst));
          return std::string(text);
        };
        ASSERT_EQ(a.rgba.size(), b.rgba.size());
        if (cpu) {
          EXPECT_EQ(a.object, b.object) << what << told(a.object, b.object);
          EXPECT_EQ(a.distance, b.distance) << what << told(a.distance, b.distance);
          EXPECT_EQ(a.steps, b.steps) << what << told(a.steps, b.steps);
          EXPECT_EQ(a.px, b.px) << what << told(a.px, b.px);
          EXPECT_LT(apart(a.rgba, b.rgba).worst, 1e-5f) << what;
        } else {
          // A GPU compiles the one-dispatch pipeline apart from the passes'
          // with contractions of its own (on the H200: AOVs 1.2e-6 apart in
          // Sol, up to 2e-3 in the quotient, carried through its
          // teleports): the tolerances of float against double
          // (PresetsMatchTheCpuRenderer), arc lengths apart by more than
          // 1e-3 at grazing pixels only.
          const Comparison d = compare(a, b);
          int grazing = 0;
          for (std::size_t k = 0; k < a.object.size(); ++k) {
            grazing += a.object[k] != 0.0f && a.object[k] == b.object[k] && std::abs(a.distance[k] - b.distance[k]) > 1e-3f;
          }
          std::printf("%s: mask differs at %d of %d pixels, colour at %d, arc lengths by %.2e (%d beyond 1e-3)\n",
                      what.c_str(), d.mask_differs, d.pixels, d.color_differs, d.distance, grazing);
          EXPECT_LE(d.mask_differs, d.pixels / 100) << what;
          EXPECT_LE(d.color_differs, d.pixels / 100) << what;
          EXPECT_LE(grazing, d.pixels / 100) << what;
        }
        int hits = 0;
        for (float o : a.object) hits += o > 0.0f;
        EXPECT_GT(hits, static_cast<int>(a.object.size()) / 20) << what << ": hits to shade";
      }
    }
    // The presenters' recorded frame: the render's colour (one world: each
    // compiles three more pipelines, seconds on lavapipe).
    if (c.name != "spheres and a cutout plane") continue;
    const sol::RenderResult ref = sol::test::render(deferred, c.scene, w, h);
    sol::vk::StorageImage target(vk_context(), w, h);
    vk_context().submit_and_wait([&](VkCommandBuffer cb) { deferred.record(cb, std::span(eyes, 1), w, h, target); });
    EXPECT_EQ(target.download(), ref.rgba) << c.name << ": record()";
  }
  expect_no_validation_errors();
}

// The kernel approaches exact balls by the bound, then takes the exact
// distance from the shortest geodesic (sol_shortest) within kExactShell:
// hit points lie on the geodesic sphere (of the nearest image of the
// centre, in the quotient) to hit_epsilon (5e-5) plus float rounding, 1e-4,
// and the hit masks follow the CPU renderer's (the double solver), its arc
// lengths too. Balls of radius 0.5 and 1.4; the ends of the radii the
// kernel accepts: a small ball near
// the eye, balls of radius kMaxExactBallRadius = 2 seen from up to 9.5 away
// (far points once took Newton's first seed out of its reach: false hits up
// to 1.6 off the sphere); in the quotient the lattice's ball at the base
// point made exact, at r = 0.25 and at the largest radius it accepts, 0.45.
// Larger exact balls are refused (the CPU renders them).
TEST(Kernel, ExactBallsLieOnTheGeodesicSphere) {
  struct Case {
    std::string name;
    sol::Scene scene;
  };
  std::vector<Case> cases;
  const sol::Ball table_ball{{1.3, 1.1, 0.6}, 0.5, true}, beyond_ball{{2.2, 1.9, -0.4}, 1.4, true};
  cases.push_back({"r = 0.5", sol::preset_scene("plane")});
  cases.back().scene.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 60.0};
  cases.back().scene.objects = {{table_ball}};
  cases.push_back({"r = 1.4", sol::preset_scene("plane")});
  cases.back().scene.camera = {{0.0, 0.0, 0.2}, {1.0, 1.0, -0.2}, {0.0, 0.0, 1.0}, 70.0};
  cases.back().scene.objects = {{beyond_ball}};
  const sol::Ball small_ball{{0.2, 0.06, 0.02}, 0.05, true};
  cases.push_back({"r = 0.05", sol::preset_scene("plane")});
  cases.back().scene.camera = {{0.0, 0.0, 0.0}, {1.0, 0.3, 0.1}, {0.0, 0.0, 1.0}, 40.0};
  cases.back().scene.objects = {{small_ball}};
  const double r = sol::vk::MarchRenderer::kMaxExactBallRadius;
  for (const glm::dvec3& centre : {glm::dvec3(20.0, -6.0, 0.4), glm::dvec3(8.0, 3.0, -0.5), glm::dvec3(-6.0, 9.0, 1.2),
                                   glm::dvec3(3.0, -3.0, 2.0)}) {
    cases.push_back({"r = 2 at (" + std::to_string(centre.x) + ", " + std::to_string(centre.y) + ")", sol::preset_scene("plane")});
    cases.back().scene.camera = {{0.0, 0.0, centre.x > 10.0 ? 0.3 : 0.0}, centre.x > 10.0 ? glm::dvec3(1.0, -0.4, 0.1) : centre,
                                 {0.0, 0.0, 1.0}, centre.x > 10.0 ? 80.0 : 70.0};
    cases.back().scene.objects = {{sol::Ball{centre, r, true}}};
  }
  for (double radius : {0.25, 0.45}) {
    cases.push_back({"quotient r = " + std::to_string(radius), sol::preset_scene("lattice-balls")});
    std::get<sol::Ball>(cases.back().scene.objects[0].shape) = sol::Ball{{0.0, 0.0, 0.0}, radius, true};
  }
  const sol::Lattice gamma = sol::Lattice::golden();
  sol::vk::MarchRenderer renderer(vk_context());
  for (const Case& c : cases) {
    const sol::Ball ball = std::get<sol::Ball>(c.scene.objects[0].shape);
    const bool quotient = c.scene.quotient() != sol::Quotient::None;
    const sol::RenderResult gpu = sol::test::render(renderer, c.scene, 24, 18);
    sol::RenderOptions settings;
    settings.width = 24;
    settings.height = 18;
    const sol::RenderResult cpu = sol::render_cpu(c.scene, settings);
    double worst = 0.0;
    int hits = 0;
    for (std::size_t i = 0; i < gpu.object.size(); ++i) {
      if (gpu.object[i] != 1.0f) continue;
      ++hits;
      const glm::dvec3 p(gpu.px[i], gpu.py[i], gpu.pz[i]);
      double d = sol::distance(p, ball.center);
      if (quotient) {  // the nearest image g·centre, g over the words near D
        for (int a = -3; a <= 3; ++a) {
          for (int b = -3; b <= 3; ++b) {
            for (int e = -1; e <= 1; ++e) {
              // (An image whose distance's lower bound is already farther cannot be nearer: not solved.)
              const glm::dvec3 image = sol::multiply(gamma.element(a, b, e), ball.center);
              if (sol::distance_lower_bound(p, image) < d) d = std::min(d, sol::distance(p, image));
            }
          }
        }
      }
      worst = std::max(worst, std::abs(d - ball.radius));
    }
    const Comparison m = compare(gpu, cpu);
    std::printf("exact ball %s: %d hits, worst |d - r| = %.2e, mask differs at %d of %d, worst arc length "
                "difference %.2e\n", c.name.c_str(), hits, worst, m.mask_differs, m.pixels, m.distance);
    EXPECT_GT(hits, 20) << c.name;
    EXPECT_LT(worst, 1e-4) << c.name;
    EXPECT_LE(m.mask_differs, 2) << c.name;  // a silhouette pixel may go either way in float
    // Both march to within hit_epsilon of the same surface; an oblique ray
    // moves along itself by more than the surface gap (measured 1.2e-3: the
    // kernel's last steps are the ball's clearance, the CPU's its distance).
    EXPECT_LT(m.distance, 5e-3) << c.name;
  }
  sol::Scene larger = cases[1].scene;
  std::get<sol::Ball>(larger.objects[0].shape).radius = 2.01;
  EXPECT_FALSE(sol::vk::MarchRenderer::supports(larger));
  EXPECT_NE(sol::vk::MarchRenderer::unsupported(larger).find("objects[0].radius"), std::string::npos);
  EXPECT_THROW(sol::test::render(renderer, larger, 8, 8), sol::NotImplemented);
  expect_no_validation_errors();
}

TEST(Kernel, NoNonFiniteValuesAtTheEdgesOfTheAcceptedRanges) {
  // As Render.NoNonFiniteValuesAtTheEdgesOfTheAcceptedRanges, in float: the
  // camera's e^{±80} and coordinates of 1e15 meet the kernel's arithmetic.
  sol::vk::MarchRenderer renderer(vk_context());
  for (const std::string& name : sol::preset_names()) {
    const sol::Scene scene = sol::preset_scene(name);
    renderer.set_world(scene);  // once for every camera
    for (const glm::dvec3& p : sol::test::extreme_positions()) {
      sol::Camera camera = scene.camera;
      camera.position = p;
      EXPECT_EQ(sol::test::non_finite_values(renderer.render(camera, {.width = 12, .height = 8})), 0)
          << name << " from (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
  }
  expect_no_validation_errors();
}

TEST(Kernel, CutoutPlanesMatchTheCpuRenderer) {
  sol::Scene scene = sol::preset_scene("plane");
  scene.objects[0].cutout = true;
  sol::SceneObject floor;
  floor.shape = sol::PlaneZ{-1.0};
  floor.pattern = sol::Pattern::Checker;
  scene.objects.push_back(floor);
  sol::RenderOptions settings;
  settings.width = 48;
  settings.height = 48;
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::test::render(renderer, scene, 48, 48);
  const Comparison c = compare(gpu, cpu);
  std::printf("cutout: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n",
              c.mask_differs, c.pixels, c.color_differs, c.distance);
  // Disc edges may go either way in float (1% as for the presets).
  EXPECT_LE(c.mask_differs, c.pixels / 100);
  EXPECT_LE(c.color_differs, c.pixels / 100);
  EXPECT_LT(c.distance, 1e-3);
  expect_no_validation_errors();
}

TEST(Kernel, QuotientObserverAtPAndGpAndThinPlanesNearFaces) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"lattice-balls", "lattice-pillars", "trace4-balls", "halfturn-balls"}) {
    sol::Scene scene = sol::preset_scene(name);
    const sol::Lattice lattice = *scene.lattice();
    scene.max_distance = 6.0;
    const sol::RenderResult here = sol::test::render(renderer, scene, 24, 18);
    for (const sol::LatticeWord& w : {sol::LatticeWord{0, 0, 1}, sol::LatticeWord{3, -2, -2}, sol::LatticeWord{400000, -300000, 0}}) {
      // g·p with the frame g turns (where the lattice's γ3 turns and c is odd).
      sol::Scene moved = scene;
      moved.camera.position = lattice.apply(w, scene.camera.position);
      if (lattice.turns() && w.c % 2 != 0) {
        moved.camera.forward = sol::half_turn(scene.camera.forward);
        moved.camera.up = sol::half_turn(scene.camera.up);
      }
      const Comparison c = compare(sol::test::render(renderer, moved, 24, 18), here);
      EXPECT_LE(c.mask_differs, 2) << name;  // the eye is teleported in double: same float input up to rounding
      EXPECT_LT(c.distance, 1e-4) << name;
    }
  }
  // Thin planes 1e-4 inside the faces z = 0 and z = h: as the CPU reference
  // (which render_test.cpp holds to the cover with all the plane's images),
  // in the golden lattice and in that of [[9, 4], [2, 1]] (trace 10, its
  // fibre's area 7).
  for (const auto& [monodromy, area] : {std::pair{sol::Monodromy{2, 1, 1, 1}, std::optional<double>()},
                                        std::pair{sol::Monodromy{9, 4, 2, 1}, std::optional<double>(7.0)}}) {
    const sol::Lattice lattice = sol::Lattice::from_monodromy(monodromy, area);
    const dvec3 g1 = lattice.generators()[0], g2 = lattice.generators()[1];
    for (const double c : {1e-4, lattice.height() - 1e-4}) {
      sol::Scene thin;
      sol::set_space(thin, sol::MonodromySpace{monodromy, area});
      thin.camera = {0.43 * g1 + 0.21 * g2 + dvec3(0.0, 0.0, 0.5 * lattice.height()), {0.3, 0.5, -0.2}, {0, 0, 1}, 100.0};
      thin.max_distance = 8.0;
      thin.max_steps = 400;
      thin.objects = {{sol::PlaneZ{c}}};
      sol::RenderOptions settings;
      settings.width = 24;
      settings.height = 18;
      const Comparison d = compare(sol::test::render(renderer, thin, 24, 18), sol::render_cpu(thin, settings));
      EXPECT_LE(d.mask_differs, d.pixels / 100) << monodromy.str() << " " << c;
      EXPECT_LT(d.distance, 1e-3) << monodromy.str() << " " << c;  // float over several teleports
    }
  }
  expect_no_validation_errors();
}

// The non-compact quotients on the kernel (LATTICE_LOOPS: a z loop's D has
// every x, y, xy loops' every z; every image a candidate): as the CPU
// renderer (which render_test.cpp holds to the universal cover), with the
// tolerances of PresetsMatchTheCpuRenderer; and the observer at p and at
// g·p (γ3², γ1³ γ2⁻²) sees the same image.
TEST(Kernel, NonCompactQuotientsMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const sol::Scene& scene : {sol::test::z_loop_scene(), sol::test::xy_loops_scene()}) {
    const sol::Lattice lattice = *scene.lattice();
    const char* name = lattice.loops() == sol::Lattice::Loops::Z ? "z loop" : "xy loops";
    EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene), "") << name;
    sol::RenderOptions settings;
    settings.width = 48;
    settings.height = 32;
    const sol::RenderResult gpu = sol::test::render(renderer, scene, settings.width, settings.height);
    for (float v : gpu.rgba) ASSERT_TRUE(std::isfinite(v)) << name;
    const Comparison c = compare(gpu, sol::render_cpu(scene, settings));
    std::printf("%s: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n", name,
                c.mask_differs, c.pixels, c.color_differs, c.distance);
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
    EXPECT_LT(c.distance, 0.05) << name;  // grazing rays (PresetsMatchTheCpuRenderer); measured 1.3e-5, 3.1e-5
    const sol::LatticeWord w = lattice.loops() == sol::Lattice::Loops::Z ? sol::LatticeWord{0, 0, 2} : sol::LatticeWord{3, -2, 0};
    sol::Scene moved = scene;
    moved.camera.position = lattice.apply(w, scene.camera.position);
    const Comparison d = compare(sol::test::render(renderer, moved, 24, 18), sol::test::render(renderer, scene, 24, 18));
    EXPECT_LE(d.mask_differs, 2) << name;  // the eye is teleported in double: same float input up to rounding
    EXPECT_LT(d.distance, 1e-4) << name;
  }
  expect_no_validation_errors();
}

// Mirrors on the kernel (radiance in march/shading.glsl: the reflected ray
// marched by the one march, as a ray that leaves its surface): a perfect
// mirror x = 0 shows the reflected scene (support/mirrors.hpp) as the CPU
// renderer's test does, the kernel's image against its own render of the
// reflected scene, and against the CPU's (measured: 0 of 3072 pixels
// differ in both); in the quotient, a half mirror z = c under lattice-balls (the
// balls' images reflected in it, with fog) and a glowing ball as the CPU
// renders them (measured: 0 of 1536 differ). Tolerances: edge pixels of
// grazing rays (1 %), colours to 2e-3 (float against double).
TEST(Kernel, MirrorsShowTheReflectedSceneAndMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::RenderOptions settings;
  settings.width = 64;
  settings.height = 48;
  const int pixels = settings.width * settings.height;
  const sol::RenderResult mirrored = sol::test::render(renderer, sol::test::mirror_scene(true), 64, 48);
  const sol::RenderResult reflected = sol::test::render(renderer, sol::test::mirror_scene(false), 64, 48);
  const int differ = sol::test::colour_differences(mirrored, reflected, 2e-3);
  const int against_cpu =
      sol::test::colour_differences(mirrored, sol::render_cpu(sol::test::mirror_scene(true), settings), 2e-3);
  std::printf("mirror: %d of %d pixels differ from the reflected scene, %d from the CPU's\n", differ, pixels, against_cpu);
  EXPECT_LE(differ, pixels / 100);
  EXPECT_LE(against_cpu, pixels / 100);
  sol::Scene quotient = sol::preset_scene("lattice-balls");
  quotient.objects[0].emission = {0.3, 0.2, 0.1};
  sol::SceneObject floor{sol::PlaneZ{0.05}, {0.3, 0.3, 0.35}};
  floor.mirror = 0.6;
  quotient.objects.push_back(floor);
  quotient.max_bounces = 3;
  const sol::RenderResult gpu = sol::test::render(renderer, quotient, 48, 32);
  sol::RenderOptions small;
  small.width = 48;
  small.height = 32;
  const int quotient_differ = sol::test::colour_differences(gpu, sol::render_cpu(quotient, small), 2e-3);
  std::printf("mirror plane in the quotient: %d of %d pixels differ from the CPU's\n", quotient_differ, 48 * 32);
  EXPECT_LE(quotient_differ, 48 * 32 / 100);
  expect_no_validation_errors();
}

// A half-silvered ball in the quotient (docs/gallery/mirror-balls.json with
// one reflection and no fog): its reflected rays leave the ball as the
// CPU's do. A shading of the hit that called the diffuse light only where
// the material had a diffuse share made them hit their own ball on
// lavapipe in 16.6 % of the pixels of a 160 x 120 image (against 1.5 %
// differing by more than 2e-3 otherwise: rays that graze the quotient's
// balls); 5 % allowed.
TEST(Kernel, HalfSilveredBallsInTheQuotientReflectAsTheCpu) {
  const sol::Scene scene = sol::parse_scene(R"({"camera": {"position": [0.9, 0.3, 0.45], "forward": [0, 0, -1],
    "up": [0, 1, 0], "fov": 90}, "quotient": "golden", "objects": [{"type": "ball", "center": [0, 0, 0], "radius": 0.3,
    "color": [0.6, 0.6, 0.65], "mirror": 0.85}, {"type": "ball", "center": [0.75, 0.05, 0.3], "radius": 0.1,
    "color": [0.9, 0.55, 0.3], "emission": [0.6, 0.3, 0.1]}], "lights": [{"type": "directional", "direction": [0.3, 0.5, 1]}],
    "max_distance": 12, "max_steps": 400, "max_bounces": 1})");
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderOptions settings{.width = 80, .height = 60};
  const int differ = sol::test::colour_differences(sol::render_scene(renderer, scene, settings), sol::render_cpu(scene, settings), 2e-3);
  std::printf("half-silvered balls in the quotient: %d of %d pixels differ from the CPU's\n", differ, 80 * 60);
  EXPECT_LE(differ, 80 * 60 / 20);
  expect_no_validation_errors();
}

// Many samples of a world with mirrors and glowing objects keep the
// process's memory flat. Each sample is a dispatch with its own point of
// the pixel and weight; a driver that compiles and keeps a variant of the
// kernel whenever its parameters are written (lavapipe inlines up to four
// values of a uniform buffer that decide branches and compiles again at
// every write: the kernel's parameters live in a storage buffer for that
// reason) grew by about 6 MB a dispatch there, 570 MB over these 192 samples. The bound, 48 MB, is far
// above what a flat render moves (the colour and AOV images of 64 x 48
// pixels are 150 KB) and far below one variant every eighth sample.
TEST(Kernel, ManySamplesOfMirrorsAndGlowKeepMemoryFlat) {
  sol::Scene scene = sol::test::mirror_scene(true);
  scene.objects[1].emission = {2.0, 1.5, 1.0};
  scene.objects[2].mirror = 0.5;
  sol::vk::MarchRenderer renderer(vk_context());
  renderer.set_world(scene);
  sol::RenderOptions settings{.width = 64, .height = 48, .samples = 4};
  (void)renderer.render(scene.camera, settings);  // the pipelines built
  const double before = sol::process_memory().resident_bytes;
  settings.samples = 192;
  const sol::RenderResult image = renderer.render(scene.camera, settings);
  const double grown = sol::process_memory().resident_bytes - before;
  std::printf("192 samples of mirrors and glow: resident memory grew by %.1f MB\n", grown / 1e6);
  ASSERT_GT(before, 0.0) << "no /proc/self/status";
  EXPECT_LT(grown, 48e6);
  EXPECT_GT(sol::test::red_mean(image).mean, 0.05);  // something was drawn
  expect_no_validation_errors();
}

// A ray that runs out of march steps is counted on the kernel as on the
// CPU (Render.RaysOutOfStepsAreCounted): with max_steps 3, counted over
// every sample (Stats, the per-pixel AOV's sum equal to the count; its
// own step rules: within a factor of two of the CPU's), with or without
// the AOVs; at the default none.
TEST(Kernel, RaysOutOfStepsAreCounted) {
  sol::Scene scene = sol::preset_scene("sandwich");
  sol::RenderOptions settings{.width = 16, .height = 12, .samples = 3};
  sol::vk::MarchRenderer renderer(vk_context());
  EXPECT_EQ(sol::render_scene(renderer, scene, settings).rays_out_of_steps, 0u);
  scene.max_steps = 3;
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  double sum = 0.0;
  for (const float n : gpu.out_of_steps) sum += n;
  std::printf("max_steps 3: %llu rays out of steps on the kernel, %llu on the CPU\n",
              static_cast<unsigned long long>(gpu.rays_out_of_steps), static_cast<unsigned long long>(cpu.rays_out_of_steps));
  EXPECT_GT(gpu.rays_out_of_steps, 0u);
  EXPECT_EQ(sum, static_cast<double>(gpu.rays_out_of_steps));
  EXPECT_GT(2 * gpu.rays_out_of_steps, cpu.rays_out_of_steps);
  EXPECT_LT(gpu.rays_out_of_steps, 2 * cpu.rays_out_of_steps);
  settings.aovs = false;
  EXPECT_EQ(sol::render_scene(renderer, scene, settings).rays_out_of_steps, gpu.rays_out_of_steps);
  expect_no_validation_errors();
}

// World::max_bounces is a path's length on the kernel as on the CPU
// (Path.MaxBouncesIsThePathLength): a box of perfect emitting mirrors
// shows (B + 1) E by paths and by direct light (float: within 1e-5 per
// unit).
TEST(Kernel, MaxBouncesIsThePathLength) {
  sol::Scene scene = sol::test::furnace_in(sol::Box{{0.1, -0.1, 0.05}, {0.6, 0.5, 0.4}}, sol::Quotient::None, 1.0);
  sol::vk::MarchRenderer renderer(vk_context());
  for (const int bounces : {0, 3}) {
    scene.max_bounces = bounces;
    renderer.set_world(scene);
    for (const sol::Transport transport : {sol::Transport::Direct, sol::Transport::Path}) {
      const sol::RenderResult r = renderer.render(scene.camera, {.width = 6, .height = 4, .samples = 2, .transport = transport});
      for (std::size_t k = 0; k < 24; ++k) {
        EXPECT_NEAR(r.rgba[4 * k], 0.5 * (bounces + 1), 1e-5 * (bounces + 1)) << bounces << " bounces, pixel " << k;
      }
    }
  }
  expect_no_validation_errors();
}

// The kernel's path tracer (march/paths.glsl) in furnaces: an eye inside a
// closed enclosure that emits E = 0.5 and reflects with albedo 0.6, no
// other light, sees E / (1 - ρ) = 1.25, and with half of the reflectance
// a mirror's E / (1 - 0.6 · 0.5 - 0.5) = 2.5 (render_test.cpp's furnaces),
// whatever the enclosure: every solid is seen from inside (HAS_INSIDE: a
// bound's -d inside; an exact ball's inner bound, r less an upper bound of
// the distance to the centre, finished by the exact solve; in Sol and the
// quotient). Two worlds of enclosures, with an eye inside each (one
// pipeline a world): in Sol a box, a ball drawn by its bound and an exact
// ball of radius 1, half a mirror; in the golden quotient an exact ball
// and a box at the corner of D (whose images the march meets in the
// neighbouring cells). Each eye sees only its enclosure's inner wall, no
// nearer than its own distance to it guarantees, its mean within 4
// standard errors of the value (36 pixels of 8 paths), and the kernel's
// paths are the CPU's for the same seed (at least 80 % of the pixels to
// 1e-3, as PathsAreTheCpuPathsForTheSameSeed). In the quotient the exact ball is a target of next-event
// estimation (its images around D; from inside the box they are all
// hidden): the furnace holds, and the CPU's paths, with it combined and
// alone (PathSampling::GlowOnly; Path.GlowSamplingInTheQuotientAgreesAndHelps
// checks the estimators' agreement over a lit plane on the CPU).
TEST(Kernel, PathsInEveryEnclosureMakeAFurnaceWithTheCpuPaths) {
  const sol::Lattice golden = sol::Lattice::golden();
  const glm::dvec3 corner = 0.5 * (golden.generators()[0] + golden.generators()[1]);
  struct Enclosure {
    sol::Shape shape;
    glm::dvec3 eye;
    double mirror = 0.0, expected = 1.25;
  };
  struct Furnaces {
    sol::Quotient quotient = sol::Quotient::None;
    std::vector<Enclosure> enclosures;
  };
  std::vector<Furnaces> worlds(2);
  worlds[0].quotient = sol::Quotient::None;
  worlds[0].enclosures.push_back({sol::Box{{0.1, -0.1, 0.05}, {0.6, 0.5, 0.4}}, {0.0, 0.0, 0.0}});
  worlds[0].enclosures.push_back({sol::Ball{{0.0, 0.0, 3.0}, 0.8, false}, {0.0, 0.0, 2.9}});
  worlds[0].enclosures.push_back({sol::Ball{{0.0, 0.0, -3.0}, 1.0, true}, {0.0, 0.0, -3.0}, 0.5, 2.5});
  worlds[1].quotient = sol::Quotient::Golden;
  worlds[1].enclosures.push_back({sol::Ball{{0.0, 0.0, 0.0}, 0.2, true}, {0.0, 0.0, 0.0}});
  worlds[1].enclosures.push_back({sol::Box{corner, {0.12, 0.12, 0.12}}, corner + glm::dvec3(0.02, -0.01, 0.0)});
  const sol::RenderOptions settings{.width = 6, .height = 6, .samples = 8, .transport = sol::Transport::Path, .seed = 7};
  for (const Furnaces& world : worlds) {
    sol::Scene scene = sol::test::furnace_in(world.enclosures[0].shape, world.quotient);
    scene.objects.clear();
    std::vector<sol::Camera> eyes;
    for (const Enclosure& e : world.enclosures) {
      scene.objects.push_back(sol::test::furnace_wall(e.shape, e.mirror));
      eyes.push_back(scene.camera);
      eyes.back().position = e.eye;
    }
    sol::validate(scene);
    sol::vk::MarchRenderer renderer(vk_context());
    renderer.set_world(scene);
    sol::CpuRenderer cpu_renderer(scene);
    // In the quotient next-event estimation alone as well (the glowing exact ball's images are its targets).
    std::vector<sol::PathSampling> samplings = {sol::PathSampling::Combined};
    if (world.quotient != sol::Quotient::None) samplings.push_back(sol::PathSampling::GlowOnly);
    for (const sol::PathSampling sampling : samplings) {
      sol::RenderOptions options = settings;
      options.path_sampling = sampling;
      for (std::size_t first = 0; first < eyes.size(); first += 2) {  // (a render takes one or two eyes)
        const std::span<const sol::Camera> these(eyes.data() + first, std::min<std::size_t>(2, eyes.size() - first));
        const sol::RenderResult gpu = renderer.render(these, options);
        const sol::RenderResult cpu = cpu_renderer.render(these, options);
        // At the default max_steps no ray runs out of steps in an enclosure
        // (each wall met from inside by its faces' clearance).
        EXPECT_EQ(gpu.rays_out_of_steps, 0u);
        EXPECT_EQ(cpu.rays_out_of_steps, 0u);
        const int row = 6 * static_cast<int>(these.size());
        for (std::size_t eye = first; eye < first + these.size(); ++eye) {
          // A camera ray goes at least as far as the eye's own distance to the wall (-d there) guarantees.
          const double guaranteed = -sol::shape_distance(scene.objects[eye].shape, eyes[eye].position);
          ASSERT_GT(guaranteed, 0.0) << "eye " << eye;
          sol::RenderResult one{.width = 6, .height = 6};
          for (int y = 0; y < 6; ++y) {
            for (int x = 0; x < 6; ++x) {
              const std::size_t k = static_cast<std::size_t>(y * row + static_cast<int>(eye - first) * 6 + x);
              ASSERT_TRUE(std::isfinite(gpu.rgba[4 * k]));
              ASSERT_EQ(gpu.object[k], static_cast<float>(eye + 1)) << "eye " << eye;  // its own enclosure's wall
              EXPECT_GE(gpu.distance[k], guaranteed - 1e-3) << "eye " << eye;  // (float)
              one.rgba.insert(one.rgba.end(), gpu.rgba.begin() + 4 * k, gpu.rgba.begin() + 4 * k + 4);
            }
          }
          sol::test::expect_furnace_mean(one, world.enclosures[eye].expected,
                                         std::string("kernel furnace in ") +
                                             (world.quotient == sol::Quotient::None ? "Sol" : "the golden quotient") +
                                             ", eye " + std::to_string(eye) + ", sampling " +
                                             std::to_string(static_cast<int>(sampling)));
        }
        const std::size_t agree = sol::test::pixels_agreeing(gpu, cpu, 1e-3f);
        std::printf("furnaces, kernel against CPU: %zu of %zu pixels agree to 1e-3\n", agree, gpu.object.size());
        // The CPU's paths, pixel for pixel, inside the glowing exact ball
        // too: next-event estimation to its own sphere marches without it
        // and each segment solves its exit on both devices, so float and
        // double take the same draws (measured 36 of 36; marching both to
        // the sphere left 5 of 36 alike).
        EXPECT_GE(agree, gpu.object.size() * 8 / 10);
      }
    }
  }
  expect_no_validation_errors();
}

// The kernel traces the CPU's paths: the same estimator with the same
// random numbers (splitmix64 from the seed, the pixel and the sample), so
// that with one seed most pixels agree to float rounding, and a path
// differs only where float and double choose differently (a silhouette, a
// roulette or mirror draw on the edge of its probability, a glancing
// bounce), after which it is another sample of the same estimator. A
// diffuse floor, a glowing ball, a half mirror ball and an exact point
// light with shadows: at
// least 80 % of the pixels agree to 1e-3 (measured: about 95 %), and over
// the image the mean difference is within 3 standard errors of 0. Then:
// the same seed gives the same image, another seed another one.
sol::Scene floor_glow_and_mirror() {
  sol::Scene scene;
  scene.camera = {{0.0, 0.0, 0.0}, {0.0, 1.0, -0.25}, {0.0, 0.0, 1.0}, 80.0};
  sol::SceneObject floor{sol::PlaneZ{-0.6}, {0.7, 0.6, 0.5}};
  sol::SceneObject glow{sol::Ball{{0.6, 1.8, 0.0}, 0.35, false}, {0.5, 0.5, 0.5}};
  glow.emission = {2.0, 1.5, 1.0};
  sol::SceneObject mirror{sol::Ball{{-0.6, 2.0, -0.2}, 0.4, false}, {0.8, 0.8, 0.9}};
  mirror.mirror = 0.6;
  scene.objects = {floor, glow, mirror};
  sol::Light light;
  light.type = sol::LightType::Point;
  light.position = {0.0, 1.0, 1.5};
  light.intensity = 2.0;
  light.exact = true;  // along every geodesic to it, with 1/J and shadows
  light.shadows = true;
  scene.lights = {light};
  scene.max_distance = 8.0;
  return scene;
}

// floor_glow_and_mirror with its mirror ball made clear glass (index 1.5).
sol::Scene floor_glow_and_glass() {
  sol::Scene scene = floor_glow_and_mirror();
  scene.objects[2].material = sol::Material::Glass;
  scene.objects[2].mirror = 0.0;
  scene.objects[2].ior = 1.5;
  scene.objects[2].color = {0.95, 0.95, 1.0};
  return scene;
}

// The kernel's paths against the CPU's for the same seed: every value
// finite, 80 % of the pixels within 1e-3 (paths that part by rounding make
// the rest) and the mean difference within 3 standard errors.
void expect_paths_agree(const sol::RenderResult& gpu, const sol::RenderResult& cpu, const char* what) {
  const std::size_t n = cpu.rgba.size() / 4;
  for (float v : gpu.rgba) ASSERT_TRUE(std::isfinite(v)) << what;
  const std::size_t agree = sol::test::pixels_agreeing(gpu, cpu, 1e-3f);
  const sol::test::MeanAndError d = sol::test::red_difference(gpu, cpu);
  std::printf("%s, kernel against CPU: %zu of %zu pixels agree to 1e-3; mean difference %.4f, standard error %.4f\n",
              what, agree, n, d.mean, d.error);
  EXPECT_GE(agree, n * 8 / 10) << what;
  EXPECT_LE(std::abs(d.mean), 3.0 * d.error + 1e-6) << what;
}

TEST(Kernel, PathsAreTheCpuPathsForTheSameSeed) {
  const sol::Scene scene = floor_glow_and_mirror();
  const sol::RenderOptions settings{.width = 24, .height = 16, .samples = 8, .transport = sol::Transport::Path, .seed = 11};
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  const std::size_t n = cpu.rgba.size() / 4;
  expect_paths_agree(gpu, cpu, "paths");
  double lit = 0.0;
  for (std::size_t k = 0; k < n; ++k) lit += gpu.object[k] == 1.0f ? gpu.rgba[4 * k] : 0.0;
  EXPECT_GT(lit, 0.0);  // the floor is lit
  EXPECT_EQ(sol::render_scene(renderer, scene, settings).rgba, gpu.rgba);
  sol::RenderOptions other = settings;
  other.seed = 12;
  EXPECT_NE(sol::render_scene(renderer, scene, other).rgba, gpu.rgba);
  expect_no_validation_errors();
}

// A path that leaves the inner wall of an exact ball solves the ball's exit
// by Newton's method on the arc length before it marches the rest of the
// world up to it (MarchResume::exit_k; docs/lighting.md, "Enclosures"):
// inside a dark exact ball whose checkered albedo (0.7) weighs every bounce
// by where it lands, lit by a glowing bound ball inside it (no next-event
// target: every path is reflection sampling's), the kernel's paths are
// the CPU's for the same seed (the CPU steps by the exact distance): at
// least 80 % of the pixels agree to 1e-3 (measured: 79 of 80), the mean
// within 3 standard errors. An exit off the sphere picks other cells of
// the checker and other roulette draws: with the exit taken at the search's
// first trial (the Euclidean chord 2 r cos θ), 41 of 80.
TEST(Kernel, PathsLeavingAnExactBallsInnerWallAreTheCpuPaths) {
  sol::Scene scene;
  scene.camera = {{0.1, -0.05, 0.0}, {1.0, 0.3, 0.1}, {0.0, 0.0, 1.0}, 90.0};
  sol::SceneObject wall{sol::Ball{{0.0, 0.0, 0.0}, 1.0, true}, {0.7, 0.7, 0.7}};
  wall.pattern = sol::Pattern::Checker;
  sol::SceneObject lamp{sol::Ball{{-0.4, 0.2, -0.3}, 0.3, false}, {0.5, 0.5, 0.5}};
  lamp.emission = {2.0, 2.0, 2.0};
  scene.objects = {wall, lamp};
  scene.lights.clear();
  const sol::RenderOptions settings{.width = 10, .height = 8, .samples = 4, .transport = sol::Transport::Path, .seed = 5};
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  EXPECT_EQ(gpu.rays_out_of_steps, 0u);
  expect_paths_agree(gpu, cpu, "paths inside an exact ball");
  expect_no_validation_errors();
}

// Inside a glowing solid on the kernel (as Path.NextEventEstimationFromInsideAGlowingBallAgrees):
// from its inner wall the solid is no target, so in the exact ball's
// furnace next-event estimation alone is reflection sampling, image for
// image; in a room inside a glowing exact ball with a box and a small
// glowing ball (sol::test::room_in_a_glowing_ball), next-event estimation
// alone, reflection sampling alone and both agree within 3 standard
// errors of their pixel differences, and the kernel's combined image with
// the CPU's. Exits aimed 0.01 inside the sphere brightened the combined
// image by 0.13 (the emission met there counted by both strategies).
TEST(Kernel, NextEventEstimationFromInsideAGlowingBallAgrees) {
  const sol::Scene scene = sol::test::room_in_a_glowing_ball();
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene furnace = sol::test::furnace(0.0);
  EXPECT_EQ(sol::render_scene(renderer, furnace, sol::test::path_options(6, 4, 2, 5, sol::PathSampling::GlowOnly)).rgba,
            sol::render_scene(renderer, furnace, sol::test::path_options(6, 4, 2, 5, sol::PathSampling::ReflectionOnly)).rgba)
      << "the ball whose inner wall a path's vertex lies on is no target from there";
  std::vector<sol::RenderResult> images;
  for (const auto sampling : {sol::PathSampling::Combined, sol::PathSampling::ReflectionOnly, sol::PathSampling::GlowOnly}) {
    images.push_back(sol::render_scene(renderer, scene, sol::test::path_options(12, 10, 16, 31, sampling)));
    EXPECT_EQ(images.back().rays_out_of_steps, 0u);
  }
  sol::test::expect_estimators_agree(images[0], images[1], "kernel, combined - reflection");
  sol::test::expect_estimators_agree(images[0], images[2], "kernel, combined - next-event estimation");
  sol::test::expect_estimators_agree(images[1], images[2], "kernel, reflection - next-event estimation");
  sol::test::expect_estimators_agree(
      images[0], sol::render_cpu(scene, sol::test::path_options(12, 10, 4, 32, sol::PathSampling::Combined)),
      "combined, kernel - CPU");
  expect_no_validation_errors();
}

// The gallery's hall of mirrors (docs/gallery/mirror-balls.json: a
// half-silvered ball and a glowing bound ball in the golden quotient, fog,
// up to 4 reflections) by paths: the kernel's are the CPU's for the same
// seed: their means agree within 3 standard errors (the paths themselves
// part after a few reflections in float against double: about half the
// pixels agree to 1e-3, so no share of them is asked). A kernel whose paths
// added a hit's emission after the roulette lost much of the glowing
// ball's light here on lavapipe (mean red 0.087 against the CPU's 0.1006 at
// 64 paths), the sum the same.
TEST(Kernel, PathsInTheHallOfMirrorsAreTheCpuPaths) {
  const sol::Scene scene = sol::parse_scene(R"({"camera": {"position": [0.9, 0.3, 0.45], "forward": [0, 0, -1],
    "up": [0, 1, 0], "fov": 90}, "quotient": "golden", "objects": [{"type": "ball", "center": [0, 0, 0], "radius": 0.3,
    "color": [0.6, 0.6, 0.65], "mirror": 0.85}, {"type": "ball", "center": [0.75, 0.05, 0.3], "radius": 0.1,
    "color": [0.9, 0.55, 0.3], "emission": [0.6, 0.3, 0.1]}], "lights": [{"type": "directional", "direction": [0.3, 0.5, 1]}],
    "fog": {"density": 0.0833}, "max_distance": 12, "max_steps": 400, "max_bounces": 4})");
  const sol::RenderOptions settings{.width = 24, .height = 18, .samples = 16, .transport = sol::Transport::Path, .seed = 3};
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings), cpu = sol::render_cpu(scene, settings);
  const sol::test::MeanAndError d = sol::test::red_difference(gpu, cpu);
  double red = 0.0;
  for (std::size_t k = 0; k < cpu.rgba.size(); k += 4) red += cpu.rgba[k] / static_cast<double>(cpu.rgba.size() / 4);
  std::printf("hall of mirrors: CPU mean red %.4f; kernel - CPU %.4f, standard error %.4f; %zu of %zu pixels agree to 1e-3\n",
              red, d.mean, d.error, sol::test::pixels_agreeing(gpu, cpu, 1e-3f), cpu.rgba.size() / 4);
  EXPECT_GT(red, 0.05);  // the glowing ball's light and its reflections
  EXPECT_LE(std::abs(d.mean), 3.0 * d.error + 1e-6);
  expect_no_validation_errors();
}

// The mirror material (sol/materials/mirror.h, one function both devices
// compile) on the kernel: a white one is the diffuse material with mirror
// share 1 to the bit, with direct light and with paths of one seed; a
// coloured one is the CPU's, with direct light (the mirror scene, pixels
// within the float-vs-double 2e-3 as MirrorsShowTheReflectedScene...) and
// with paths (as PathsAreTheCpuPathsForTheSameSeed: 80 % of the pixels to
// 1e-3, the mean difference within 3 standard errors).
TEST(Kernel, TheMirrorMaterialIsTheCpusTintedMirror) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene diffuse = sol::test::mirror_scene(true);  // its last object: a plane x = 0, mirror 1
  sol::Scene white = diffuse, tinted = diffuse;
  for (sol::Scene* s : {&white, &tinted}) {
    s->objects.back().material = sol::Material::Mirror;
    s->objects.back().mirror = 0.0;
  }
  white.objects.back().color = glm::dvec3(1.0);
  tinted.objects.back().color = {0.9, 0.5, 0.25};
  for (const sol::Transport transport : {sol::Transport::Direct, sol::Transport::Path}) {
    const sol::RenderOptions settings{.width = 32, .height = 24, .samples = 2, .transport = transport, .seed = 3};
    EXPECT_EQ(sol::render_scene(renderer, white, settings).rgba, sol::render_scene(renderer, diffuse, settings).rgba);
  }
  const sol::RenderOptions direct{.width = 48, .height = 32};
  const int differ = sol::test::colour_differences(sol::render_scene(renderer, tinted, direct), sol::render_cpu(tinted, direct), 2e-3);
  std::printf("tinted mirror material: %d of %d pixels differ from the CPU's\n", differ, 48 * 32);
  EXPECT_LE(differ, 48 * 32 / 100);

  sol::Scene paths = floor_glow_and_mirror();
  paths.objects[2].material = sol::Material::Mirror;
  paths.objects[2].mirror = 0.0;
  paths.objects[2].color = {0.9, 0.7, 0.4};
  const sol::RenderOptions settings{.width = 24, .height = 16, .samples = 8, .transport = sol::Transport::Path, .seed = 11};
  expect_paths_agree(sol::render_scene(renderer, paths, settings), sol::render_cpu(paths, settings),
                     "paths with a mirror-material ball");
  expect_no_validation_errors();
}

// The glossy material (sol/materials/glossy.h and sol_specular_direction,
// one function both devices compile) on the kernel: with direct light each
// sample follows one glossy reflection drawn from the pixel's sample's
// random numbers, the CPU's too, so the images agree pixel by pixel as the
// mirror material's (the mirror scene, 16 samples: float against double
// moves a reflected ray that grazes an edge, so at most 1 % of the pixels
// beyond 2e-3, where the mirror material has none); with paths as
// PathsAreTheCpuPathsForTheSameSeed; and a
// glossy furnace (a box emitting 0.5, albedo 0.6, roughness 0.6) holds
// E / (1 - ρ) = 1.25 within 4 standard errors. A white glossy material of
// roughness 0 is the mirror material, to the bit.
TEST(Kernel, TheGlossyMaterialIsTheCpus) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene glossy = sol::test::mirror_scene(true);  // its last object: a plane x = 0, mirror 1
  glossy.objects.back().material = sol::Material::Glossy;
  glossy.objects.back().mirror = 0.0;
  glossy.objects.back().color = {0.9, 0.7, 0.4};
  glossy.objects.back().roughness = 0.3;
  const sol::RenderOptions direct{.width = 48, .height = 32, .samples = 16, .seed = 4};
  const int differ = sol::test::colour_differences(sol::render_scene(renderer, glossy, direct), sol::render_cpu(glossy, direct), 2e-3);
  std::printf("glossy material, direct light: %d of %d pixels differ from the CPU's\n", differ, 48 * 32);
  EXPECT_LE(differ, 48 * 32 / 100);
  sol::Scene sharp = glossy, mirror = glossy;
  sharp.objects.back().roughness = mirror.objects.back().roughness = 0.0;
  mirror.objects.back().material = sol::Material::Mirror;
  const sol::RenderOptions few{.width = 32, .height = 24, .samples = 2, .seed = 4};
  EXPECT_EQ(sol::render_scene(renderer, sharp, few).rgba, sol::render_scene(renderer, mirror, few).rgba);

  sol::Scene paths = floor_glow_and_mirror();
  paths.objects[2].material = sol::Material::Glossy;
  paths.objects[2].mirror = 0.0;
  paths.objects[2].roughness = 0.25;
  paths.objects[2].color = {0.9, 0.7, 0.4};
  const sol::RenderOptions settings{.width = 24, .height = 16, .samples = 8, .transport = sol::Transport::Path, .seed = 11};
  expect_paths_agree(sol::render_scene(renderer, paths, settings), sol::render_cpu(paths, settings),
                     "paths with a glossy ball");

  sol::Scene furnace = sol::test::furnace_in(sol::Box{{0.1, -0.1, 0.05}, {0.6, 0.5, 0.4}});
  furnace.objects[0].material = sol::Material::Glossy;
  furnace.objects[0].roughness = 0.6;
  const sol::RenderResult r =
      sol::render_scene(renderer, furnace, {.width = 6, .height = 6, .samples = 32, .transport = sol::Transport::Path, .seed = 2});
  sol::test::expect_furnace_mean(r, 1.25, "glossy furnace on the kernel");
  expect_no_validation_errors();
}

// The glass material (sol/materials/glass.h and sol_dielectric_direction,
// one function both devices compile) on the kernel, whose rays go on inside
// the solid (HAS_INSIDE) to its far wall and out: a glass ball of index 1
// is not seen (the kernel's image of the scene without it, but for the
// float rounding of the restarted marches: at most 1 % of the pixels beyond
// 2e-3); a ball of index 1.5 renders the CPU's image (the same numbers
// choose reflection or refraction on both: at most 2 % of the pixels beyond
// 0.02 where a ray grazing an edge goes either way), in Sol and in the
// golden quotient, where far images are reached along geodesics that part
// exponentially (the flow is Anosov) and float's rounding already moves
// some pixels of the scene without glass (`own`): twice those may differ
// more; paths through it agree with the CPU's as
// PathsAreTheCpuPathsForTheSameSeed; and glass in a furnace keeps its
// E / (1 - ρ) = 1.25 within 4 standard errors.
TEST(Kernel, TheGlassMaterialIsTheCpus) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* quotient : {"none", "golden"}) {
    const sol::Scene without = sol::test::behind_glass(std::nullopt, quotient),
                     clear = sol::test::behind_glass(1.0, quotient), bent = sol::test::behind_glass(1.5, quotient);
    const sol::RenderOptions settings{.width = 32, .height = 24, .samples = 4, .seed = 9};
    const int unseen = sol::test::colour_differences(sol::render_scene(renderer, clear, settings),
                                                     sol::render_scene(renderer, without, settings), 2e-3);
    const int differ = sol::test::colour_differences(sol::render_scene(renderer, bent, settings), sol::render_cpu(bent, settings), 2e-2);
    // Float's own share: the scene without glass, kernel against CPU.
    const int own = sol::test::colour_differences(sol::render_scene(renderer, without, settings), sol::render_cpu(without, settings), 2e-3);
    std::printf("glass, %s: index 1: %d of %d pixels differ from the scene without it; index 1.5: %d from the CPU's; "
                "without glass the kernel's image differs from the CPU's at %d\n",
                quotient, unseen, 32 * 24, differ, own);
    EXPECT_LE(unseen, 2 * own + 32 * 24 / 100) << quotient;
    EXPECT_LE(differ, 2 * own + 32 * 24 / 50) << quotient;
  }
  const sol::Scene paths = floor_glow_and_glass();
  const sol::RenderOptions settings{.width = 24, .height = 16, .samples = 8, .transport = sol::Transport::Path, .seed = 11};
  expect_paths_agree(sol::render_scene(renderer, paths, settings), sol::render_cpu(paths, settings), "paths through a glass ball");
  // Lossless glass keeps a furnace (as Path.GlassInAFurnaceKeepsItsRadiance).
  const sol::RenderResult r =
      sol::render_scene(renderer, sol::test::glass_furnace(), {.width = 8, .height = 8, .samples = 32, .transport = sol::Transport::Path, .seed = 5});
  sol::test::expect_furnace_mean(r, 1.25, "glass in a furnace on the kernel");
  expect_no_validation_errors();
}

// A presenter's refinement by paths (solview --refine-paths): the k-th
// path of every pixel recorded into the running mean, one frame after the
// other (PixelSample::path), is render()'s image of as many paths, to the
// bit (the same dispatches with the same uniforms).
// Consecutive ranges of samples (RenderOptions::first_sample) weighted by
// their counts are the render of all of them on the kernel too: the same
// sample points and paths (to float rounding of the running means).
TEST(Kernel, BatchesOfSamplesMakeTheWholeRender) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const auto& [scene, transport] : {std::pair{sol::preset_scene("plane"), sol::Transport::Direct},
                                         std::pair{floor_glow_and_mirror(), sol::Transport::Path}}) {
    renderer.set_world(scene);
    sol::RenderOptions all{.width = 16, .height = 12, .samples = 5, .transport = transport, .seed = 3};
    const sol::RenderResult whole = renderer.render(scene.camera, all);
    sol::RenderOptions first = all, rest = all;
    first.samples = 2;
    rest.first_sample = 2;
    rest.samples = 3;
    rest.aovs = false;
    const sol::RenderResult a = renderer.render(scene.camera, first), b = renderer.render(scene.camera, rest);
    double worst = 0.0;
    for (std::size_t k = 0; k < whole.rgba.size(); ++k) {
      worst = std::max(worst, static_cast<double>(std::abs((2.0f * a.rgba[k] + 3.0f * b.rgba[k]) / 5.0f - whole.rgba[k])));
    }
    EXPECT_LT(worst, 1e-5) << static_cast<int>(transport);  // float running means of up to 5 values near 1
    EXPECT_NE(a.rgba, whole.rgba);
  }
  expect_no_validation_errors();
}

TEST(Kernel, PathsRecordedOneByOneAreTheRenderedImage) {
  const sol::Scene scene = floor_glow_and_mirror();
  const int w = 16, h = 12, samples = 4;
  sol::vk::MarchRenderer renderer(vk_context());
  renderer.set_world(scene);
  const sol::RenderResult rendered = renderer.render(
      scene.camera, {.width = w, .height = h, .samples = samples, .transport = sol::Transport::Path, .seed = 5});
  sol::vk::StorageImage target(vk_context(), w, h);
  for (int k = 0; k < samples; ++k) {
    const sol::vk::PixelSample sample{k == 0 ? glm::dvec2(0.5) : sol::pixel_sample(k), 1.0 / (k + 1), k, 5};
    vk_context().submit_and_wait([&](VkCommandBuffer cb) { renderer.record(cb, std::span(&scene.camera, 1), w, h, target, sample); });
  }
  EXPECT_EQ(target.download(), rendered.rgba);
  double lit = 0.0;
  for (float v : rendered.rgba) lit += v;
  EXPECT_GT(lit, 0.0);
  try {
    vk_context().submit_and_wait([&](VkCommandBuffer cb) {
      renderer.record(cb, std::span(&scene.camera, 1), w, h, target, sol::vk::PixelSample{{0.5, 0.5}, 1.0, -2, 0});
    });
    ADD_FAILURE() << "a path index of -2 accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("its path be -1 or an index"), std::string::npos) << e.what();
  }
  expect_no_validation_errors();
}

// Next-event estimation to a glowing exact ball on the kernel (the CPU's
// glow_sample: a point of the exact sphere, connected by the connection
// solver, visible by a march) with the same random numbers as the CPU: for
// each of the three samplings, most pixels agree to float rounding with
// the CPU's image of the same seed (as above: at least 80 %), and the
// three kernel images agree with each other as unbiased estimators of one
// image (their mean difference within 3 standard errors, as the CPU's
// Path.ReflectionSamplingGlowSamplingAndBothAgree). The quotient's targets
// (a glowing ball's images) are the furnace's above, alone and combined.
// An eye inside a closed exact ball that neither glows nor mirrors sees no
// light at all on a path, whatever shines outside: an exact point light
// with shadows (with a reach in Sol) and a glowing exact ball, with a mirror
// ball, a box and a tube beside them, in Sol and in the golden quotient.
// Every path stays inside (its segments, shadow rays and connections end
// on the inner wall), so every pixel is exactly 0 on both devices. (The
// kernel once added an exact light's point-light fallback inside, where its
// connection solve came back empty: blue pixels up to 1.6.)
TEST(Kernel, PathsInsideAClosedBallSeeNoLight) {
  const std::string objects = R"("objects": [
      {"type": "plane_z", "c": 0, "color": [0.8, 0.8, 0.8], "pattern": "checker"},
      {"type": "ball", "center": [0, 0, 0.6], "radius": 0.4, "material": "mirror"},
      {"type": "ball", "center": [1, 0.5, 0.6], "radius": 0.3, "exact": true, "emission": [4, 3, 2]},
      {"type": "ball", "center": [-1, 0.5, 0.6], "radius": 0.3, "exact": true, "color": [0.3, 0.6, 0.9]},
      {"type": "box", "center": [-1, 1.5, 0.5], "half_size": [0.15, 0.15, 0.15]},
      {"type": "tube", "axis": "z", "through": [0, 0, 0], "radius": 0.1}],)";
  const std::string eye = R"({"camera": {"position": [-1, 0.5, 0.6]},)";
  const std::vector<sol::Scene> scenes = {
      sol::parse_scene(eye + objects + R"("lights": [{"type": "point", "position": [0.5, -1, 2], "intensity": 10,
                                          "exact": true, "reach": 2, "shadows": true}]})"),
      sol::parse_scene(eye + objects + R"("lights": [{"type": "point", "position": [0.2, -0.3, 0.4], "intensity": 10,
                                          "exact": true, "shadows": true}], "quotient": "golden"})")};
  sol::vk::MarchRenderer renderer(vk_context());
  for (const sol::Scene& scene : scenes) {
    const char* where = scene.quotient() == sol::Quotient::Golden ? "golden" : "Sol";
    const sol::RenderResult gpu = sol::render_scene(
        renderer, scene, {.width = 16, .height = 12, .samples = 4, .transport = sol::Transport::Path, .seed = 1});
    // (The CPU's paths inside an exact ball are dear: fewer of them.)
    const sol::RenderResult cpu =
        sol::render_cpu(scene, {.width = 6, .height = 4, .samples = 2, .transport = sol::Transport::Path, .seed = 1});
    for (const sol::RenderResult* image : {&gpu, &cpu}) {
      float most = 0.0f;
      for (std::size_t k = 0; k < image->rgba.size(); k += 4) {
        most = std::max({most, image->rgba[k], image->rgba[k + 1], image->rgba[k + 2]});
      }
      EXPECT_EQ(most, 0.0f) << where << (image == &gpu ? " kernel" : " CPU");
    }
  }
  expect_no_validation_errors();
}

// The three strategies' images of `scene` on the kernel (10 × 10, 4 paths
// a pixel, one seed: combined, reflection, next-event estimation), each
// the CPU's paths for the same seed in at least 80 % of the pixels to 1e-3.
std::vector<sol::RenderResult> three_strategies_as_the_cpu(sol::vk::MarchRenderer& renderer, const sol::Scene& scene,
                                                           const std::string& where) {
  std::vector<sol::RenderResult> images;
  for (const auto sampling : {sol::PathSampling::Combined, sol::PathSampling::ReflectionOnly, sol::PathSampling::GlowOnly}) {
    const sol::RenderOptions settings{.width = 10, .height = 10, .samples = 4, .transport = sol::Transport::Path,
                                      .seed = 21, .path_sampling = sampling};
    images.push_back(sol::render_scene(renderer, scene, settings));
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const std::size_t n = cpu.rgba.size() / 4;
    const std::size_t agree = sol::test::pixels_agreeing(images.back(), cpu, 1e-3f);
    std::printf("%s, sampling %d: %zu of %zu pixels agree with the CPU's to 1e-3 (rays out of steps: kernel %llu, CPU %llu)\n",
                where.c_str(), static_cast<int>(sampling), agree, n,
                static_cast<unsigned long long>(images.back().rays_out_of_steps),
                static_cast<unsigned long long>(cpu.rays_out_of_steps));
    EXPECT_GE(agree, n * 8 / 10) << where << ", sampling " << static_cast<int>(sampling);
  }
  return images;
}

TEST(Kernel, PathsReachGlowingBallsAsTheCpuPathsDo) {
  sol::vk::MarchRenderer renderer(vk_context());
  const std::vector<sol::RenderResult> images = three_strategies_as_the_cpu(renderer, sol::test::glow_over_plane(), "glow");
  sol::test::expect_estimators_agree(images[0], images[1], "kernel, combined - reflection");
  sol::test::expect_estimators_agree(images[0], images[2], "kernel, combined - glow");
  sol::test::expect_estimators_agree(images[1], images[2], "kernel, reflection - glow");
  expect_no_validation_errors();
}

// The kernel's next-event estimation to a glowing box and a glowing bound
// ball (lamp_over_plane: a lamp over a plane beside a ball;
// sol/surface_light.h's points, shared with the CPU, and the connection
// solves a world with exact balls takes, which such a world loads too):
// in Sol and in the golden quotient (where they are not targets: the
// kernel's paths, reflection's alone, are still the CPU's),
// for each strategy the kernel's paths are the CPU's for the same seed (at
// least 80 % of the pixels to 1e-3: three_strategies_as_the_cpu;
// without the connection table the kernel's light points found no way and
// its image came out darker), and the kernel's three estimators agree (in
// the quotient they are one, image for image).
TEST(Kernel, PathsReachGlowingBoxesAndBoundBallsAsTheCpuPathsDo) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const auto& [lamp, golden] : {std::pair{sol::test::flat_box_lamp(), false}, std::pair{sol::test::flat_box_lamp(), true},
                                     std::pair{sol::test::bound_ball_lamp(), false}, std::pair{sol::test::bound_ball_lamp(), true}}) {
    const sol::Scene scene = sol::test::lamp_over_plane(lamp, golden);
    const std::string where = std::string(std::holds_alternative<sol::Box>(lamp) ? "box, " : "bound ball, ") +
                              (golden ? "golden, " : "Sol, ");
    const std::vector<sol::RenderResult> images = three_strategies_as_the_cpu(renderer, scene, where);
    if (golden) {  // not targets: the three strategies are reflection's, path for path (the same seed)
      EXPECT_EQ(images[0].rgba, images[1].rgba) << where;
      EXPECT_EQ(images[0].rgba, images[2].rgba) << where;
      continue;
    }
    sol::test::expect_estimators_agree(images[0], images[1], "kernel, " + where + "combined - reflection");
    sol::test::expect_estimators_agree(images[0], images[2], "kernel, " + where + "combined - glow");
    sol::test::expect_estimators_agree(images[1], images[2], "kernel, " + where + "reflection - glow");
  }
  expect_no_validation_errors();
}

// The kernel's next-event estimation to glowing tubes (along x, y and
// vertical) over a floor: the window about the diffuse point's foot on the
// axis and its points from sol/surface_light.h, shared with the CPU. For each strategy the
// kernel's paths are the CPU's for the same seed
// (three_strategies_as_the_cpu), its three estimators agree, and no ray
// runs out of steps on either device. A tube in the golden quotient and a
// glowing plane (a ceiling, a wall) are no targets: the three strategies
// one image.
TEST(Kernel, PathsReachGlowingTubesAsTheCpuPathsDo) {
  sol::vk::MarchRenderer renderer(vk_context());
  const std::vector<std::pair<std::string, sol::Shape>> lamps = {
      {"tube along x", sol::test::tube_lamp(sol::TubeAxis::X)}, {"tube along y", sol::test::tube_lamp(sol::TubeAxis::Y)},
      {"vertical tube", sol::test::tube_lamp(sol::TubeAxis::Z)}};
  for (const auto& [kind, lamp] : lamps) {
    const sol::Scene scene = sol::test::lamp_over_plane(lamp);
    const std::vector<sol::RenderResult> images = three_strategies_as_the_cpu(renderer, scene, kind);
    sol::test::expect_estimators_agree(images[0], images[1], "kernel, " + kind + ", combined - reflection");
    sol::test::expect_estimators_agree(images[0], images[2], "kernel, " + kind + ", combined - glow");
    sol::test::expect_estimators_agree(images[1], images[2], "kernel, " + kind + ", reflection - glow");
    // No ray out of steps: a reflected path that leaves the floor at u_z ≈ 0.004 (under the tube along x) bends
    // back into it and ran out on both devices, until the floor's pass ended where u_z turns.
    for (const sol::RenderResult& image : images) EXPECT_EQ(image.rays_out_of_steps, 0u) << kind;
    const sol::RenderOptions reflection{.width = 10, .height = 10, .samples = 4, .transport = sol::Transport::Path,
                                        .seed = 21, .path_sampling = sol::PathSampling::ReflectionOnly};
    EXPECT_EQ(sol::render_cpu(scene, reflection).rays_out_of_steps, 0u) << kind << ", CPU";
  }
  // (A vertical tube in the quotient is the closed curve of γ3 through a lattice point.)
  const sol::Tube gamma3 = sol::make_tube(sol::TubeAxis::Z, {0.0, 0.0, 0.0}, 0.04, sol::Lattice::default_axes());
  for (const auto& [kind, scene] : {std::pair{"vertical tube, golden", sol::test::lamp_over_plane(gamma3, true)},
                                    std::pair{"ceiling", sol::test::lamp_over_plane(sol::test::ceiling_lamp())},
                                    std::pair{"wall", sol::test::lamp_over_plane(sol::test::wall_lamp())}}) {
    const std::vector<sol::RenderResult> images = three_strategies_as_the_cpu(renderer, scene, kind);
    EXPECT_EQ(images[0].rgba, images[1].rgba) << kind;
    EXPECT_EQ(images[0].rgba, images[2].rgba) << kind;
  }
  expect_no_validation_errors();
}

// The same lamps in a crowd (eight small balls far away make the world
// one: march/crowd.glsl): a crowd's glowing objects are targets on both
// devices (its first kListedObjects of them: sol::glow_target_objects, the
// kernel's Params::crowd_targets), an exact ball's too (before, a crowd's
// boxes, bound balls and tubes were found by reflection alone and its
// exact balls path traced on the CPU alone). For each strategy the
// kernel's paths are the CPU's for the same seed, the three estimators
// agree, and next-event estimation is taken (its image is not
// reflection's, as it is where there is no target). With nine glowing
// balls the ninth is reflection's alone and the estimators still agree.
TEST(Kernel, PathsReachACrowdsGlowingObjectsAsTheCpuPathsDo) {
  sol::vk::MarchRenderer renderer(vk_context());
  const auto crowded = [](sol::Scene s) {
    for (int k = 0; k < 8; ++k) s.objects.push_back({sol::Ball{{6.0 + k, 6.0, 2.0}, 0.1, false}, {0.5, 0.5, 0.5}});
    return s;
  };
  sol::Scene nine = crowded(sol::test::lamp_over_plane(sol::test::bound_ball_lamp()));
  for (std::size_t k = 3; k < nine.objects.size(); ++k) nine.objects[k].emission = {0.5, 0.5, 0.5};
  ASSERT_EQ(sol::glow_target_objects(sol::MarchWorld(nine)).size(), sol::kListedObjects);
  const std::pair<std::string, sol::Scene> worlds[] = {
      {"box, crowd", crowded(sol::test::lamp_over_plane(sol::test::flat_box_lamp()))},
      {"bound ball, crowd", crowded(sol::test::lamp_over_plane(sol::test::bound_ball_lamp()))},
      {"tube along x, crowd", crowded(sol::test::lamp_over_plane(sol::test::tube_lamp(sol::TubeAxis::X)))},
      {"exact ball, crowd", crowded(sol::test::lamp_over_plane(sol::Ball{{0.0, 0.1, 0.4}, 0.12, true}))},
      {"nine glowing balls, crowd", nine}};
  for (const auto& [where, scene] : worlds) {
    ASSERT_GT(scene.objects.size(), sol::kListedObjects) << where;
    EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene, sol::Transport::Path), "") << where;
    const std::vector<sol::RenderResult> images = three_strategies_as_the_cpu(renderer, scene, where);
    EXPECT_NE(images[1].rgba, images[2].rgba) << where;
    sol::test::expect_estimators_agree(images[0], images[1], "kernel, " + where + ", combined - reflection");
    sol::test::expect_estimators_agree(images[0], images[2], "kernel, " + where + ", combined - glow");
    sol::test::expect_estimators_agree(images[1], images[2], "kernel, " + where + ", reflection - glow");
  }
  expect_no_validation_errors();
}

// A lamp over a floor, path traced: next-event estimation's connections
// and the paths' segments leave the floor and the lamp's faces almost
// level, and a segment or connection that grazes a face bends back into
// the box. Neither device runs out of march steps on them (at most one ray
// in 1000 paths; stepping by |z - c| near the floor, by the box's bound on
// the kernel's path segments and passing the face it bends back into, the
// kernel ran 3.6 % of its paths out of steps, the CPU 1.7 %), and the
// kernel's image is the CPU's (mean within 1 %: the same seed's differ by
// 0.02 %, two seeds' by 0.4 %; seeing every solid from inside on the
// kernel's paths, tried for the same end, made it 5 % brighter).
TEST(Kernel, PathsLeavingAFloorOrAFaceAlmostLevelDoNotRunOutOfSteps) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene scene = sol::test::lamp_over_plane(sol::test::flat_box_lamp());
  const sol::RenderOptions settings{.width = 32, .height = 24, .samples = 16, .transport = sol::Transport::Path, .seed = 5};
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  const std::uint64_t paths = 32 * 24 * 16;
  std::printf("lamp over a floor, %llu paths: out of steps kernel %llu, CPU %llu\n", static_cast<unsigned long long>(paths),
              static_cast<unsigned long long>(gpu.rays_out_of_steps), static_cast<unsigned long long>(cpu.rays_out_of_steps));
  EXPECT_LE(gpu.rays_out_of_steps * 1000, paths);
  EXPECT_LE(cpu.rays_out_of_steps * 1000, paths);
  EXPECT_NEAR(sol::test::red_mean(gpu).mean / sol::test::red_mean(cpu).mean, 1.0, 0.01);
  expect_no_validation_errors();
}

// Lamps over a floor (a flat box, a tube along x, a glowing ceiling), path
// traced, as a listed world and as a crowd (eight small balls far away
// make it one: march/crowd.glsl): a connection or a segment that leaves
// a face almost level and bends back into the solid it leaves (from a
// box's top towards a point of its side, skimming the top), or a floor
// it leaves (u_z turns), is blocked there. Passed until 2 hit_epsilon
// deep, 2 hit_epsilon a step, the kernel ran such rays out of steps: 15,
// 38, 55 and 5 of these renders' (box listed, box and tube crowded,
// ceiling crowded), the CPU none (it sees the solid from inside and steps
// by its faces). Now no ray on the kernel.
TEST(Kernel, PathsSkimmingTheSolidTheyLeaveDoNotRunOutOfSteps) {
  sol::vk::MarchRenderer renderer(vk_context());
  const auto crowded = [](sol::Scene s) {
    for (int k = 0; k < 8; ++k) s.objects.push_back({sol::Ball{{6.0 + k, 6.0, 2.0}, 0.1, false}, {0.5, 0.5, 0.5}});
    return s;
  };
  const std::pair<const char*, sol::Scene> worlds[] = {
      {"box", sol::test::lamp_over_plane(sol::test::flat_box_lamp())},
      {"box, crowd", crowded(sol::test::lamp_over_plane(sol::test::flat_box_lamp()))},
      {"tube along x, crowd", crowded(sol::test::lamp_over_plane(sol::test::tube_lamp(sol::TubeAxis::X)))},
      {"ceiling, crowd", crowded(sol::test::lamp_over_plane(sol::test::ceiling_lamp()))}};
  for (const auto& [name, scene] : worlds) {
    ASSERT_EQ(scene.objects.size() > sol::kListedObjects, std::string(name).ends_with("crowd")) << name;
    const sol::RenderOptions settings{.width = 96, .height = 72, .samples = 16, .transport = sol::Transport::Path, .seed = 3};
    const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
    std::printf("lamp over a floor (%s): %llu rays out of steps on the kernel\n", name,
                static_cast<unsigned long long>(gpu.rays_out_of_steps));
    EXPECT_EQ(gpu.rays_out_of_steps, 0u) << name;
  }
  expect_no_validation_errors();
}

// Camera rays that turn just short of a plane z = c, in worlds of planes
// alone (a sandwich seen along x = y, whose middle rays climb to within
// 1e-4 of its planes; a cutout plane over a floor, whose rays dive through
// its holes and climb back): the kernel takes no tangent for such rays,
// and stepping by |z - c| about the turning point it ran 51 of each
// render's rays out of steps, the CPU none. It steps by the clearance to
// hit_epsilon of a ray taken as heading for the plane, its |u_z| from the
// height (climb_speed): none now, and the objects the rays meet are the
// CPU's but for at most 1 % of the pixels (a ray whose turning point lies
// within float's error of the hit band may meet the plane on one device
// and miss it on the other).
TEST(Kernel, CameraRaysTurningJustShortOfAPlaneDoNotRunOutOfSteps) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene sandwich;
  sandwich.camera = {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {0.0, 0.0, 1.0}, 100.0};
  sandwich.objects.clear();  // (one by one, as in sol::test::glow_over_plane_golden)
  sandwich.objects.push_back({sol::PlaneZ{0.25}, {0.35, 0.6, 0.95}, sol::Pattern::Circles});
  sandwich.objects.push_back({sol::PlaneZ{-0.25}, {0.95, 0.55, 0.3}, sol::Pattern::Circles});
  sol::Scene cutout;
  cutout.camera = {{0.0, 0.0, 1.5}, {0.3, 0.2, -1.0}, {0.0, 1.0, 0.0}, 90.0};
  cutout.objects.clear();
  cutout.objects.push_back({sol::PlaneZ{0.0}, {0.95, 0.75, 0.3}, sol::Pattern::Circles});
  cutout.objects.back().cutout = true;
  cutout.objects.push_back({sol::PlaneZ{-1.0}, {0.4, 0.6, 0.9}, sol::Pattern::Checker});
  for (const auto& [name, scene] : {std::pair{"sandwich", sandwich}, std::pair{"cutout over a floor", cutout}}) {
    const sol::RenderOptions settings{.width = 96, .height = 72, .samples = 16, .aovs = true};
    const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    std::size_t differ = 0;
    for (std::size_t k = 0; k < cpu.object.size(); ++k) differ += gpu.object[k] != cpu.object[k] ? 1 : 0;
    std::printf("%s: rays out of steps kernel %llu, CPU %llu; %zu of %zu pixels meet another object\n", name,
                static_cast<unsigned long long>(gpu.rays_out_of_steps), static_cast<unsigned long long>(cpu.rays_out_of_steps),
                differ, cpu.object.size());
    EXPECT_EQ(gpu.rays_out_of_steps, 0u) << name;
    EXPECT_EQ(cpu.rays_out_of_steps, 0u) << name;
    EXPECT_LE(differ * 100, cpu.object.size()) << name;
  }
  expect_no_validation_errors();
}

// A glowing bound ball in the golden quotient (lattice-balls with its ball
// glowing, as the gallery's), path traced: a path that leaves a ball's
// image at a grazing angle and bends back into it is blocked 2
// hit_epsilon in, as in Sol. Passed through 2 hit_epsilon a step instead
// (the quotient's march had no such rule), the kernel ran 34 rays of a
// 128 × 96 × 8-path render out of steps (21 still at 1600 steps), the CPU
// none. Now neither device does, and the kernel's mean is the CPU's
// (within 1 %: the same seed's paths, two seeds' means differ by about 0.5 %).
TEST(Kernel, PathsBendingBackIntoABoundBallInTheQuotientDoNotRunOutOfSteps) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene scene = sol::preset_scene("lattice-balls");
  scene.objects[0].emission = {0.6, 0.35, 0.2};
  scene.max_bounces = 4;
  const sol::RenderOptions settings{.width = 96, .height = 72, .samples = 8, .transport = sol::Transport::Path, .seed = 3};
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  std::printf("glowing lattice-balls: out of steps kernel %llu, CPU %llu; red mean kernel %.5f, CPU %.5f\n",
              static_cast<unsigned long long>(gpu.rays_out_of_steps), static_cast<unsigned long long>(cpu.rays_out_of_steps),
              sol::test::red_mean(gpu).mean, sol::test::red_mean(cpu).mean);
  EXPECT_EQ(gpu.rays_out_of_steps, 0u);
  EXPECT_EQ(cpu.rays_out_of_steps, 0u);
  EXPECT_NEAR(sol::test::red_mean(gpu).mean / sol::test::red_mean(cpu).mean, 1.0, 0.01);
  expect_no_validation_errors();
}

// A path-traced world with exact balls is one pipeline on the kernel: each
// pixel's camera ray is its path's first segment, marched by the path's own
// march (PATH_FROM_EYE). Its AOVs are that segment's hit, as the CPU's are
// its camera ray's: in Sol and in the golden quotient, the same object in
// all but a silhouette's pixels (float against double at a grazing edge: at
// most 1 in 50), and where the objects agree the arc length and the hit
// point within 1e-3 (the march's float hit tolerance is 1e-4 of the arc
// length; 1e-3 leaves room for the exact ball's float solve).
TEST(Kernel, PathsFromTheEyeWriteTheCpusAovs) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const sol::Scene& scene : {sol::test::glow_over_plane(), sol::test::glow_over_plane_golden()}) {
    const sol::RenderOptions settings{.width = 24, .height = 18, .samples = 2, .transport = sol::Transport::Path, .seed = 3};
    const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const std::size_t n = cpu.object.size();
    ASSERT_EQ(gpu.object.size(), n);
    std::size_t differ = 0, hits = 0;
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_TRUE(std::isfinite(gpu.rgba[4 * k]) && std::isfinite(gpu.distance[k])) << k;
      if (gpu.object[k] != cpu.object[k]) {
        ++differ;
        continue;
      }
      if (cpu.object[k] == 0.0f) continue;
      ++hits;
      EXPECT_NEAR(gpu.distance[k], cpu.distance[k], 1e-3) << "pixel " << k;
      EXPECT_NEAR(gpu.px[k], cpu.px[k], 1e-3) << "pixel " << k;
      EXPECT_NEAR(gpu.py[k], cpu.py[k], 1e-3) << "pixel " << k;
      EXPECT_NEAR(gpu.pz[k], cpu.pz[k], 1e-3) << "pixel " << k;
      EXPECT_GT(gpu.steps[k], 0.0f) << "pixel " << k;
    }
    std::printf("paths from the eye (%s): %zu of %zu pixels hit the same object, %zu differ\n",
                scene.quotient() == sol::Quotient::Golden ? "golden" : "Sol", hits, n, differ);
    EXPECT_GT(hits, n / 2);
    EXPECT_LE(differ * 50, n);
  }
  expect_no_validation_errors();
}

// Next-event estimation within a glowing ball's reach on the kernel
// (glow_reach: sol_connections with the longer connections' table, the
// reach build): in far_glow most of the light comes along the longer
// geodesics, and the kernel finds them as
// the CPU's sol::geodesics_between does: its image by next-event
// estimation alone is the CPU's for the same seed in at least 12 of the 16
// pixels (to 1e-3; measured 16), its mean the longer connections' light.
TEST(Kernel, GlowReachConnectsAlongTheLongerGeodesicsAsTheCpu) {
  if (!sol::test::full_sweeps()) GTEST_SKIP() << "its own kernel variant, about a minute on lavapipe: SOL_FULL_SWEEPS=1 runs it";
  const sol::Scene scene = sol::test::far_glow(3.0);
  const sol::RenderOptions settings{.width = 4,
                                    .height = 4,
                                    .samples = 4,
                                    .transport = sol::Transport::Path,
                                    .seed = 1,
                                    .path_sampling = sol::PathSampling::GlowOnly};
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
  const sol::RenderResult cpu = sol::render_cpu(scene, settings);
  for (std::size_t k = 0; k < 16; ++k) ASSERT_TRUE(std::isfinite(gpu.rgba[4 * k]));
  const std::size_t agree = sol::test::pixels_agreeing(gpu, cpu, 1e-3f);
  const double mean = sol::test::red_mean(gpu).mean;
  std::printf("glow reach, kernel against CPU: %zu of 16 pixels agree to 1e-3 (means %.4f, %.4f)\n", agree, mean,
              sol::test::red_mean(cpu).mean);
  EXPECT_GE(agree, 12u);
  EXPECT_GT(mean, 0.3);  // the longer connections' light (the minimisers' alone: 0.058 on the CPU)
  expect_no_validation_errors();
}

// A glowing ball's glow_reach above the seed table's (3) keeps path
// tracing on the CPU, and direct light, which never reads it, on the kernel.
TEST(Kernel, GlowReachKeepsOnlyPathsOnTheCpu) {
  sol::Scene scene = sol::test::far_glow(5.0);
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene, sol::Transport::Direct), "");
  EXPECT_NE(sol::vk::MarchRenderer::unsupported(scene, sol::Transport::Path).find("objects[1].glow_reach"), std::string::npos);
  sol::vk::MarchRenderer renderer(vk_context());
  renderer.set_world(scene);
  EXPECT_NO_THROW(renderer.render(scene.camera, {.width = 4, .height = 4}));
  EXPECT_THROW(renderer.render(scene.camera, {.width = 4, .height = 4, .transport = sol::Transport::Path}), sol::NotImplemented);
  // A presenter's path sample (record) is refused as well, before anything is recorded.
  sol::vk::StorageImage target(vk_context(), 4, 4);
  EXPECT_THROW(vk_context().submit_and_wait([&](VkCommandBuffer cb) {
    renderer.record(cb, std::span(&scene.camera, 1), 4, 4, target, sol::vk::PixelSample{{0.5, 0.5}, 1.0, 0, 1});
  }), sol::NotImplemented);
  expect_no_validation_errors();
}

// Monodromies the kernel's float resolves: up to |trace| 200
// (MarchRenderer::kMaxMonodromyTrace) it draws a ball in the bundle of
// [[t - 1, 1], [t - 2, 1]] as the CPU does (pixels more than 0.05 off: at
// most 1 in 200; measured none at 100 and 200, 0.1 % at 300 and 36 % at
// 10^9 + 1, which it speckled); above, unsupported() says so with the
// figure and --device auto takes the CPU.
TEST(Kernel, LargeMonodromyTracesRenderOnTheCpu) {
  auto bundle = [](long long t) {
    // (From a preset: GCC 12 warns of an uninitialised light in a default World built inline.)
    sol::Scene s = sol::preset_scene("lattice-balls");
    s.objects.resize(1);
    s.objects[0].shape = sol::Ball{{0.0, 0.0, 0.0}, 0.2, false};
    s.camera = {{0.3, 0.2, 0.4}, {-1.0, -0.5, -0.8}, {0.0, 0.0, 1.0}, 90.0};
    sol::set_space(s, sol::MonodromySpace{{t - 1, 1, t - 2, 1}, std::nullopt});
    return s;
  };
  sol::vk::MarchRenderer renderer(vk_context());
  for (const long long t : {7LL, 200LL}) {
    const sol::Scene s = bundle(t);
    ASSERT_EQ(sol::vk::MarchRenderer::unsupported(s), "") << t;
    const sol::RenderResult gpu = sol::test::render(renderer, s, 48, 32);
    const sol::RenderResult cpu = sol::render_cpu(s, {.width = 48, .height = 32});
    const int differ = sol::test::colour_differences(gpu, cpu, 0.05);
    std::printf("trace %lld: %d of 1536 pixels differ from the CPU's by more than 0.05\n", t, differ);
    EXPECT_LE(differ, 1536 / 200) << t;
  }
  for (const long long t : {201LL, 1000000001LL}) {
    const std::string why = sol::vk::MarchRenderer::unsupported(bundle(t));
    EXPECT_NE(why.find("quotient.monodromy: trace " + std::to_string(t)), std::string::npos) << why;
    EXPECT_NE(why.find("CPU only"), std::string::npos) << why;
  }
  expect_no_validation_errors();
}

// A crowded quotient (trace4-balls in a monodromy's small fibre: 74 and
// 148 images near the domain, against the golden lattice's 50; the
// kernel's limit is the CPU's, sol::QuotientField::kMaxImages, and image
// indices above 127 fill the field's candidate bytes) renders on the
// kernel as on the CPU: the same objects (at most 1 % of the pixels apart, a grazing ray
// in float against double) and arc lengths to 1e-3 where both hit, as
// PresetsMatchTheCpuRenderer.
TEST(Kernel, CrowdedQuotientsRenderOnTheKernelAsOnTheCpu) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const double area : {0.3, 0.12}) {
    sol::Scene crowded = sol::preset_scene("trace4-balls");
    sol::set_space(crowded, sol::MonodromySpace{{3, 1, 2, 1}, area});
    const std::size_t images = sol::quotient_images(crowded).size();
    std::printf("area %g: %zu images\n", area, images);
    ASSERT_GT(images, 64u);
    ASSERT_LE(images, sol::QuotientField::kMaxImages);
    EXPECT_EQ(sol::vk::MarchRenderer::unsupported(crowded), "");
    sol::RenderOptions settings;
    settings.width = 48;
    settings.height = 32;
    const sol::RenderResult cpu = sol::render_cpu(crowded, settings);
    const sol::RenderResult gpu = sol::test::render(renderer, crowded, settings.width, settings.height);
    const Comparison c = compare(gpu, cpu);
    int hits = 0, far = 0;
    for (std::size_t k = 0; k < cpu.object.size(); ++k) {
      if (cpu.object[k] == 0.0f || gpu.object[k] != cpu.object[k]) continue;
      ++hits;
      far += std::abs(gpu.distance[k] - cpu.distance[k]) > 1e-3f;
    }
    std::printf("crowded quotient, %zu images: hit mask differs at %d of %d pixels, %d hits, %d apart by more than 1e-3\n",
                images, c.mask_differs, c.pixels, hits, far);
    EXPECT_GT(hits, c.pixels / 4);
    EXPECT_LE(c.mask_differs, c.pixels / 100);
    EXPECT_LE(far, c.pixels / 100);
  }
  for (const char* name : {"lattice-balls", "lattice-pillars", "lattice-boxes", "trace4-balls", "trace4-pillars", "halfturn-balls"}) {
    EXPECT_EQ(sol::vk::MarchRenderer::unsupported(sol::preset_scene(name)), "") << name;
  }
  expect_no_validation_errors();
}

// The quotient march takes every ray off the plane regime
// (sol_direction_off_plane_regime in sol_forward.glsl: μ = |ab| raised to
// 2e-24, or a vertical line), so that its steps leave that regime's
// position out. The rays of that regime are those in a plane x = const or
// y = const through the eye: with an odd image size the middle column and
// row of a camera looking along z (lattice-balls) are such rays (the
// middle pixel's sample lies on the axis), and its middle pixel is
// vertical; a camera looking along x has its middle column in a plane
// y = const. Each of those pixels against the CPU renderer, which marches
// them in double by its own plane and vertical regimes.
TEST(Kernel, QuotientRaysInPlanesXOrYConstMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene balls = sol::preset_scene("lattice-balls");
  sol::Scene pillars = sol::preset_scene("lattice-pillars");
  pillars.camera.forward = {1.0, 0.0, 0.0};
  pillars.camera.up = {0.0, 0.0, 1.0};
  const int width = 33, height = 25;
  for (const sol::Scene& scene : {balls, pillars}) {
    const int mid_i = width / 2, mid_j = height / 2;
    const bool along_z = scene.camera.forward.z != 0.0;
    // The pixels of the plane regime, checked from the camera's own rays:
    // one horizontal component exactly 0.
    std::vector<std::pair<int, int>> pixels;
    for (int j = 0; j < height; ++j) pixels.emplace_back(mid_i, j);
    if (along_z) {
      for (int i = 0; i < width; ++i) {
        if (i != mid_i) pixels.emplace_back(i, mid_j);
      }
    }
    for (const auto& [i, j] : pixels) {
      const dvec3 d = sol::camera_ray(scene.camera, i, j, width, height);
      ASSERT_EQ(d.x * d.y, 0.0) << i << ", " << j;
    }
    sol::RenderOptions settings;
    settings.width = width;
    settings.height = height;
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const sol::RenderResult gpu = sol::test::render(renderer, scene, width, height);
    const sol::MarchWorld world(scene);
    int hits = 0, mask_differs = 0, grazing = 0;
    double worst = 0.0;
    for (const auto& [i, j] : pixels) {
      const auto k = static_cast<std::size_t>(j * width + i);
      ASSERT_TRUE(std::isfinite(gpu.distance[k]) && std::isfinite(gpu.px[k]) && std::isfinite(gpu.py[k]) &&
                  std::isfinite(gpu.pz[k]))
          << i << ", " << j;
      if (gpu.object[k] != cpu.object[k]) {
        ++mask_differs;
        continue;
      }
      if (cpu.object[k] == 0.0f) continue;
      ++hits;
      const double difference = std::abs(gpu.distance[k] - cpu.distance[k]);
      if (difference < 1e-3) {
        worst = std::max(worst, difference);
        continue;
      }
      // A grazing hit, as PresetsMatchTheCpuRenderer's: the kernel's point
      // lies within hit_epsilon of the surface by the double bounds.
      ++grazing;
      const double gap = surface_gap(world, static_cast<int>(gpu.object[k]), dvec3(gpu.px[k], gpu.py[k], gpu.pz[k]));
      EXPECT_GT(gap, -1e-5) << i << ", " << j;
      EXPECT_LT(gap, scene.hit_epsilon + 1e-5) << i << ", " << j;
      EXPECT_LT(difference, 0.05) << i << ", " << j;
    }
    std::printf("%s: %zu rays of the plane regime, %d hits (%d grazing), mask differs at %d, worst distance difference "
                "of the others %.2e\n",
                along_z ? "lattice-balls" : "lattice-pillars along x", pixels.size(), hits, grazing, mask_differs, worst);
    EXPECT_GE(hits, static_cast<int>(pixels.size()) / 4);  // the lines do meet objects
    // As PresetsMatchTheCpuRenderer (1% of pixels there): a graze may go
    // either way, at one of these pixels.
    EXPECT_LE(mask_differs + grazing, 1);
  }
  expect_no_validation_errors();
}

// A quotient world of several kinds (tubes, a plane z = c, a ball): the
// kernel reads each image's code (march/quotient.glsl's image_type, which a world of
// one kind does not read) and tells them apart as the CPU reference does.
TEST(Kernel, QuotientWorldOfSeveralKindsMatchesTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Lattice lattice = sol::Lattice::golden();
  sol::Scene mixed = sol::preset_scene("lattice-pillars");
  mixed.objects.push_back({sol::PlaneZ{0.2 * lattice.height()}, {0.8, 0.8, 0.8}, sol::Pattern::Checker});
  mixed.objects.push_back({sol::Ball{{0.9, 0.9, 0.6}, 0.15}, {0.9, 0.5, 0.3}});
  sol::RenderOptions settings;
  settings.width = 32;
  settings.height = 24;
  const sol::RenderResult mixed_cpu = sol::render_cpu(mixed, settings);
  int tube = 0, plane = 0, ball = 0;  // objects 1-3, 4, 5
  for (float object : mixed_cpu.object) {
    tube += object >= 1.0f && object <= 3.0f ? 1 : 0;
    plane += object == 4.0f ? 1 : 0;
    ball += object == 5.0f ? 1 : 0;
  }
  std::printf("mixed quotient world: %d tube, %d plane, %d ball pixels\n", tube, plane, ball);
  EXPECT_GT(std::min({tube, plane, ball}), 10);  // each kind is seen
  const Comparison m = compare(sol::test::render(renderer, mixed, 32, 24), mixed_cpu);
  EXPECT_LE(m.mask_differs, m.pixels / 100);
  EXPECT_LE(m.color_differs, m.pixels / 100);
  EXPECT_LT(m.distance, 2e-3);  // as PresetsMatchTheCpuRenderer's quotient presets
  expect_no_validation_errors();
}

// The quotient's tubes reach the march as four-word records (Image::bound:
// a horizontal tube's direction scaled by its radius and turned so that its
// x component is not negative, a vertical one's radius negated). Tubes of
// each case against the CPU reference, which marches the tubes themselves
// in double: along -γ1 and -γ2 (directions of negative x component, turned;
// the quotient takes horizontal tubes along γ1 and γ2 only), along γ2 as
// given, and vertical.
TEST(Kernel, QuotientTubesOfEveryRecordMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Lattice lattice = sol::Lattice::golden();
  sol::Scene tubes;
  tubes.space = sol::GoldenSpace{};
  tubes.camera = {{1.1, 0.4, 0.5 * lattice.height()}, {1.0, 0.6, -0.15}, {0.0, 0.0, 1.0}, 100.0};
  tubes.max_distance = 6.0;
  tubes.max_steps = 400;
  tubes.fog_density = 1.0 / 5.0;
  const dvec3 gamma1 = sol::tube_axis_direction(sol::TubeAxis::Gamma1, sol::Lattice::golden()), gamma2 = sol::tube_axis_direction(sol::TubeAxis::Gamma2, sol::Lattice::golden());
  tubes.objects = {{sol::Tube{{0.0, 0.9, 0.3}, -gamma1, 0.08}, {0.9, 0.35, 0.3}, sol::Pattern::Checker},
                   {sol::Tube{{1.6, 0.0, 0.7}, -gamma2, 0.07}, {0.35, 0.8, 0.4}, sol::Pattern::Checker},
                   {sol::make_tube(sol::TubeAxis::Gamma2, {0.4, 0.2, 0.1}, 0.09, sol::Lattice::golden()), {0.9, 0.8, 0.2}, sol::Pattern::Checker},
                   {sol::make_tube(sol::TubeAxis::Z, sol::multiply(lattice.element(1, 0, 0), dvec3(0.0)), 0.1, sol::Lattice::golden()), {0.35, 0.5, 0.95},
                    sol::Pattern::Checker}};
  sol::RenderOptions settings;
  settings.width = 32;
  settings.height = 24;
  const sol::RenderResult cpu = sol::render_cpu(tubes, settings);
  std::array<int, 4> seen{};
  for (float object : cpu.object) {
    if (object >= 1.0f) ++seen[static_cast<std::size_t>(object) - 1];
  }
  std::printf("quotient tubes along -gamma1, -gamma2, gamma2 and z: %d, %d, %d, %d pixels\n", seen[0], seen[1], seen[2],
              seen[3]);
  EXPECT_GT(*std::min_element(seen.begin(), seen.end()), 10);  // each record's case is seen
  const Comparison c = compare(sol::test::render(renderer, tubes, 32, 24), cpu);
  std::printf("hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n", c.mask_differs,
              c.pixels, c.color_differs, c.distance);
  EXPECT_LE(c.mask_differs, c.pixels / 100);
  EXPECT_LE(c.color_differs, c.pixels / 100);
  EXPECT_LT(c.distance, 2e-3);  // as PresetsMatchTheCpuRenderer's quotient presets
  expect_no_validation_errors();
}

TEST(Kernel, PlaneAovsLieOnThePlane) {
  sol::vk::MarchRenderer renderer(vk_context());
  // Full size: hits that stop just below z = 0 in float occur near the centre rows.
  const sol::RenderResult r = sol::test::render(renderer, sol::preset_scene("plane"), 512, 512);
  int hits = 0, unlit = 0;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    if (r.object[k] == 1.0f) {
      ++hits;
      EXPECT_LT(std::abs(r.pz[k]), 1e-4f);
      // Lit from above: red >= 0.3 (pattern) * 0.95 * (0.15 + 0.85 * 0.87) = 0.25; a
      // normal facing away (a hit stopped just below z = 0) would give 0.043.
      if (r.rgba[4 * k] <= 0.2f) ++unlit;
    } else {
      EXPECT_EQ(r.object[k], 0.0f);
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_EQ(unlit, 0);
}

TEST(Kernel, FarObserverSeesTheSameImage) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene scene = sol::preset_scene("plane");
  const sol::RenderResult here = sol::test::render(renderer, scene, 32, 32);
  scene.camera.position = dvec3(1e6, -1e6, 1.5);  // (X, Y, 0) * (0, 0, 1.5): a symmetry of `plane`
  const sol::RenderResult there = sol::test::render(renderer, scene, 32, 32);
  EXPECT_EQ(here.object, there.object);
  EXPECT_EQ(here.rgba, there.rgba);  // the kernel sees identical camera-relative input
  EXPECT_EQ(here.distance, there.distance);
}

TEST(Kernel, OffAxisWindowMatchesTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene scene = sol::preset_scene("sandwich");
  scene.camera.frustum = sol::Frustum{-1.3, 0.7, -0.9, 0.4};
  sol::RenderOptions settings;
  settings.width = 40;
  settings.height = 24;
  const Comparison c = compare(sol::test::render(renderer, scene, 40, 24), sol::render_cpu(scene, settings));
  EXPECT_LE(c.mask_differs, c.pixels / 100);  // as for the presets
  EXPECT_LE(c.color_differs, c.pixels / 100);
  sol::Scene centred = scene;
  centred.camera.frustum.reset();
  EXPECT_GT(compare(sol::test::render(renderer, centred, 40, 24), sol::render_cpu(scene, settings)).color_differs, c.pixels / 10);
  expect_no_validation_errors();
}

TEST(Kernel, SwapSymmetry) {
  // σ(x, y, z) = (y, x, -z): the view of z = 1 from (0, 0, h) looking down
  // equals the view of z = -1 from (0, 0, -h) looking up with the camera
  // (and light) mapped by σ (render_test.cpp checks the CPU renderer).
  auto sigma = [](const dvec3& v) { return dvec3(v.y, v.x, -v.z); };
  sol::Scene a;
  a.camera = {{0, 0, 2.2}, {0.1, 0.05, -1}, {0, 1, 0}, 80.0};
  a.objects = {{sol::PlaneZ{1.0}, {0.9, 0.7, 0.2}, sol::Pattern::Circles}};
  sol::Scene b = a;
  b.camera = {sigma(a.camera.position), sigma(a.camera.forward), sigma(a.camera.up), a.camera.fov};
  b.objects[0].shape = sol::PlaneZ{-1.0};
  b.lights[0].direction = sigma(a.lights[0].direction);
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::RenderResult ra = sol::test::render(renderer, a, 40, 30), rb = sol::test::render(renderer, b, 40, 30);
  const Comparison c = compare(ra, rb);
  // Float rounding differs between the mirrored rays (their a and b swap
  // roles in the kernel), so a disc edge may flip a pixel or two.
  EXPECT_EQ(c.mask_differs, 0);
  EXPECT_LE(c.color_differs, 2);
  // The march may stop one step earlier in one of them: both within the hit
  // epsilon (5e-5) of the plane, so the arc lengths differ by up to about that.
  EXPECT_LT(c.distance, 1e-4);
  double px_py = 0;
  for (std::size_t k = 0; k < ra.px.size(); ++k) px_py = std::max(px_py, static_cast<double>(std::abs(ra.px[k] - rb.py[k])));
  EXPECT_LT(px_py, 1e-4);
}

TEST(Kernel, StereoInOneDispatchEqualsEachEyesMonoRender) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene scene = sol::preset_scene("sheets");
  const sol::RenderResult both = sol::test::render_stereo(renderer, scene, 20, 12, 0.4);
  ASSERT_EQ(both.width, 40);
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.4);
  sol::Scene left = scene, right = scene;
  left.camera = eyes.left;
  right.camera = eyes.right;
  const sol::RenderResult l = sol::test::render(renderer, left, 20, 12), r = sol::test::render(renderer, right, 20, 12);
  int differ = 0;
  for (int j = 0; j < 12; ++j) {
    for (int i = 0; i < 20; ++i) {
      const std::size_t k = static_cast<std::size_t>(j * 20 + i);
      const std::size_t kl = static_cast<std::size_t>(j * 40 + i), kr = kl + 20;
      // Same kernel, same float inputs per eye: identical, bit for bit.
      differ += both.distance[kl] != l.distance[k] || both.distance[kr] != r.distance[k] ||
                both.rgba[4 * kl] != l.rgba[4 * k] || both.rgba[4 * kr] != r.rgba[4 * k] ||
                both.px[kr] != r.px[k];
    }
  }
  EXPECT_EQ(differ, 0);
  // And the two eyes do differ (the parallax is there).
  EXPECT_NE(l.distance, r.distance);
  expect_no_validation_errors();
}

// MarchRenderer::record (the presenters' path: the caller's command buffer,
// colour only) writes exactly render()'s colour, mono and stereo, with the
// target larger than the image (the rest untouched).
TEST(Kernel, RecordedDispatchWritesRendersColour) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"sandwich", "lattice-balls"}) {
    const sol::Scene scene = sol::preset_scene(name);
    const int w = 12, h = 8;
    const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.2);
    for (int n : {1, 2}) {
      const std::vector<sol::Camera> cams = n == 1 ? std::vector<sol::Camera>{scene.camera}
                                                   : std::vector<sol::Camera>{eyes.left, eyes.right};
      const sol::RenderResult ref = n == 1 ? sol::test::render(renderer, scene, w, h) : sol::test::render_stereo(renderer, scene, w, h, 0.2);
      sol::vk::StorageImage target(vk_context(), static_cast<std::uint32_t>(n * w + 3), h + 2);
      vk_context().submit_and_wait([&](VkCommandBuffer cb) { renderer.record(cb, cams, w, h, target); });
      const std::vector<float> got = target.download();
      int differ = 0;
      for (int j = 0; j < h; ++j) {
        for (int i = 0; i < n * w; ++i) {
          for (int c = 0; c < 4; ++c) {
            const float a = got[(static_cast<std::size_t>(j) * (n * w + 3) + i) * 4 + c];
            const float b = ref.rgba[(static_cast<std::size_t>(j) * n * w + i) * 4 + c];
            differ += a != b;
          }
        }
      }
      EXPECT_EQ(differ, 0) << name << " eyes " << n;
    }
  }
  const sol::Scene scene = sol::preset_scene("plane");
  renderer.set_world(scene);
  sol::vk::StorageImage small(vk_context(), 4, 4);
  EXPECT_THROW(vk_context().submit_and_wait([&](VkCommandBuffer cb) {
    renderer.record(cb, std::vector<sol::Camera>{scene.camera}, 8, 8, small);
  }), sol::InvalidArgument);
  expect_no_validation_errors();
}

// Frames in flight (MarchOptions::frames_in_flight = 3, the presenters'
// ring): three frames recorded into command buffers of their own and
// submitted one after another without waiting, each with another camera,
// the third after set_world changed the world (a deferring one, spheres,
// whose lists grow: buffers replaced while frames are pending), and a
// fourth reusing the first frame's descriptor set once the first is done.
// Each frame's image is render()'s image of its own camera and world, bit
// for bit: a frame reads the uniforms its commands wrote, not a later
// frame's (a host-written uniform buffer would show the last camera in all).
TEST(Kernel, FramesInFlightEachRenderTheirOwnCameraAndWorld) {
  sol::vk::Context& context = vk_context();
  sol::vk::MarchRenderer renderer(context, {.frames_in_flight = 3});
  sol::vk::MarchRenderer reference(context);
  const int w = 16, h = 12;
  const sol::Scene lattice = sol::preset_scene("lattice-balls"), spheres = sol::preset_scene("spheres");
  struct Shot {
    const sol::Scene* scene;
    sol::Camera camera;
  };
  std::vector<Shot> shots;
  for (int k = 0; k < 4; ++k) {
    const sol::Scene& scene = k == 2 ? spheres : lattice;
    sol::Camera c = scene.camera;
    c.position += glm::dvec3(0.07 * k, -0.05 * k, 0.03 * k);
    shots.push_back({&scene, c});
  }
  VkDevice device = context.device();
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr,
                                    VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT, context.queue_family_index()};
  VkCommandPool pool = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateCommandPool(device, &pool_info, nullptr, &pool), VK_SUCCESS);
  std::vector<VkCommandBuffer> cbs(4);
  VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool,
                                       VK_COMMAND_BUFFER_LEVEL_PRIMARY, 4};
  ASSERT_EQ(vkAllocateCommandBuffers(device, &allocate, cbs.data()), VK_SUCCESS);
  std::vector<VkFence> fences(4);
  for (VkFence& f : fences) {
    VkFenceCreateInfo info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO, nullptr, 0};
    ASSERT_EQ(vkCreateFence(device, &info, nullptr, &f), VK_SUCCESS);
  }
  std::vector<sol::vk::StorageImage> targets;
  // Whatever fails, nothing is destroyed while a frame still runs.
  struct Idle {
    sol::vk::Context& c;
    ~Idle() { c.wait_idle(); }
  } idle{context};
  for (int k = 0; k < 4; ++k) targets.emplace_back(context, static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
  renderer.set_world(lattice);
  for (int k = 0; k < 4; ++k) {
    if (k == 2) renderer.set_world(spheres);  // frames 0 and 1 may still run
    if (k == 3) {
      renderer.set_world(lattice);
      // Frame 3 takes frame 0's descriptor set: frame 0 must be done (the contract).
      ASSERT_EQ(vkWaitForFences(device, 1, &fences[0], VK_TRUE, UINT64_MAX), VK_SUCCESS);
    }
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                   VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    ASSERT_EQ(vkBeginCommandBuffer(cbs[k], &begin), VK_SUCCESS);
    renderer.record(cbs[k], std::span(&shots[k].camera, 1), w, h, targets[k]);
    sol::vk::record_memory_barrier(cbs[k], VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                   VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                                   VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
    ASSERT_EQ(vkEndCommandBuffer(cbs[k]), VK_SUCCESS);
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cbs[k];
    ASSERT_EQ(vkQueueSubmit(context.queue(), 1, &submit, fences[k]), VK_SUCCESS);
  }
  ASSERT_EQ(vkWaitForFences(device, 4, fences.data(), VK_TRUE, UINT64_MAX), VK_SUCCESS);
  for (int k = 0; k < 4; ++k) {
    sol::Scene scene = *shots[k].scene;
    scene.camera = shots[k].camera;
    const sol::RenderResult want = sol::test::render(reference, scene, w, h);
    EXPECT_EQ(targets[k].download(), want.rgba) << "frame " << k;
  }
  // The frames differ from one another (each camera is its own).
  EXPECT_NE(targets[0].download(), targets[1].download());
  for (VkFence f : fences) vkDestroyFence(device, f, nullptr);
  vkDestroyCommandPool(device, pool, nullptr);
  EXPECT_THROW(sol::vk::MarchRenderer(context, {.frames_in_flight = 0}), sol::InvalidArgument);
  EXPECT_THROW(sol::vk::MarchRenderer(context, {.frames_in_flight = sol::vk::kMaxFramesInFlight + 1}),
               sol::InvalidArgument);
  expect_no_validation_errors();
}

// The C++ sRGB encoding the kernel's 8-bit output is held to below: the
// IEC 61966-2-1 curve at points worked out by hand (linear below 0.0031308
// with slope 12.92, 1.055 c^(1/2.4) - 0.055 above; 18% grey encodes to 0.4614).
TEST(Kernel, SrgbEncodingIsTheStandardCurve) {
  EXPECT_EQ(sol::programs::srgb_encode(0.0), 0.0);
  EXPECT_NEAR(sol::programs::srgb_encode(0.001), 0.01292, 1e-15);
  EXPECT_NEAR(sol::programs::srgb_encode(0.0031308), 0.040449936, 1e-9);
  EXPECT_NEAR(sol::programs::srgb_encode(0.18), 0.46135612950044164, 1e-14);
  EXPECT_NEAR(sol::programs::srgb_encode(0.5), 0.7353569830524495, 1e-14);
  EXPECT_NEAR(sol::programs::srgb_encode(1.0), 1.0, 1e-15);
  EXPECT_EQ(sol::programs::srgb_encode(-0.5), 0.0);  // clamped
  EXPECT_NEAR(sol::programs::srgb_encode(2.0), 1.0, 1e-15);
  EXPECT_EQ(sol::programs::srgb_byte(0.5f), 188);  // 0.7354 · 255 = 187.5...
}

// MarchRenderer::record into a caller's 8-bit image (the presenters' direct
// path into a storage-capable swapchain image) writes render()'s colour
// sRGB-encoded, within 1 in 255, mono and stereo, in both channel orders,
// with the target larger than the image; `spheres` through the deferred
// passes (the shade pass writes the 8-bit colour).
TEST(Kernel, UnormTargetHoldsTheSrgbEncodedColour) {
  sol::vk::MarchRenderer renderer(vk_context());
  // lavapipe has the feature and both formats: there the test must run.
  if (vk_context().is_cpu()) {
    ASSERT_TRUE(vk_context().storage_write_without_format());
  }
  int formats_tested = 0;
  for (VkFormat format : {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM}) {
    if (!sol::vk::MarchRenderer::can_write_unorm(vk_context(), format)) {
      EXPECT_FALSE(vk_context().is_cpu()) << "lavapipe cannot write format " << format;
      continue;
    }
    ++formats_tested;
    const bool bgr = format == VK_FORMAT_B8G8R8A8_UNORM;
    for (const char* name : {"plane", "sandwich", "lattice-balls", "spheres"}) {
      // Each display: the default (the colour clamped), brighter through the
      // filmic curve, darker and clamped; the curves from their definitions
      // here (clamp: min(x, 1); aces: Narkowicz's rational fit).
      for (const sol::Display display : {sol::Display{}, sol::Display{1.5, sol::Tone::Aces}, sol::Display{-1.0, sol::Tone::Clamp}}) {
        const sol::Scene scene = sol::preset_scene(name);
        const int w = 12, h = 8;
        const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, 0.2);
        for (int n : {1, 2}) {
          const std::vector<sol::Camera> cams = n == 1 ? std::vector<sol::Camera>{scene.camera}
                                                       : std::vector<sol::Camera>{eyes.left, eyes.right};
          const sol::RenderResult ref = n == 1 ? sol::test::render(renderer, scene, w, h) : sol::test::render_stereo(renderer, scene, w, h, 0.2);
          const auto tw = static_cast<std::uint32_t>(n * w + 3), th = static_cast<std::uint32_t>(h + 2);
          sol::vk::StorageImage target(vk_context(), tw, th, format);
          const sol::vk::UnormTarget unorm{target.view(), format, tw, th, display};
          vk_context().submit_and_wait([&](VkCommandBuffer cb) { renderer.record(cb, cams, w, h, unorm); });
          const std::vector<std::uint8_t> got = target.download_bytes();
          int worst = 0;
          for (int j = 0; j < h; ++j) {
            for (int i = 0; i < n * w; ++i) {
              const std::size_t at_target = static_cast<std::size_t>(j) * tw + static_cast<std::size_t>(i);
              const std::size_t at_ref = static_cast<std::size_t>(j * n * w + i);
              for (int c = 0; c < 4; ++c) {
                const std::size_t from = static_cast<std::size_t>(bgr && c < 3 ? 2 - c : c);
                const int byte = got[at_target * 4 + from];
                const double linear = ref.rgba[at_ref * 4 + static_cast<std::size_t>(c)];
                const double x = std::max(linear, 0.0) * std::exp2(display.exposure);
                const double shown = display.tone == sol::Tone::Aces
                                         ? std::min(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 1.0)
                                         : std::min(x, 1.0);
                const double encoded = c < 3 ? sol::programs::srgb_encode(shown) : std::clamp(linear, 0.0, 1.0);  // alpha: linear
                const auto want = static_cast<int>(std::lround(255.0 * encoded));
                worst = std::max(worst, std::abs(byte - want));
              }
            }
          }
          EXPECT_LE(worst, 1) << name << " eyes " << n << " format " << format << " exposure " << display.exposure;
        }
      }
    }
  }
  if (vk_context().is_cpu()) {
    EXPECT_EQ(formats_tested, 2);
  }
  // Wrong format, null view, too small: refused before anything is recorded.
  const sol::Scene scene = sol::preset_scene("plane");
  renderer.set_world(scene);
  const std::vector<sol::Camera> cams{scene.camera};
  sol::vk::StorageImage rgba32f(vk_context(), 8, 8);
  EXPECT_THROW(vk_context().submit_and_wait([&](VkCommandBuffer cb) {
    renderer.record(cb, cams, 8, 8, sol::vk::UnormTarget{rgba32f.view(), VK_FORMAT_R32G32B32A32_SFLOAT, 8, 8});
  }), sol::InvalidArgument);
  EXPECT_THROW(vk_context().submit_and_wait([&](VkCommandBuffer cb) {
    renderer.record(cb, cams, 8, 8, sol::vk::UnormTarget{VK_NULL_HANDLE, VK_FORMAT_R8G8B8A8_UNORM, 8, 8});
  }), sol::InvalidArgument);
  if (sol::vk::MarchRenderer::can_write_unorm(vk_context(), VK_FORMAT_R8G8B8A8_UNORM)) {
    sol::vk::StorageImage small(vk_context(), 4, 4, VK_FORMAT_R8G8B8A8_UNORM);
    EXPECT_THROW(vk_context().submit_and_wait([&](VkCommandBuffer cb) {
      renderer.record(cb, cams, 8, 8, sol::vk::UnormTarget{small.view(), VK_FORMAT_R8G8B8A8_UNORM, 4, 4});
    }), sol::InvalidArgument);
  }
  expect_no_validation_errors();
}

TEST(Kernel, Rk4IntegratorAgreesAtSmallSteps) {
  sol::vk::MarchRenderer closed(vk_context());
  sol::vk::MarchRenderer rk4(vk_context(), {.integrator = sol::vk::Integrator::RK4, .rk4_step = 0.01});
  // sheets: a world of planes x, y only, whose closed-form kernel solves
  // their crossings and has no march loop; with RK4 it is marched.
  for (const char* name : {"sandwich", "sheets"}) {
    const sol::Scene scene = sol::preset_scene(name);
    const sol::RenderResult a = sol::test::render(closed, scene, 24, 16), b = sol::test::render(rk4, scene, 24, 16);
    const Comparison c = compare(b, a);
    int hits = 0;
    for (float o : a.object) hits += o != 0.0f ? 1 : 0;
    EXPECT_GT(hits, c.pixels / 2) << name;
    EXPECT_LE(c.mask_differs, c.pixels / 50) << name;
    EXPECT_LT(c.distance, 1e-2) << name;
  }
  expect_no_validation_errors();
}

// A world prepared once (MarchRenderer::set_world) renders any camera as a
// fresh renderer given the scene with that camera does, also after another
// world was set in between, in Sol and in the quotient.
TEST(Kernel, PreparedWorldRendersAnyCamera) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"sandwich", "lattice-balls"}) {
    const sol::Scene scene = sol::preset_scene(name);
    renderer.set_world(scene);
    for (const dvec3& offset : {dvec3(0.0), dvec3(0.3, -0.2, 0.1), dvec3(-1.7, 2.2, -0.4)}) {
      sol::Scene moved = scene;
      moved.camera.position += offset;
      moved.camera.forward = glm::normalize(moved.camera.forward + 0.2 * offset);
      const sol::RenderResult prepared = renderer.render(moved.camera, {.width = 16, .height = 12});
      sol::vk::MarchRenderer fresh(vk_context());
      const sol::RenderResult reference = sol::test::render(fresh, moved, 16, 12);
      EXPECT_EQ(prepared.rgba, reference.rgba) << name;
      EXPECT_EQ(prepared.object, reference.object) << name;
    }
  }
  sol::vk::MarchRenderer empty(vk_context());
  EXPECT_THROW((void)empty.render(sol::Camera{}, {.width = 8, .height = 8}), std::logic_error);
  expect_no_validation_errors();
}

// Supersampled images on the kernel (one dispatch per sample into a running
// mean) against the CPU reference's mean of the same samples; 1 sample is
// the plain image; the AOVs stay the centre's.
TEST(Kernel, SupersamplingMatchesTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"plane", "lattice-balls"}) {
    const sol::Scene scene = sol::preset_scene(name);
    renderer.set_world(scene);
    sol::RenderOptions settings;
    settings.width = 48;
    settings.height = 32;
    settings.samples = 8;
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    const sol::RenderResult gpu = renderer.render(std::span(&scene.camera, 1), {.width = 48, .height = 32, .samples = 8});
    const sol::RenderResult plain = renderer.render(scene.camera, {.width = 48, .height = 32});
    const sol::RenderResult one = renderer.render(std::span(&scene.camera, 1), {.width = 48, .height = 32, .samples = 1});
    EXPECT_EQ(one.rgba, plain.rgba) << name;
    EXPECT_EQ(gpu.object, plain.object) << name;
    EXPECT_EQ(gpu.distance, plain.distance) << name;
    // As PresetsMatchTheCpuRenderer, per sample: a grazing ray may go either
    // way in float (moving that pixel's mean by up to 1/8 of a colour step),
    // so at most 2% of the pixels differ by more than 2e-3, and the mean
    // difference stays below 2e-3.
    int differ = 0;
    double sum = 0;
    for (std::size_t k = 0; k < gpu.rgba.size(); ++k) {
      const double d = std::abs(gpu.rgba[k] - cpu.rgba[k]);
      sum += d;
      if (d > 2e-3) ++differ;
    }
    const double mean = sum / static_cast<double>(gpu.rgba.size());
    std::printf("%s, 8 samples: %d of %zu values differ by more than 2e-3, mean difference %.2e\n", name, differ,
                gpu.rgba.size(), mean);
    EXPECT_LE(differ, static_cast<int>(gpu.rgba.size() / 50)) << name;
    EXPECT_LT(mean, 2e-3) << name;
  }
  const sol::Camera camera = sol::preset_scene("plane").camera;
  EXPECT_THROW(renderer.render(std::span(&camera, 1), {.width = 8, .height = 8, .samples = 0}), sol::InvalidArgument);
  expect_no_validation_errors();
}

// The equirectangular and fisheye projections on the kernel against the CPU
// reference (PresetsMatchTheCpuRenderer's tolerances), in Sol and in the
// quotient; outside the fisheye's circle both are black with no hit.
TEST(Kernel, ProjectionsMatchTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"sandwich", "lattice-balls"}) {
    sol::Scene scene = sol::preset_scene(name);
    for (const sol::Projection projection : {sol::Projection::Equirectangular, sol::Projection::Fisheye}) {
      scene.camera.projection = projection;
      scene.camera.fisheye_fov = 200.0;
      const int w = 64, h = projection == sol::Projection::Equirectangular ? 32 : 48;
      const sol::RenderResult cpu = sol::render_cpu(scene, {w, h});
      const sol::RenderResult gpu = sol::test::render(renderer, scene, w, h);
      const Comparison c = compare(gpu, cpu);
      std::printf("%s, %s: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n", name,
                  projection == sol::Projection::Fisheye ? "fisheye 200" : "equirectangular", c.mask_differs, c.pixels,
                  c.color_differs, c.distance);
      EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
      EXPECT_LE(c.color_differs, c.pixels / 100) << name;
      // In the quotient the panorama's rays go every way to max_distance 12
      // with up to about 10 restarts each: float t then drifts by about 1e-4
      // of t (1.2e-3 with the restarts of sol_ray_advanced or
      // sol_ray_restarted alike); in Sol 1e-3 as for the presets.
      EXPECT_LT(c.distance, scene.quotient() == sol::Quotient::None ? 1e-3 : 2e-3) << name;
      if (projection == sol::Projection::Fisheye) {
        EXPECT_EQ(gpu.object[0], 0.0f);
        EXPECT_EQ(gpu.rgba[0], 0.0f);
      }
    }
  }
  expect_no_validation_errors();
}

// Omnidirectional stereo (Camera::eye_offset, each column its own eye from
// the kBindingColumns records) against the CPU renderer's: in Sol planes
// z = c (plane, sandwich: the heights-only march, its culling shifted to the
// column's eye) and x = c, y = c (sheets: each faces the column's eye), and
// in the quotient (lattice-balls: the eye teleported into D), with the
// tolerances of the projections above; and the eyes differ.
TEST(Kernel, OmnidirectionalStereoMatchesTheCpuRenderer) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"plane", "sandwich", "sheets", "lattice-balls"}) {
    sol::Scene scene = sol::preset_scene(name);
    scene.camera.projection = sol::Projection::Equirectangular;
    const int w = 48, h = 24;
    const double ipd = 0.3;
    sol::RenderOptions settings;
    settings.width = w;
    settings.height = h;
    const sol::RenderResult cpu = sol::render_cpu_stereo(scene, settings, ipd);
    const sol::RenderResult gpu = sol::test::render_stereo(renderer, scene, w, h, ipd);
    ASSERT_EQ(gpu.width, 2 * w);
    const Comparison c = compare(gpu, cpu);
    std::printf("%s ODS: hit mask differs at %d of %d pixels, colour at %d, worst distance difference %.2e\n", name,
                c.mask_differs, c.pixels, c.color_differs, c.distance);
    EXPECT_LE(c.mask_differs, c.pixels / 100) << name;
    EXPECT_LE(c.color_differs, c.pixels / 100) << name;
    EXPECT_LT(c.distance, scene.quotient() == sol::Quotient::None ? 1e-3 : 2e-3) << name;
    int differ = 0;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = static_cast<std::size_t>(j * 2 * w + i);
        differ += std::abs(gpu.distance[k] - gpu.distance[k + static_cast<std::size_t>(w)]) > 1e-3f;
      }
    }
    EXPECT_GT(differ, w * h / 10) << name;
  }
  expect_no_validation_errors();
}

// Long renders in tiles: with a tiny dispatch limit the image is made of
// many small tiles (each sample of each tile one dispatch), and every value
// of it, colour and AOVs, is the one-dispatch image's bit for bit; progress
// rises to 1; a cancel stops the render with sol::Cancelled.
TEST(Kernel, TiledRenderEqualsOneDispatch) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene scene = sol::preset_scene("lattice-balls");
  renderer.set_world(scene);
  const sol::Camera eyes[] = {scene.camera, sol::stereo_eyes(scene.camera, 0.1).right};
  for (int samples : {1, 3}) {
    const sol::RenderResult whole = renderer.render(std::span(eyes, 2), {.width = 40, .height = 28, .samples = samples});
    sol::RenderOptions options{.width = 40, .height = 28, .samples = samples};
    options.max_dispatch_ms = 1e-6;  // tiles of 8 x 8 pixels (the smallest)
    std::vector<double> seen;
    options.progress = [&](double f) { seen.push_back(f); };
    const sol::RenderResult tiled = renderer.render(std::span(eyes, 2), options);
    EXPECT_EQ(tiled.rgba, whole.rgba) << samples;
    EXPECT_EQ(tiled.object, whole.object) << samples;
    EXPECT_EQ(tiled.distance, whole.distance) << samples;
    EXPECT_EQ(tiled.steps, whole.steps) << samples;
    EXPECT_EQ(tiled.px, whole.px) << samples;
    // 0 before the kernel is prepared and again once it is (the work
    // begins), then one report per dispatch (each sample of each tile; at
    // least the 4 rows of 8-pixel tiles over 28 rows times the samples),
    // rising strictly to 1.
    ASSERT_GE(seen.size(), 2u + 4u * static_cast<unsigned>(samples));
    EXPECT_EQ(seen[0], 0.0);
    EXPECT_EQ(seen[1], 0.0);
    EXPECT_GT(seen[2], 0.0);
    EXPECT_TRUE(std::adjacent_find(seen.begin() + 2, seen.end(), std::greater_equal<>()) == seen.end());
    EXPECT_EQ(seen.back(), 1.0);
  }
  std::atomic<bool> stop{false};
  sol::RenderOptions options{.width = 40, .height = 28};
  options.max_dispatch_ms = 1e-6;
  options.cancel = &stop;
  int rows_done = 0;
  options.progress = [&](double fraction) {
    if (fraction == 0.0) return;  // the reports before any dispatch
    ++rows_done;
    stop = true;  // asked to stop after the first dispatch
  };
  EXPECT_THROW(renderer.render(std::span(eyes, 1), options), sol::Cancelled);
  EXPECT_EQ(rows_done, 1);  // heard at once, not at the end of the band
  expect_no_validation_errors();
}

// Without AOVs (RenderOptions::aovs false, solrender without --aov) the
// kernel's colour is the same bits, mono and stereo, and nothing else is
// read back: the AOV vectors stay empty.
TEST(Kernel, ColourAloneIsTheSameColour) {
  sol::vk::MarchRenderer renderer(vk_context());
  for (const char* name : {"lattice-balls", "spheres"}) {
    const sol::Scene scene = sol::preset_scene(name);
    renderer.set_world(scene);
    const sol::Camera eyes[] = {scene.camera, sol::stereo_eyes(scene.camera, 0.1).right};
    for (std::size_t n : {1u, 2u}) {
      const sol::RenderResult all = renderer.render(std::span(eyes, n), {.width = 24, .height = 16, .samples = 2});
      const sol::RenderResult colour =
          renderer.render(std::span(eyes, n), {.width = 24, .height = 16, .samples = 2, .aovs = false});
      EXPECT_EQ(colour.rgba, all.rgba) << name << " " << n;
      EXPECT_EQ(colour.width, all.width);
      for (const auto* plane : {&colour.object, &colour.distance, &colour.px, &colour.py, &colour.pz, &colour.steps}) {
        EXPECT_TRUE(plane->empty()) << name;
      }
    }
  }
  expect_no_validation_errors();
}

// RenderOptions::rows: the colour handed over band by band as each band of
// tiles is done (a tiny max_dispatch_ms makes bands of 8 rows; 2 samples,
// stereo), in order and covering every row once, is render()'s colour bit
// for bit, and the result holds none.
TEST(Kernel, ColourHandedOverBandByBandIsTheColour) {
  sol::vk::MarchRenderer renderer(vk_context());
  const sol::Scene scene = sol::preset_scene("lattice-balls");
  renderer.set_world(scene);
  const sol::Camera eyes[] = {scene.camera, sol::stereo_eyes(scene.camera, 0.1).right};
  const sol::RenderOptions base{.width = 24, .height = 40, .samples = 2, .max_dispatch_ms = 1e-6, .aovs = false};
  const sol::RenderResult whole = renderer.render(eyes, base);
  std::vector<float> bands;
  int next_row = 0, count = 0;
  sol::RenderOptions streamed = base;
  streamed.rows = [&](int first, int rows, std::span<const float> rgba) {
    EXPECT_EQ(first, next_row);
    EXPECT_EQ(rgba.size(), static_cast<std::size_t>(rows) * 48 * 4);
    next_row = first + rows;
    ++count;
    bands.insert(bands.end(), rgba.begin(), rgba.end());
  };
  const sol::RenderResult r = renderer.render(eyes, streamed);
  EXPECT_EQ(next_row, 40);
  EXPECT_GT(count, 1);  // several bands, each handed over when done
  EXPECT_TRUE(r.rgba.empty());
  EXPECT_EQ(r.width, 48);
  EXPECT_EQ(bands, whole.rgba);
  expect_no_validation_errors();
}

TEST(Kernel, RejectsBadInput) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene scene = sol::preset_scene("plane");
  EXPECT_THROW(sol::test::render(renderer, scene, 0, 10), sol::InvalidArgument);
  // An exact ball too large for the kernel's float solves: not rendered
  // here, said so up front, naming the field (which --device auto takes as
  // "render on the CPU"); a glowing exact ball among more objects than the
  // kernel lists is (a crowd's targets: Params::crowd_targets); more
  // objects than any world holds: invalid on every renderer.
  scene.objects.resize(9, scene.objects[0]);
  scene.objects[7].shape = sol::Ball{{0.0, 0.0, 1.0}, 0.3, true};
  scene.objects[7].emission = {1.0, 1.0, 1.0};
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene, sol::Transport::Path), "");
  scene.objects[7].shape = sol::Ball{{0.0, 0.0, 1.0}, 2.5, true};
  EXPECT_NE(sol::vk::MarchRenderer::unsupported(scene).find("objects[7].radius: exact balls of a radius above 2"),
            std::string::npos);
  scene.objects[7] = scene.objects[0];
  scene.objects.resize(sol::kMaxObjects + 1, scene.objects[0]);
  EXPECT_THROW(sol::test::render(renderer, scene, 8, 8), sol::InvalidArgument);
  EXPECT_EQ(sol::vk::MarchRenderer::unsupported(scene), "");  // (set_world says why)
  EXPECT_THROW(sol::vk::MarchRenderer(vk_context(), {.integrator = sol::vk::Integrator::RK4, .rk4_step = 0.0}),
               sol::InvalidArgument);
}

}  // namespace

namespace {

// The arc length at which the geodesic from `eye` with unit direction
// `direction` (frame components) crosses the plane x = c (PlaneX) or y = c
// (PlaneY), in double: bisection of the monotone x(t) - c on the double
// closed form over [0, limit], to 1e-13; -1 when it does not cross.
double exact_plane_crossing(const dvec3& eye, const dvec3& direction, const sol::SceneObject& object, double limit) {
  const sol::ClosedFormGeodesic<double> g(direction);
  const bool is_x = std::holds_alternative<sol::PlaneX>(object.shape);
  const double c = is_x ? std::get<sol::PlaneX>(object.shape).c : std::get<sol::PlaneY>(object.shape).c;
  auto f = [&](double t) {
    const dvec3 p = sol::multiply(eye, g.at(t).position);
    return is_x ? p.x - c : p.y - c;
  };
  double lo = 0.0, hi = limit;
  const double f0 = f(lo);
  if (f0 * f(hi) > 0.0) return -1.0;
  while (hi - lo > 1e-13 * std::max(1.0, hi)) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) * f0 > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Over the pixels where both renders hit the same plane x = c or y = c.
struct CrossingErrors {
  double cpu = 0;      // worst |t - exact| / max(1, exact)
  double gpu = 0;      // worst distance of the kernel's hit (on the exact ray) from the plane over its budget
  double gpu_arc = 0;  // worst |t - exact| of the kernel
  int planes = 0;      // such pixels
  Comparison images;   // the two renders (masks, colours, arc lengths)
  double mean_steps = 0;  // the kernel's
  int unsettled = 0;      // the kernel's rays of over 16 positions (planes x, y only: roots unsettled, then marched)
  int unsettled_hits = 0;     // of those, the ones the CPU sees hit
  int unsettled_differ = 0;   // of those, the ones whose object differs between the renders
};

// Each pixel of a mono or ODS stereo pair (`ipd` > 0, equirectangular) whose
// ray hits a plane x = c or y = c in both renders: the arc lengths against
// the exact crossing of its ray from its eye.
CrossingErrors plane_crossing_errors(const sol::Scene& scene, int w, int h, double ipd) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::RenderOptions settings;
  settings.width = w;
  settings.height = h;
  const bool stereo = ipd > 0.0;
  const sol::RenderResult cpu = stereo ? sol::render_cpu_stereo(scene, settings, ipd) : sol::render_cpu(scene, settings);
  const sol::RenderResult gpu = stereo ? sol::test::render_stereo(renderer, scene, w, h, ipd) : sol::test::render(renderer, scene, w, h);
  EXPECT_EQ(gpu.width, cpu.width);
  const sol::StereoEyes eyes = sol::stereo_eyes(scene.camera, ipd);
  CrossingErrors e;
  e.images = compare(gpu, cpu);
  for (std::size_t k = 0; k < gpu.steps.size(); ++k) {
    e.mean_steps += gpu.steps[k] / static_cast<double>(gpu.steps.size());
    if (gpu.steps[k] > 16.0f) {  // march/plane_roots.glsl's kPlaneRootIterations
      ++e.unsettled;
      e.unsettled_hits += cpu.object[k] != 0.0f ? 1 : 0;
      e.unsettled_differ += gpu.object[k] != cpu.object[k] ? 1 : 0;
    }
  }
  for (int eye = 0; eye < (stereo ? 2 : 1); ++eye) {
    const sol::Camera camera = stereo ? (eye == 0 ? eyes.left : eyes.right) : scene.camera;
    sol::Camera mono = camera;
    mono.eye_offset = 0.0;
    for (int i = 0; i < w; ++i) {
      const sol::ColumnEye column = sol::column_eye(camera, i, w);
      for (int j = 0; j < h; ++j) {
        const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(cpu.width) + static_cast<std::size_t>(eye * w + i);
        if (gpu.object[k] == 0 || gpu.object[k] != cpu.object[k]) continue;
        const sol::SceneObject& o = scene.objects[static_cast<std::size_t>(gpu.object[k]) - 1];
        if (!std::holds_alternative<sol::PlaneX>(o.shape) && !std::holds_alternative<sol::PlaneY>(o.shape)) continue;
        const dvec3 direction = glm::normalize(column.transport * sol::camera_ray(mono, i, j, w, h));
        const dvec3 eye_at = sol::multiply(camera.position, column.offset);
        const double exact = exact_plane_crossing(eye_at, direction, o, scene.max_distance);
        EXPECT_GT(exact, 0.0) << i << ", " << j;
        e.cpu = std::max(e.cpu, std::abs(cpu.distance[k] - exact) / std::max(1.0, exact));
        e.gpu_arc = std::max(e.gpu_arc, std::abs(gpu.distance[k] - exact));
        // The kernel's hit on the true ray: its distance from the plane (sinh of it).
        const dvec3 at = sol::multiply(eye_at, sol::ClosedFormGeodesic<double>(direction).at(gpu.distance[k]).position);
        const bool is_x = std::holds_alternative<sol::PlaneX>(o.shape);
        const double c = is_x ? std::get<sol::PlaneX>(o.shape).c : std::get<sol::PlaneY>(o.shape).c;
        const double off = std::abs((is_x ? at.x : at.y) - c) * std::exp(is_x ? -at.z : at.z);
        e.gpu = std::max(e.gpu, off / (scene.hit_epsilon + 5e-5 * std::max(1.0, exact)));
        ++e.planes;
      }
    }
  }
  return e;
}

}  // namespace

// Planes x = c and y = c are met as roots of the monotone x(t) - c, y(t) - c
// (render.cpp first_plane_crossing, march/plane_roots.glsl plane_xy_roots), not marched:
// both renderers' hits against the crossing found by bisection in double,
// for the sheets preset seen mono and as an ODS pair (rays from each
// column's eye), and with a ball in front of the sheets (the march of the
// other objects stops at the crossing). The CPU solves to double precision
// and stores t in float: within two float roundings (1.2e-7 relative). The
// kernel stops within the hit epsilon of the plane by its float closed form,
// whose positions hold 5e-5 relative (Kernel.FlowMatchesTheDoubleClosedForm):
// its hit, put on the exact ray, lies within eps + 5e-5 max(1, t) of the
// plane. Its arc length is off by that over the sine of the crossing's
// angle (printed; sphere tracing stopped eps / sine short as well).
TEST(Kernel, PlanesXYHitAtTheirCrossing) {
  sol::Scene sheets = sol::preset_scene("sheets");
  sol::Scene ball = sheets;
  ball.objects.push_back({sol::Ball{{0.4, 0.6, 0.1}, 0.3}, {0.9, 0.9, 0.9}});
  sol::Scene ods = sheets;
  ods.camera.projection = sol::Projection::Equirectangular;
  sol::Scene away = sheets;  // looking away from both sheets: each ray's x and y grow
  away.camera.forward = -away.camera.forward;
  away.camera.fov = 40.0;
  sol::Scene on = sheets;  // the eye on the sheet x = 0: every ray hits it at once, or the other
  on.camera.position.x = 0.0;
  // Every direction from farther away, up to 200: some rays' roots do not
  // settle within 16 positions (float rounding far out); the kernel then
  // marches the planes (for a world of planes x, y only, inside plane_xy_roots).
  sol::Scene far = sheets;
  far.camera.position = {5.0, 3.0, 2.0};
  far.camera.projection = sol::Projection::Equirectangular;
  far.max_distance = 200.0;
  struct Case {
    const char* name;
    const sol::Scene& scene;
    int w, h;
    double ipd;
    bool hits;  // most pixels see a sheet
  };
  for (const Case& c : {Case{"sheets", sheets, 48, 32, 0.0, true}, Case{"sheets with a ball", ball, 48, 32, 0.0, true},
                        Case{"sheets ODS", ods, 48, 24, 0.3, true}, Case{"looking away", away, 24, 16, 0.0, false},
                        Case{"on a sheet", on, 24, 16, 0.0, true}, Case{"far, all around", far, 96, 48, 0.0, true}}) {
    const CrossingErrors e = plane_crossing_errors(c.scene, c.w, c.h, c.ipd);
    std::printf("%s: %d plane hits, %d masks differ, mean kernel steps %.2f (%d rays over 16, %d of them "
                "hits on the CPU, %d differ); kernel: worst off the plane %.2f of its budget, arc length %.2e; CPU: arc "
                "length %.2e relative\n",
                c.name, e.planes, e.images.mask_differs, e.mean_steps, e.unsettled, e.unsettled_hits, e.unsettled_differ,
                e.gpu, e.gpu_arc, e.cpu);
    if (&c.scene == &far) {
      // The march after unsettled roots is exercised, and sees what the CPU sees.
      EXPECT_GT(e.unsettled_hits, 0) << "the march after unsettled roots is not exercised";
      EXPECT_EQ(e.unsettled_differ, 0);
    }
    if (c.hits) {
      EXPECT_GT(e.planes, c.w * c.h / 2) << c.name;
    } else {
      EXPECT_EQ(e.images.mask_differs + e.planes, 0) << c.name;
    }
    // As Kernel.PresetsMatchTheCpuRenderer: grazing rays may go either way.
    EXPECT_LE(e.images.mask_differs, e.images.pixels / 100) << c.name;
    EXPECT_LE(e.images.color_differs, e.images.pixels / 100) << c.name;
    EXPECT_LT(e.cpu, 1.2e-7) << c.name;
    EXPECT_LE(e.gpu, 1.0) << c.name;
    // Solved, not marched: sphere tracing took 11.8 steps per ray on the
    // sheets preset; the roots take 3 to 5 positions (with the ball, the
    // march of the ball's bound takes its steps).
    if (&c.scene != &ball) {
      EXPECT_LT(e.mean_steps, 6.0) << c.name;
    }
  }
  expect_no_validation_errors();
}
// A diffuse bounce off a glowing bound ball in a world with glass (whose
// rays the kernel marches inside solids): the kernel's path leaves the ball
// as the CPU's does. Float's bound dips below 0 along a ray leaving the
// surface almost tangentially, and the pass ended there where the ray
// heads for the face it leaves met the ball again at once (its emission
// again at every bounce: 6 to 11 of the ball's pixels parted from the
// CPU's in each seed below, the kernel brighter by 4 to 6 standard errors
// over them; kHeadsDepth). One bounce, four seeds: no pixel of the ball
// parts from the CPU's by more than 1e-2 (measured: none), and over the
// seeds the mean difference is within 3 standard errors.
TEST(Kernel, PathsLeavingAGlowingBallInAWorldWithGlassAreTheCpus) {
  sol::vk::MarchRenderer renderer(vk_context());
  sol::Scene scene = floor_glow_and_glass();
  scene.max_bounces = 1;
  double sum = 0.0, variance = 0.0;
  int parted = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const sol::RenderOptions settings{.width = 24, .height = 16, .samples = 8, .transport = sol::Transport::Path, .seed = seed};
    const sol::RenderResult gpu = sol::render_scene(renderer, scene, settings);
    const sol::RenderResult cpu = sol::render_cpu(scene, settings);
    for (std::size_t k = 0; k < cpu.object.size(); ++k) {
      if (cpu.object[k] == 2.0f && std::abs(gpu.rgba[4 * k] - cpu.rgba[4 * k]) > 1e-2f) ++parted;
    }
    const sol::test::MeanAndError d = sol::test::red_difference(gpu, cpu);
    sum += d.mean;
    variance += d.error * d.error;
  }
  const double mean = sum / 4.0, error = std::sqrt(variance) / 4.0;
  std::printf("glowing ball beside glass, kernel against CPU: %d pixels of the ball parted in 4 seeds; mean difference %.5f, standard error %.5f\n",
              parted, mean, error);
  EXPECT_EQ(parted, 0);
  EXPECT_LE(std::abs(mean), 3.0 * error + 1e-6);
  expect_no_validation_errors();
}
