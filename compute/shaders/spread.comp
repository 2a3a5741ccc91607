#version 450
// Evaluates the kernel's J (sol_spreading.glsl) for a list of (direction,
// arc length) pairs: the test that holds it to libsol's double
// sol::sphere_area_density (tests/kernel_test.cpp); or (VALUE 1) the
// Jacobian of the exponential map at v = direction * arc length
// (sol_exp_jacobian, in frame components at its end point), held to
// differences of the double flow; or (VALUE 2) the logarithm's series at
// w = the query's xyz (sol_log_series, sol/log_series.h: the exact balls'
// Newton starts), held to the double exponential map; or (VALUE 3) the
// geodesic's end point and unit tangent there (sol_spread: a glowing
// ball's sampled point), held to the double closed form.
#extension GL_GOOGLE_include_directive : require

#include "sol/log_series.h"
#include "sol_spreading.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
// 0: J, one float per query; 1: the exponential map's Jacobian, nine
// floats per query (column-major); 2: the logarithm's series, three floats
// per query; 3: the end point and tangent, six floats per query.
layout(constant_id = 0) const int VALUE = 0;

layout(std430, set = 0, binding = 0) readonly buffer Queries {
  vec4 queries[];  // xyz: direction (frame components), w: arc length; VALUE 2: xyz the target w
};
layout(std430, set = 0, binding = 1) writeonly buffer Results {
  float results[];  // J, the Jacobians, or the series' vectors
};
layout(push_constant) uniform Count {
  uint count;
} pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  if (VALUE == 1) {
    const vec4 q = queries[i];
    const mat3 J = sol_exp_jacobian(normalize(q.xyz) * q.w, 0.0, 0.0);  // the frame at the end point
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) results[9 * i + uint(3 * c + r)] = J[c][r];
    }
    return;
  }
  if (VALUE == 2) {
    const vec3 v = sol_log_series(queries[i].xyz);
    for (int c = 0; c < 3; ++c) results[3 * i + uint(c)] = v[c];
    return;
  }
  if (VALUE == 3) {
    const SolSpread s = sol_spread(queries[i].xyz, queries[i].w);
    for (int c = 0; c < 3; ++c) {
      results[6 * i + uint(c)] = s.position[c];
      results[6 * i + uint(3 + c)] = s.direction[c];
    }
    return;
  }
  results[i] = sol_sphere_area_density(queries[i].xyz, queries[i].w);
}
