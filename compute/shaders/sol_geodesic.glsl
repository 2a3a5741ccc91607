// Closed-form Sol geodesics from the origin in float: the GLSL mirror of
// libsol's ClosedFormGeodesic<float> (libsol/src/closed_form.cpp, the
// derivation in libsol/include/sol/closed_form.hpp) and of the elliptic
// functions it needs (libsol/src/elliptic.cpp, carlson.hpp). Keep the two in
// step: tests/kernel_test.cpp holds them together.
//
// The positions by Jacobi's zeta function (sol_forward_zeta, the quotient
// march's first pass) are the kernel's own: no C++ mirror; tested against
// libsol's double closed form.
//
// Differences from the C++ float version, all below float rounding at the
// arc lengths a frame uses: K comes from a float AGM (no double-double
// K_lo), the AGM chain of sn, cn, dn runs in float, and the AGM sequence is
// computed once per ray.
//
// In three files: sol_elliptic.glsl (the elliptic functions), sol_ray.glsl
// (a ray prepared once: regimes, set-up, heights, cut time) and
// sol_forward.glsl (positions and tangents at an arc length, restarts,
// translation).
#ifndef SOL_GEODESIC_GLSL
#define SOL_GEODESIC_GLSL

#include "sol_elliptic.glsl"
#include "sol_ray.glsl"
#include "sol_forward.glsl"

#endif  // SOL_GEODESIC_GLSL
