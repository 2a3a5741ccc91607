// How light spreads along a geodesic: J(v, t), the area of the geodesic
// sphere of radius t per unit solid angle at the direction v (frame
// components at the start). The float method of sol::sphere_area_density
// (libsol/include/sol/spreading.hpp has the derivation): the velocity u and
// two Jacobi fields (ξ in frame components at the current point, δu the
// variation of u) integrated together by classical RK4 in equal steps of at
// most kSpreadingStep; J = |det[ξ1, ξ2, u]|.
#ifndef SOL_SPREADING_GLSL
#define SOL_SPREADING_GLSL

#include "sol/kernel_constants.h"

struct SolJacobi {
  vec3 x1, d1;  // the first field ξ and its δu
  vec3 x2, d2;  // the second
  vec3 u;       // the velocity, frame components
};

// The linearised geodesic equations of one field along u.
void sol_variation(vec3 u, vec3 x, vec3 d, out vec3 dx, out vec3 dd) {
  dx = vec3(d.x + u.x * x.z - u.z * x.x, d.y - u.y * x.z + u.z * x.y, d.z);
  dd = vec3(u.z * d.x + u.x * d.z, -u.z * d.y - u.y * d.z, 2.0 * (u.y * d.y - u.x * d.x));
}

SolJacobi sol_jacobi_rate(SolJacobi y) {
  SolJacobi r;
  sol_variation(y.u, y.x1, y.d1, r.x1, r.d1);
  sol_variation(y.u, y.x2, y.d2, r.x2, r.d2);
  r.u = vec3(y.u.x * y.u.z, -y.u.y * y.u.z, y.u.y * y.u.y - y.u.x * y.u.x);
  return r;
}

SolJacobi sol_jacobi_step(SolJacobi y, float h, SolJacobi k) {
  return SolJacobi(y.x1 + h * k.x1, y.d1 + h * k.d1, y.x2 + h * k.x2, y.d2 + h * k.d2, y.u + h * k.u);
}

float sol_sphere_area_density(vec3 direction, float t) {
  const vec3 v = normalize(direction);
  // An orthonormal pair orthogonal to v, against the axis least aligned with it.
  const vec3 a = abs(v.x) <= abs(v.y) && abs(v.x) <= abs(v.z) ? vec3(1.0, 0.0, 0.0)
                 : (abs(v.y) <= abs(v.z) ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
  const vec3 w1 = normalize(cross(a, v)), w2 = cross(v, w1);
  SolJacobi y = SolJacobi(vec3(0.0), w1, vec3(0.0), w2, v);
  const int steps = max(1, int(ceil(t / kSpreadingStep)));
  const float h = t / float(steps);
  for (int s = 0; s < steps; ++s) {
    const SolJacobi k1 = sol_jacobi_rate(y);
    const SolJacobi k2 = sol_jacobi_rate(sol_jacobi_step(y, 0.5 * h, k1));
    const SolJacobi k3 = sol_jacobi_rate(sol_jacobi_step(y, 0.5 * h, k2));
    const SolJacobi k4 = sol_jacobi_rate(sol_jacobi_step(y, h, k3));
    y.x1 += h / 6.0 * (k1.x1 + 2.0 * k2.x1 + 2.0 * k3.x1 + k4.x1);
    y.d1 += h / 6.0 * (k1.d1 + 2.0 * k2.d1 + 2.0 * k3.d1 + k4.d1);
    y.x2 += h / 6.0 * (k1.x2 + 2.0 * k2.x2 + 2.0 * k3.x2 + k4.x2);
    y.d2 += h / 6.0 * (k1.d2 + 2.0 * k2.d2 + 2.0 * k3.d2 + k4.d2);
    y.u += h / 6.0 * (k1.u + 2.0 * k2.u + 2.0 * k3.u + k4.u);
  }
  return abs(dot(cross(y.x1, y.x2), normalize(y.u)));
}

#endif  // SOL_SPREADING_GLSL
