#version 450
// Evaluates the kernel's J (sol_spreading.glsl) for a list of (direction,
// arc length) pairs: the test that holds it to libsol's double
// sol::sphere_area_density (tests/kernel_test.cpp).
#extension GL_GOOGLE_include_directive : require

#include "sol_spreading.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std430, set = 0, binding = 0) readonly buffer Queries {
  vec4 queries[];  // xyz: direction (frame components), w: arc length
};
layout(std430, set = 0, binding = 1) writeonly buffer Results {
  float results[];  // J
};
layout(push_constant) uniform Count {
  uint count;
} pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  results[i] = sol_sphere_area_density(queries[i].xyz, queries[i].w);
}
