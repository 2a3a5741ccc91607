#version 450
// Evaluates the kernel's closed-form geodesic for a list of (direction, arc
// length) pairs: the test that holds sol_geodesic.glsl to libsol's double
// closed form (tests/kernel_test.cpp), also walked in segments
// (sol_ray_advanced).
#extension GL_GOOGLE_include_directive : require

#include "sol_geodesic.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
// More than 1: the arc length is walked in this many equal segments, the ray
// restarted at the end of each (forward: sol_ray_restarted, as the quotient
// march does at its teleports; backward: sol_ray_advanced) and the positions
// composed by the group law.
layout(constant_id = 0) const int SEGMENTS = 1;
// What to evaluate: 0 the position (and the height); 1 the unit tangent at
// arc length w >= 0, as sol_forward gives it to the quotient march's
// clearances; 2 the cut time (sol_cut_time) of the direction, in x; 3 the
// position at arc length w >= 0 by Jacobi's zeta function (sol_forward_zeta,
// walked in SEGMENTS as the quotient march's first pass restarts its rays:
// sol_ray_restarted_zeta); 4 the unit tangent there by sol_forward_zeta.
layout(constant_id = 1) const int VALUE = 0;

layout(std430, set = 0, binding = 0) readonly buffer Queries {
  vec4 queries[];  // xyz: direction (frame components), w: arc length
};
layout(std430, set = 0, binding = 1) writeonly buffer Results {
  vec4 results[];  // xyz: position, w: height from sol_height
};
layout(push_constant) uniform Count {
  uint count;
} pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const vec4 query = queries[i];
  if (VALUE == 3 || VALUE == 4) {
    SolRay zeta = sol_ray(query.xyz);
    sol_ray_zeta(zeta);
    if (VALUE == 4) {
      results[i] = vec4(sol_forward_zeta(zeta, query.w).direction, 0.0);
      return;
    }
    const float segment = query.w / float(SEGMENTS);
    vec3 origin = vec3(0.0);
    for (int k = 0; k < SEGMENTS; ++k) {
      const SolForward f = sol_forward_zeta(zeta, segment);
      origin = sol_translate(origin, f.position);
      zeta = sol_ray_restarted_zeta(zeta, f);
    }
    results[i] = vec4(origin, 0.0);
    return;
  }
  SolRay ray = sol_ray(query.xyz);
  sol_ray_integrals(ray);
  if (VALUE == 1) {
    results[i] = vec4(sol_forward(ray, query.w).direction, 0.0);
    return;
  }
  if (VALUE == 2) {
    results[i] = vec4(sol_cut_time(normalize(query.xyz)), 0.0, 0.0, 0.0);
    return;
  }
  if (SEGMENTS == 1) {
    // Forward arc lengths through the march's path (sol_position_forward).
    const vec3 position = query.w >= 0.0 ? sol_position_forward(ray, query.w) : sol_position(ray, query.w);
    results[i] = vec4(position, sol_height(ray, query.w));
    return;
  }
  const float segment = query.w / float(SEGMENTS);
  vec3 origin = vec3(0.0);
  for (int k = 0; k < SEGMENTS; ++k) {
    if (segment >= 0.0) {  // as the quotient march restarts its rays (sol_ray_restarted)
      const SolForward f = sol_forward(ray, segment);
      origin = sol_translate(origin, f.position);
      ray = sol_ray_restarted(ray, segment, f);
    } else {
      origin = sol_translate(origin, sol_position(ray, segment));
      ray = sol_ray_advanced(ray, segment);
    }
  }
  results[i] = vec4(origin, origin.z);
}
