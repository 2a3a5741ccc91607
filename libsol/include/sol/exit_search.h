// The exit search's rounds, written once for the kernels (float) and the
// CPU renderer (double): a path segment that leaves the inner wall of an
// exact ball of radius below kConvexBallRadius finds its exit by Newton's
// method on the arc length s for f(s) = r − hit_epsilon/2, f the distance
// from the ball's centre along the ray (docs/lighting.md, "Enclosures";
// exit_newton in compute/shaders/march/steps.glsl, and exact_ball_exit in
// libsol/src/render.cpp where its solve at once finds no exit). Valid C++ (namespace sol::kernel,
// double) and GLSL (float), as sol/log_series.h.
#ifndef SOL_EXIT_SEARCH_H
#define SOL_EXIT_SEARCH_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#define SOL_EXIT_FUNCTION inline constexpr
namespace sol::kernel {
#else
#define SOL_EXIT_FUNCTION
#endif

/// The most rounds a search takes before the segment marches as any ray.
SOL_CONSTANT(int, kExitRounds, 8);

/// Whether the trial where the distance from the centre exceeds the radius
/// by `excess` (the exact signed distance to the sphere), changing at
/// `slope` along the ray, is the exit: within hit_epsilon/4 of the level
/// r − hit_epsilon/2, heading out.
SOL_EXIT_FUNCTION bool sol_exit_found(SOL_REAL excess, SOL_REAL slope, SOL_REAL eps) {
  const SOL_REAL error = excess + 0.5 * eps;
  return (error < 0.0 ? -error : error) < 0.25 * eps && slope > 0.0;
}

/// The next trial after `t` (not the exit) in a ball of `radius`: Newton's
/// step where the distance grows (slope above 1e-3), capped at 2r +
/// hit_epsilon (within which a geodesic that left the ball cannot meet it
/// again); half as far again where it does not and the trial is inside
/// (before the nearest approach); 0 where it is outside while heading in
/// (the search gives up, as where the next trial is past the march's limit).
SOL_EXIT_FUNCTION SOL_REAL sol_exit_next(SOL_REAL t, SOL_REAL excess, SOL_REAL slope, SOL_REAL radius, SOL_REAL eps) {
  const SOL_REAL error = excess + 0.5 * eps;
  const SOL_REAL newton = t - error / (slope > 1e-3 ? slope : 1.0);
  const SOL_REAL cap = 2.0 * radius + eps;
  return slope > 1e-3 ? (newton < cap ? newton : cap) : (error < 0.0 ? 1.5 * t : 0.0);
}

#ifdef __cplusplus
}  // namespace sol::kernel
#endif
#undef SOL_EXIT_FUNCTION

#endif  // SOL_EXIT_SEARCH_H
