// The deferred passes' lists (docs/renderer.md "Deferred passes"; layout in
// sol/vk/march_interface.h): the march pass appends the rays the resume
// pass goes on with and the hits the shade pass shades; those passes read
// one record per invocation.
#ifndef SOL_MARCH_QUEUE_GLSL
#define SOL_MARCH_QUEUE_GLSL

// A pixel of the (side-by-side) image in one word, and back.
uint pack_pixel(ivec2 pixel) { return uint(pixel.x) | (uint(pixel.y) << 16); }
ivec2 unpack_pixel(uint word) { return ivec2(int(word & 0xffffu), int(word >> 16)); }

// The records a dispatch's lists have room for: one per pixel of its tile.
int queue_capacity() { return params.tile.z * params.tile.w; }

// A new record's slot in a list (its count in `header.w`), counting the
// list's workgroups in header.x as records fill them.
#define SOL_QUEUE_APPEND(header, slot)                                  \
  {                                                                     \
    slot = atomicAdd(header.w, 1);                                      \
    if (slot % (kGroupSize * kGroupSize) == 0) atomicAdd(header.x, 1);  \
  }

// This invocation's record in a resume or shade dispatch.
int queue_slot() { return int(gl_WorkGroupID.x) * kGroupSize * kGroupSize + int(gl_LocalInvocationIndex); }

// Unit vectors in two floats (the octahedral map; exact up to float rounding).
vec2 octahedral_encode(vec3 n) {
  const vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
}
vec3 octahedral_decode(vec2 p) {
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}

// The march pass: a hit for the shade pass (q, t, its normal, the scene
// object it lies on, its pattern's coordinates and the ray's unit tangent u
// there, which a path goes on from).
void defer_shading(ivec2 pixel, vec3 q, float t, vec3 n, int object, vec2 uv, vec3 u) {
  int slot;
  SOL_QUEUE_APPEND(queue.shade, slot);
  const int at = kQueueResumeRecord * queue_capacity() + kQueueShadeRecord * slot;
  queue_records[at] = uvec4(floatBitsToUint(q), floatBitsToUint(t));
  queue_records[at + 1] = uvec4(floatBitsToUint(octahedral_encode(n)), pack_pixel(pixel), uint(object));
  queue_records[at + 2] = uvec4(floatBitsToUint(uv), floatBitsToUint(octahedral_encode(u)));
}

// The march pass: a ray for the resume pass. In Sol one that reached an
// exact ball's shell, to go on with from arc length t, march step `step`,
// with the cutout planes it is passing; in the quotient one of μ below
// kZetaLeastMu, which the resume pass marches from its start (0, 0, 0).
void defer_exact(ivec2 pixel, float t, uint passing, int step) {
  int slot;
  SOL_QUEUE_APPEND(queue.resume, slot);
  queue_records[kQueueResumeRecord * slot] = uvec4(pack_pixel(pixel), floatBitsToUint(t), passing, uint(step));
}

#endif  // SOL_MARCH_QUEUE_GLSL
