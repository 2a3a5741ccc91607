// How light spreads along Sol's geodesics: the area of a geodesic sphere
// per unit solid angle of the directions that reach it (docs/lighting.md).
//
// A point light sends its power evenly over the unit sphere of directions.
// The directions within a small solid angle dΩ about v reach, after arc
// length t, a patch of the geodesic sphere of radius t of area J(v, t) dΩ.
// Radiance is constant along a geodesic, so the irradiance at a surface
// point reached that way is E = I · cos θ / J(v, t), I = Φ / 4π the radiant
// intensity. In Euclidean space J = t²; in Sol it is
//
//   J(v, t) = |Y1(t) × Y2(t)|,
//
// Y1, Y2 the Jacobi fields along the geodesic γ(s) = exp(s v) with
// Y(0) = 0 and Y'(0) = w1, w2, an orthonormal pair orthogonal to v: the
// derivative of the exponential map, Y_k(t) = t · d exp_{tv}(w_k).
//
// Method. The fields are the derivatives of the flow with respect to the
// initial direction. Written in frame components at γ(s), ξ = (e^{-z} δx,
// e^{z} δy, δz), with δu the variation of the velocity's frame components
// u = (u1, u2, u3), the linearised geodesic equations (geodesic.hpp) are
//
//   ξ1' = δu1 + u1 ξ3 − u3 ξ1,   ξ2' = δu2 − u2 ξ3 + u3 ξ2,   ξ3' = δu3,
//   δu1' = u3 δu1 + u1 δu3,  δu2' = −u3 δu2 − u2 δu3,  δu3' = 2 (u2 δu2 − u1 δu1),
//
// with ξ(0) = 0, δu(0) = w: no exponentials, quadratic right-hand sides.
// The Gauss lemma keeps ξ orthogonal to u(s), so Y1 × Y2 is parallel to
// u(t) and the signed determinant det[ξ1, ξ2, u(t)] changes sign at each
// conjugate point, where J = 0 and light focuses (a caustic).
//
// Double: u(s) from the closed form (sol/closed_form.hpp, exact), the
// twelve variations by adaptive Dormand–Prince at relative tolerance 1e-12
// (relative accuracy near 1e-10 up to t = 10; tests/spreading_test.cpp).
// Float: the kernel's method (compute/shaders/sol_spreading.glsl), classical
// RK4 of u and the variations together, fixed steps of at most
// kSpreadingStep; relative accuracy about 1e-4 up to t = 6.
//
// Exact special cases (tests): along the z axis J = sinh² t; along the
// straight lines (1, ±1, 0)/√2, J = |2(1 − cos √2t) − t sin(√2t)/√2|,
// conjugate at t = √2π; for small t, J = t² (1 + u3² t²/3) + O(t⁵)
// (t² (1 − Ric(v, v) t²/6) with Sol's Ric(v, v) = −2 v3²).
#pragma once

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"

namespace sol {

/// The signed determinant det[Y1(t), Y2(t), γ'(t)] above for the geodesic
/// from the origin with unit initial `direction` (frame components;
/// normalised on use), t >= 0: |value| = J(v, t), the sign flipping at each
/// conjugate point. The fields' pair w1, w2 is oriented so that the value
/// is positive for small t. Throws InvalidArgument for a zero or non-finite
/// direction, a negative or non-finite t.
double jacobi_determinant(const glm::dvec3& direction, double t);

/// J(v, t) = |jacobi_determinant(direction, t)|: the area of the geodesic
/// sphere of radius t about the origin per unit solid angle at `direction`;
/// t² + O(t⁴) near 0, zero at conjugate points.
double sphere_area_density(const glm::dvec3& direction, double t);
/// The same integrated at the relative tolerance `tolerance` in [1e-14,
/// 1e-4] (the two above take 1e-12): the path tracer's 1e-6 costs about a
/// tenth and stays within about 1e-6 of it, far below any image's noise.
/// InvalidArgument for a tolerance outside that range.
double sphere_area_density(const glm::dvec3& direction, double t, double tolerance);

/// The float version: the kernel's fixed-step RK4 (kSpreadingStep), for
/// tests that hold the kernel to libsol and for single-precision callers.
float sphere_area_density(const glm::vec3& direction, float t);

/// What the renderers take as J for a light's irradiance I cos θ / J: J,
/// never below kMinSpreading (a caustic shows as a bright line of at most
/// 1 / kMinSpreading times the light's intensity, not an infinity).
inline double clamped_spreading(double density) {
  return density > kernel::kMinSpreading ? density : kernel::kMinSpreading;
}

}  // namespace sol
