// How light spreads along a geodesic: J(v, t), the area of the geodesic
// sphere of radius t per unit solid angle at the direction v (frame
// components at the start). The float method of sol::sphere_area_density
// (libsol/include/sol/spreading.hpp has the derivation): the velocity u and
// two Jacobi fields (ξ in frame components at the current point, δu the
// variation of u) integrated together by classical RK4 in equal steps of at
// most kSpreadingStep; J = |det[ξ1, ξ2, u]|. The same steps carry the
// position, so that one integration gives the geodesic's end, its tangent
// there and J (sol_spread: a glowing ball's sampled point). With three
// fields the same equations give the Jacobian of the exponential map
// (sol_exp_jacobian).
//
// sol_spread takes each RK4 step's four stages as turns of one loop (one
// rate in its body): the driver inlines every call of a function, and the
// path kernel calls J from four places, so four rates in each body would
// be sixteen in the pipeline; the arithmetic is classical RK4's, in its
// order. sol_exp_jacobian keeps its four rates in line: it runs in every
// Newton iteration of the exact solves, where the rolled loop made paths
// through exact balls 60 % slower on lavapipe.
#ifndef SOL_SPREADING_GLSL
#define SOL_SPREADING_GLSL

#include "sol/kernel_constants.h"

struct SolJacobi {
  vec3 x1, d1;  // the first field ξ and its δu
  vec3 x2, d2;  // the second
  vec3 u;       // the velocity, frame components
  vec3 p;       // the position (coordinates)
  vec2 e;       // e^{z}, e^{-z} there
};

// The linearised geodesic equations of one field along u.
void sol_variation(vec3 u, vec3 x, vec3 d, out vec3 dx, out vec3 dd) {
  dx = vec3(d.x + u.x * x.z - u.z * x.x, d.y - u.y * x.z + u.z * x.y, d.z);
  dd = vec3(u.z * d.x + u.x * d.z, -u.z * d.y - u.y * d.z, 2.0 * (u.y * d.y - u.x * d.x));
}

// The geodesic equations (u' in the frame; the position's rate, the frame
// being e^{z} ∂x, e^{-z} ∂y, ∂z) and the fields' along it.
SolJacobi sol_jacobi_rate(SolJacobi y) {
  SolJacobi r;
  sol_variation(y.u, y.x1, y.d1, r.x1, r.d1);
  sol_variation(y.u, y.x2, y.d2, r.x2, r.d2);
  r.u = vec3(y.u.x * y.u.z, -y.u.y * y.u.z, y.u.y * y.u.y - y.u.x * y.u.x);
  r.p = vec3(y.e.x * y.u.x, y.e.y * y.u.y, y.u.z);
  r.e = vec2(y.e.x * y.u.z, -y.e.y * y.u.z);
  return r;
}

SolJacobi sol_jacobi_step(SolJacobi y, float h, SolJacobi k) {
  return SolJacobi(y.x1 + h * k.x1, y.d1 + h * k.d1, y.x2 + h * k.x2, y.d2 + h * k.d2, y.u + h * k.u, y.p + h * k.p,
                   y.e + h * k.e);
}

// The geodesic from the origin with unit initial direction v, after arc
// length t: J(v, t), the end point exp(t v) and the unit tangent there
// (frame components). The end agrees with the closed form to RK4's
// accuracy (Kernel.SpreadEndsMatchTheClosedForm).
struct SolSpread {
  float density;
  vec3 position;
  vec3 direction;
};

