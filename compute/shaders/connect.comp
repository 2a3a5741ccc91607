#version 450
// Runs the kernel's connection solver (sol_connection.glsl) on a list of
// targets: the test that holds it to libsol's sol::geodesics_between
// (tests/kernel_test.cpp).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_control_flow_attributes : require

#include "sol_geodesic.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;
// Built twice, as march.comp: every connection found kept (the longer
// connections' table, queries with a reach), or with SOL_MINIMISERS_BUILD
// the minimisers' 4 slots.
#ifdef SOL_MINIMISERS_BUILD
#define SOL_FOUND_SLOTS 4
#endif

layout(std430, set = 0, binding = 0) readonly buffer Queries {
  vec4 queries[];  // xyz: w (the target seen from the origin), w: reach
};
layout(std430, set = 0, binding = 1) writeonly buffer Results {
  vec4 results[];  // per query kSeedSlots + 1 entries: the connections (direction, length), then (count, 0, 0, 0)
};
layout(std430, set = 0, binding = 2) readonly buffer ConnectionSeeds {
  vec4 connection_seeds[];
};
layout(push_constant) uniform Count {
  uint count;
} pc;

#include "sol_connection.glsl"

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec4 found[SOL_FOUND_SLOTS];
  const int n = sol_connections(queries[i].xyz, queries[i].w, found);
  const uint base = i * uint(kSeedSlots + 1);
  for (int s = 0; s < SOL_FOUND_SLOTS; ++s) results[base + uint(s)] = found[s];
  for (int s = SOL_FOUND_SLOTS; s < kSeedSlots; ++s) results[base + uint(s)] = vec4(0.0);
  results[base + uint(kSeedSlots)] = vec4(float(n), 0.0, 0.0, 0.0);
}
