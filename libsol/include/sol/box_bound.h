// The lower bound of the Sol distance from a point to a coordinate box
// (sol::box_distance_lower_bound, sol/coordinate_box.hpp, where it is
// derived), the part that the CPU's tree of bounds (double) and the
// kernel's (compute/shaders/march/crowd.glsl, float) share: the hyperbolic
// distance from the point's projection on the (x, z) plane (side 1, e =
// e^{-q_z}) or on the (y, z) plane (side -1, e = e^{q_z}) to the box's, a
// rectangle of horizontal gap g >= 0 and heights [lo, hi]. Valid C++ (in
// namespace sol::kernel, double) and GLSL (float), as sol/kernel_constants.h.
//
// The height s of the nearest point, e^{2s} = 1 + 2A with A = ½ (g e)²,
// clamped to the box's heights; there d = 2 asinh √(sinh²(s/2) + ½ A e^{-side s}),
// with one exponential for sinh(s/2) and e^{-side s}. (Evaluated at the
// rounded root of a convex minimisation, it exceeds the exact minimum by
// a term of the root's error squared, far below the rounding of either
// type; sinh(s/2) by its exponentials is off by the rounding of 1
// absolutely, which the bound's use, against distances of hit_epsilon
// and more, never sees.)
#ifndef SOL_BOX_BOUND_H
#define SOL_BOX_BOUND_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <algorithm>
#include <cmath>
namespace sol::kernel {
#define SOL_SHARED_FUNCTION inline
using std::abs;
using std::clamp;
using std::exp;
using std::log;
using std::sqrt;
#else
#define SOL_SHARED_FUNCTION
#endif

SOL_SHARED_FUNCTION SOL_REAL sol_projected_box_distance(SOL_REAL g, SOL_REAL qz, SOL_REAL e, SOL_REAL side, SOL_REAL lo,
                                                        SOL_REAL hi) {
  if (g == 0.0) return abs(clamp(qz, lo, hi) - qz);  // the height's gap alone
  const SOL_REAL w = g * e;
  const SOL_REAL a = 0.5 * w * w;
  const SOL_REAL s = clamp(qz + side * 0.5 * log(1.0 + 2.0 * a), lo, hi) - qz;
  const SOL_REAL half_s = exp(0.5 * s);
  const SOL_REAL inverse = 1.0 / half_s;
  const SOL_REAL h = 0.5 * (half_s - inverse);  // sinh(s/2)
  const SOL_REAL x = h * h + 0.5 * a * (side > 0.0 ? inverse * inverse : half_s * half_s);
  return 2.0 * log(sqrt(x) + sqrt(1.0 + x));
}

#undef SOL_SHARED_FUNCTION
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_BOX_BOUND_H