SolSpread sol_spread(vec3 direction, float t) {
  const vec3 v = normalize(direction);
  // An orthonormal pair orthogonal to v, against the axis least aligned with it.
  const vec3 a = abs(v.x) <= abs(v.y) && abs(v.x) <= abs(v.z) ? vec3(1.0, 0.0, 0.0)
                 : (abs(v.y) <= abs(v.z) ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
  const vec3 w1 = normalize(cross(a, v)), w2 = cross(v, w1);
  SolJacobi y = SolJacobi(vec3(0.0), w1, vec3(0.0), w2, v, vec3(0.0), vec2(1.0));
  const int steps = max(1, int(ceil(t / kSpreadingStep)));
  const float h = t / float(steps);
  // Stage i & 3 of step i / 4: k_i at `at`; sum = k1 + 2 k2 + 2 k3 + k4.
  SolJacobi at = y, sum = y;
  int i = 0;
  do {
    const int stage = i & 3;
    const SolJacobi k = sol_jacobi_rate(at);
    if (stage == 0) {
      sum = k;
    } else {
      sum = sol_jacobi_step(sum, stage == 3 ? 1.0 : 2.0, k);
    }
    if (stage == 3) {
      y = sol_jacobi_step(y, h / 6.0, sum);
      at = y;
    } else {
      at = sol_jacobi_step(y, stage == 2 ? h : 0.5 * h, k);
    }
  } while (++i < 4 * steps);
  SolSpread s;
  s.density = abs(dot(cross(y.x1, y.x2), normalize(y.u)));
  s.position = y.p;
  s.direction = normalize(y.u);
  return s;
}

float sol_sphere_area_density(vec3 direction, float t) { return sol_spread(direction, t).density; }

// The Jacobian of the exponential map at the origin, d exp(v)/dv, for the
// connection solver's Newton steps (sol_newton in sol_connection.glsl), in
// frame components at the height w_z (the target's) where exp(v) lies at
// the height z_end. A variation δv moves exp(v) by the Jacobi field ξ along
// the geodesic with ξ(0) = 0, ξ'(0) = δv / t (t = |v|, arc length s = t τ
// for the curve τ -> exp(τ v)), taken at s = t: so the columns are the
// fields ξ_i with ξ_i'(0) = e_i / t, integrated with the velocity by RK4 in
// equal steps of at most kJacobianStep (as sol_sphere_area_density, with
// three fields), then moved from the frame at exp(v) to the frame at w_z
// (x scales by e^{z_end - w_z}, y by its inverse). Products and sums only
// (one exp), where a forward-difference Jacobian takes three closed-form
// evaluations (each a ray's set-up, its integrals and a position). Step
// 0.25: at 0.5 the Newton iterations near the cut locus, where J is nearly
// singular, converged too slowly (test Kernel.ExpJacobianMatchesDifferences
// holds it to the double flow).
const float kJacobianStep = 0.25;

struct SolFields {
  vec3 u;     // the velocity
  mat3 x, d;  // the three fields (columns) and their δu
};

SolFields sol_fields_rate(SolFields y) {
  SolFields r;
  r.u = vec3(y.u.x * y.u.z, -y.u.y * y.u.z, y.u.y * y.u.y - y.u.x * y.u.x);
  for (int i = 0; i < 3; ++i) {
    vec3 rx, rd;
    sol_variation(y.u, y.x[i], y.d[i], rx, rd);
    r.x[i] = rx;
    r.d[i] = rd;
  }
  return r;
}

SolFields sol_fields_step(SolFields y, float h, SolFields k) {
  return SolFields(y.u + h * k.u, y.x + h * k.x, y.d + h * k.d);
}

mat3 sol_exp_jacobian(vec3 v, float z_end, float w_z) {
  const float t = length(v);
  if (!(t > 0.0)) return mat3(1.0);  // exp(v) = v to first order at 0
  SolFields y = SolFields(v / t, mat3(0.0), mat3(1.0 / t));
  const int steps = max(1, int(ceil(t / kJacobianStep)));
  const float h = t / float(steps);
  for (int s = 0; s < steps; ++s) {
    const SolFields k1 = sol_fields_rate(y);
    const SolFields k2 = sol_fields_rate(sol_fields_step(y, 0.5 * h, k1));
    const SolFields k3 = sol_fields_rate(sol_fields_step(y, 0.5 * h, k2));
    const SolFields k4 = sol_fields_rate(sol_fields_step(y, h, k3));
    y.u += (h / 6.0) * (k1.u + 2.0 * k2.u + 2.0 * k3.u + k4.u);
    y.x += (h / 6.0) * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x);
    y.d += (h / 6.0) * (k1.d + 2.0 * k2.d + 2.0 * k3.d + k4.d);
  }
  const float e = exp(z_end - w_z);
  const vec3 to_w = vec3(e, 1.0 / e, 1.0);
  return mat3(y.x[0] * to_w, y.x[1] * to_w, y.x[2] * to_w);
}

#endif  // SOL_SPREADING_GLSL
