#version 450
// The Sol ray-marcher: one invocation per pixel. The GLSL twin of libsol's
// CPU reference (libsol/src/render.cpp, documented in sol/render.hpp):
// camera-relative scene, closed-form geodesic precomputed once per ray and
// evaluated at the accumulated arc length from the ray's origin (no error
// accumulates), exact plane distances, the same shading.
//
// INTEGRATOR = 1 replaces the closed form by classical RK4 on the geodesic
// ODE in frame components with step `forward.w`; it advances from the last
// step's state, so its error accumulates (that is what the bench measures).
//
// Loops tested at their end. lavapipe runs a loop's body, masked, until no
// lane is left in it, and tests that at the body's end: a loop whose
// condition comes first (for, while) runs its body once more after its
// last lane has left, every lane masked. The loops whose bodies are dear
// (the march's steps and rounds, the objects of a step, the quotient's
// candidates, Newton's iterations) are written as do-while, tested at the
// end, behind an if where they may run no time: they run as often as their
// slowest lane needs (docs/renderer.md, "What lavapipe runs").
#extension GL_GOOGLE_include_directive : require

#include "sol/vk/march_interface.h"
#include "sol_geodesic.glsl"

// Bindings, specialisation-constant ids, limits, codes and the uniform
// layout: sol/vk/march_interface.h, shared with the host (compute/src/march.cpp).
layout(local_size_x = kGroupSize, local_size_y = kGroupSize, local_size_z = 1) in;
layout(constant_id = kSpecIntegrator) const int INTEGRATOR = 0;
// Every object a plane z = c: the march needs heights only. A specialisation
// constant, not a uniform: lavapipe evaluates both sides of every branch, so
// only a compile-time branch saves the other side's cost.
layout(constant_id = kSpecHeightsOnly) const bool HEIGHTS_ONLY = false;
// What else the scene uses: the compiler folds away what it does not.
layout(constant_id = kSpecBalls) const bool HAS_BALLS = true;  // balls or tubes
layout(constant_id = kSpecBoundBalls) const bool HAS_BOUND_BALLS = true;
layout(constant_id = kSpecTubes) const bool HAS_TUBES = true;
layout(constant_id = kSpecPlanesZ) const bool HAS_PLANES_Z = true;
layout(constant_id = kSpecPlanesXY) const bool HAS_PLANES_XY = true;
// Every object a plane x = c or y = c (sol::MarchFeatures::planes_xy_only):
// their crossing solved (plane_xy_roots) is the whole march.
layout(constant_id = kSpecPlanesXYOnly) const bool PLANES_XY_ONLY_WORLD = false;
// (The roots need the closed form: with RK4 such a world is marched.)
const bool PLANES_XY_ONLY = PLANES_XY_ONLY_WORLD && INTEGRATOR == 0;
layout(constant_id = kSpecPointLights) const bool HAS_POINT_LIGHTS = true;
layout(constant_id = kSpecFog) const bool HAS_FOG = true;
layout(constant_id = kSpecCutout) const bool HAS_CUTOUT = true;
// The compact quotient Γ\Sol (see march_quotient below).
layout(constant_id = kSpecQuotient) const bool QUOTIENT = false;
// Write the AOV images (bindings kBindingHit, kBindingPoint); off for
// presenters, which take the colour alone (MarchRenderer::record) and bind
// the colour image there too.
layout(constant_id = kSpecWriteAovs) const bool WRITE_AOVS = true;
// Exact balls (kObjectExactBall): the exact distance near their sphere (sol_shortest).
layout(constant_id = kSpecExactBalls) const bool HAS_EXACT_BALLS = false;
// Exact point lights (kLightExactPoint): directions along the geodesics to
// the light from sol_connection.glsl, seeded by the table in kBindingSeeds.
layout(constant_id = kSpecExactLights) const bool HAS_EXACT_LIGHTS = false;
// Exact point lights with a reach (the longer connections): only they look
// for the partners of connections near a fold (sol_connections), code that
// costs the kernel even where it never runs.
layout(constant_id = kSpecLightReach) const bool HAS_LIGHT_REACH = false;
#define SOL_FOLD_PARTNERS HAS_LIGHT_REACH
// Without a reach a light's search keeps the minimisers (4 slots), with one
// every connection found (sol_connection.glsl): a separate build of this
// kernel for lights with a reach (SOL_LIGHT_REACH_BUILD, march_reach_*),
// whose pipelines set HAS_LIGHT_REACH.
#ifdef SOL_LIGHT_REACH_BUILD
#define SOL_FOUND_SLOTS kSeedSlots
#else
#define SOL_FOUND_SLOTS 4
#endif
// Equirectangular or fisheye eyes (a uniform says which): compiled in only
// for them, so the perspective kernels keep their cost.
layout(constant_id = kSpecProjections) const bool HAS_PROJECTIONS = false;
// Omnidirectional stereo eyes: each column's rays start at its own eye
// (kBindingColumns); compiled in only for them.
layout(constant_id = kSpecOds) const bool HAS_ODS = false;
// Shadows of exact point lights (params.light_shadows): compiled in only for them.
layout(constant_id = kSpecShadows) const bool HAS_SHADOWS = false;
// The deferred passes (sol/vk/march_interface.h, docs/renderer.md): which
// pass this pipeline runs, and what its march pass leaves to the others.
layout(constant_id = kSpecPass) const int PASS = kPassMarch;
layout(constant_id = kSpecDeferShading) const bool DEFER_SHADING = false;
layout(constant_id = kSpecResume) const bool RESUME_WORLD = false;
// (Only the Sol march, with the closed form, stops at exact balls' shells.)
const bool DEFER_EXACT = RESUME_WORLD && HAS_EXACT_BALLS && !QUOTIENT && INTEGRATOR == 0;
// The quotient's march pass leaves the rays of μ below kZetaLeastMu to the
// resume pass: it marches the others with the zeta function's positions
// alone, the resume pass those with Carlson's integrals alone
// (quotient_forward).
const bool DEFER_SMALL_MU = RESUME_WORLD && QUOTIENT;
// The same in Sol for worlds of exact balls (the closed form): a ray of μ
// >= kZetaLeastMu takes the zeta function's positions up to its first
// exact shell, and from there on, as every other ray, Carlson's integrals.
// The march pass stops there (or, for the others, before the first step):
// the resume pass takes Carlson's alone. In one dispatch a ray's first
// round (`zeta_round`) ends where the march pass would stop and the next
// takes that step again by Carlson's integrals, so that both render the
// same image.
const bool SOL_ZETA = HAS_EXACT_BALLS && !QUOTIENT && INTEGRATOR == 0 && PASS == kPassMarch;
const bool SOL_ZETA_ONLY = SOL_ZETA && DEFER_EXACT;

layout(std140, set = 0, binding = kBindingParams) uniform ParamsBlock {
  Params params;
};

#ifdef SOL_OUTPUT_SRGB_UNORM
// The presenters' 8-bit output (a separate SPIR-V build, march_srgb_unorm;
// MarchRenderer::record with a UnormTarget): the colour, sRGB-encoded, into
// an R8G8B8A8 or B8G8R8A8 UNORM image such as a storage-capable swapchain
// image. No format qualifier, as GLSL names no BGRA format: this needs the
// shaderStorageImageWriteWithoutFormat feature, so it stays out of the
// default build.
layout(set = 0, binding = kBindingColor) uniform writeonly image2D color_image;
#else
// Read as well as written: anti-aliasing accumulates its samples here (accumulate()).
layout(set = 0, binding = kBindingColor, rgba32f) uniform image2D color_image;
#endif
layout(set = 0, binding = kBindingHit, rgba32f) uniform writeonly image2D aov_hit;      // object, distance, steps, 0
layout(set = 0, binding = kBindingPoint, rgba32f) uniform writeonly image2D aov_point;  // Px, Py, Pz, 0
// Quotient scenes: the images of the objects around D, in world coordinates
// (sol::quotient_images).
layout(std430, set = 0, binding = kBindingImages) readonly buffer Images {
  Image images[];
};

// sol::QuotientField: the quotient world's field over D, each cell's
// candidate images and reach (layout in sol/quotient_field.hpp).
layout(std430, set = 0, binding = kBindingField) readonly buffer QuotientField {
  uint field_words[];
};

// Omnidirectional stereo: each eye's columns (sol::column_eye), eye e's
// column i at e × width + i.
layout(std430, set = 0, binding = kBindingColumns) readonly buffer Columns {
  Column columns[];
};

// The quotient: the images of its exact point lights (sol::quotient_light_images).
layout(std430, set = 0, binding = kBindingLightImages) readonly buffer LightImages {
  vec4 light_images[];
};

// sol::ConnectionTable: the seeds of the connection solver (exact point lights).
layout(std430, set = 0, binding = kBindingSeeds) readonly buffer ConnectionSeeds {
  vec4 connection_seeds[];
};

// The deferred passes' lists (QueueHeader, then the records).
layout(std430, set = 0, binding = kBindingQueue) buffer Queue {
  QueueHeader queue;
  uvec4 queue_records[];
};

#include "sol_connection.glsl"
#include "sol_spreading.glsl"

// ---- The deferred passes' lists (layout in sol/vk/march_interface.h)

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

// The march pass: a hit for the shade pass (q, t, its normal, and the scene
// object, or in the quotient the image, it lies on).
void defer_shading(ivec2 pixel, vec3 q, float t, vec3 n, int index) {
  int slot;
  SOL_QUEUE_APPEND(queue.shade, slot);
  const int at = kQueueResumeRecord * queue_capacity() + kQueueShadeRecord * slot;
  queue_records[at] = uvec4(floatBitsToUint(q), floatBitsToUint(t));
  queue_records[at + 1] = uvec4(floatBitsToUint(octahedral_encode(n)), pack_pixel(pixel), uint(index));
}

// The pixel of a workgroup's invocation: runs of 8 invocations (lavapipe's
// SIMD group on AVX2: it runs the invocation indices in order, 8 to a
// vector) cover 2 x 4 pixels, four of them side by side make 8 x 4 (a
// 32-lane GPU warp), two such bands the 8 x 8 group. A SIMD group marches
// until its slowest lane is done, and a compact block of pixels holds rays
// of more nearly equal steps than a row of 8 (on lattice-pillars the
// slowest of 8 takes 1.12x the mean steps instead of 1.21x; docs/renderer.md).
ivec2 group_pixel(int index) {
  const int lane = index & 7, run = index >> 3;
  return ivec2((run & 3) * 2 + (lane & 1), (run >> 2) * 4 + (lane >> 1));
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

// A height's half exponentials (e^{z/2}, e^{-z/2}): the bounds below take
// e^{±z} as their squares and e^{±Δz/2} as their products, so that they
// divide by neither (a march step takes its point's once for all objects,
// and the objects' come with them). One exponential and its reciprocal:
// on lavapipe a division costs less than a second exponential.
vec2 half_exp(float z) {
  const float h = exp(0.5 * z);
  return vec2(h, 1.0 / h);
}

// The lower bound of the Sol distance (sol::distance_lower_bound,
// docs/mathematics.md), with the half exponentials of p.z and q.z given
// (`hp`, `hq`): sinh(Δz/2) = (e^{Δz/2} - e^{-Δz/2})/2 from their products,
// as ball_clearance.
float distance_lower_bound(vec3 p, vec3 q, vec2 hp, vec2 hq) {
  const float dx = p.x - q.x, dy = p.y - q.y;
  const vec2 e = hp * hq;  // e^{(p.z + q.z)/2}, e^{-(p.z + q.z)/2}
  const float a = 0.5 * max(dx * dx * e.y * e.y, dy * dy * e.x * e.x);
  const float sh = 0.5 * (hp.x * hq.y - hp.y * hq.x);
  const float s2 = sh * sh + 0.5 * a;
  return 2.0 * log(sqrt(s2) + sqrt(1.0 + s2));  // 2 asinh √s2
}

float distance_lower_bound(vec3 p, vec3 q) { return distance_lower_bound(p, q, half_exp(p.z), half_exp(q.z)); }

// Exact balls near their sphere: the exact distance from the centre c to q
// less the radius, from the shortest geodesic from c to q (sol_shortest,
// started from `v` and its end point `end` when `known`, the last
// solution, and left holding this one); where Newton does not land, the bound
// (safe, but the hit then lies on the bound's surface) and the next solve
// starts afresh.
float exact_ball_sdf(vec3 q, vec3 c, float radius, inout vec3 v, inout SolEnd end, inout bool known, inout mat3 J) {
  const vec3 w = vec3((q.x - c.x) * exp(-c.z), (q.y - c.y) * exp(c.z), q.z - c.z);
  const float residual = sol_shortest(w, v, end, known, J);
  if (residual < 2e-4) return length(v) - radius;
  known = false;
  return distance_lower_bound(q, c) - radius;
}

// The true sphere's outward normal at the end of the geodesic from its
// centre (the last solve's end): that geodesic's tangent there (frame
// components), as sol::sdf_ball_exact_gradient.
vec3 exact_ball_normal(SolEnd end) { return normalize(end.tangent); }

// What binding 1 receives: the linear colour, or for SOL_OUTPUT_SRGB_UNORM
// the standard sRGB OETF (IEC 61966-2-1) of it clamped to [0, 1], what an
// sRGB swapchain's blit and solrender's 8-bit files apply (C++ twin:
// srgb_encode in tests/kernel_test.cpp, which holds the two together).
vec4 output_color(vec4 linear) {
#ifdef SOL_OUTPUT_SRGB_UNORM
  vec3 c = clamp(linear.rgb, 0.0, 1.0);
  vec3 encoded = mix(kSrgbScale * pow(c, vec3(1.0 / kSrgbGamma)) - kSrgbOffset, kSrgbLinearSlope * c,
                     lessThanEqual(c, vec3(kSrgbLinearLimit)));
  return vec4(encoded, clamp(linear.a, 0.0, 1.0));
#else
  return linear;
#endif
}

// This dispatch's sample of the pixel: its colour, blended into the mean of
// the samples already in the image with the sample's weight (params.pixel_sample.z;
// 1 overwrites). The 8-bit output takes one sample (weight 1): nothing to read.
vec4 accumulate(ivec2 pixel, vec4 color, float weight) {
#ifndef SOL_OUTPUT_SRGB_UNORM
  if (weight < 1.0) color = mix(imageLoad(color_image, pixel), color, weight);
#endif
  return color;
}

// Tubes: the bounds of sol::sdf_tube (axis z: the two coordinate planes
// containing it) and sol::sdf_tube_horizontal (a horizontal line along the
// unit coordinate direction h: max(|Δz|, asinh(|h_y Δx - h_x Δy| / (|h_x| e^{-z} + |h_y| e^{z})))).
float tube_distance(vec3 q, vec3 through, int axis, vec2 h, float radius, vec2 hz) {
  const vec3 d = q - through;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;
  if (axis == kTubeVertical) return max(asinh(abs(d.x) * iez), asinh(abs(d.y) * ez)) - radius;
  const float across = abs(h.y * d.x - h.x * d.y) / (abs(h.x) * iez + abs(h.y) * ez);
  return max(asinh(across), abs(d.z)) - radius;
}

// Distance (planes: exact; balls, tubes: the bound minus the radius) to an
// object given in the coordinates of q (camera-relative, or world in the quotient).
// With the half exponentials (half_exp) of q.z (`hz`) and, for balls, of
// rel.z (`hc`) given: a march step shares them among its objects.
float object_distance(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  // Each kind only when the world has it: lavapipe evaluates every branch.
  // Exact balls are approached by the bound too (the true sphere lies inside
  // the bound's), and within kExactShell of it marched by their exact
  // distance (exact_ball_sdf) and its clearance (exact_ball_clearance).
  // (Until 2026-11 a table of d(0, ·) tightened their approach within 0.25
  // of the sphere: its eight reads per ball and step cost more than the
  // exact solves it saved, docs/exact.md.)
  if ((HAS_BOUND_BALLS && type == kObjectBall) || (HAS_EXACT_BALLS && type == kObjectExactBall)) {
    return distance_lower_bound(q, rel.xyz, hz, hc) - radius;
  }
  if (HAS_TUBES && type == kObjectTube) return tube_distance(q, rel.xyz, int(rel.w), heading, radius, hz);
  float c = rel.x;
  if (HAS_PLANES_XY && type == kObjectPlaneX) return asinh(abs(q.x - c) * hz.y * hz.y);
  if (HAS_PLANES_XY && type == kObjectPlaneY) return asinh(abs(q.y - c) * hz.x * hz.x);
  return abs(q.z - c);
}

float object_distance(int type, vec3 q, vec4 rel, vec2 heading, float radius) {
  const bool ball = (HAS_BOUND_BALLS && type == kObjectBall) || (HAS_EXACT_BALLS && type == kObjectExactBall);
  return object_distance(type, q, rel, heading, radius, half_exp(q.z), ball ? half_exp(rel.z) : vec2(1.0));
}

// ---- Clearances (sol/clearance.hpp): how far the geodesic from q with unit
// tangent u goes before it can reach an object, to second order. Each term h
// of a bound (a maximum of terms) with h' = slope and h'' >= -curvature
// stays positive up to the first root of h + slope s - ½ curvature s².

float clearance_root(float h, float slope, float curvature) {
  const float root = sqrt(slope * slope + 2.0 * curvature * max(h, 0.0));
  const float s = slope >= 0.0 ? (slope + root) / curvature : 2.0 * h / (root - slope);
  return h > 0.0 ? s : 0.0;
}

// clearance_root with curvature 1 both ways along the geodesic, (ahead:
// slope, back: -slope): with B = |slope| + √(slope² + 2h), the root on the
// side the term grows towards is B and the other 2h/B (their product is
// 2h), so one square root and one division give both without cancellation.
vec2 clearance_roots(float h, float slope) {
  const float big = abs(slope) + sqrt(slope * slope + 2.0 * max(h, 0.0));
  const float small = 2.0 * h / max(big, 1e-30);
  const vec2 s = slope >= 0.0 ? vec2(big, small) : vec2(small, big);
  return h > 0.0 ? s : vec2(0.0);
}

// The clearance of an exact ball from q (the kernel's own: the CPU steps by
// the exact distance; derivation in docs/exact.md), where its exact
// distance is f = d - r (d the distance from the centre) and f' = slope
// along the ray, for steps of at most kExactClearanceCap. Sol's
// sectional curvatures are at most 1 (its curvature operator is diagonal
// in the frame, +1, -1, -1), so by the Hessian comparison theorem
// Hess d >= cot(d) (g - ∇d ∇d) where d < π, before any conjugate or cut
// point (those lie at least √2 π away): along the ray f'' >= min(0, cot d),
// and over the step d stays below D = d + cap. So f'' >= -M with M = 0
// where D <= π/2 (f convex: a Newton step never passes its root), -cot D
// up to π - 0.1, and no clearance beyond. Aimed at f = hit_epsilon/2, so
// that float rounding of the slope does not carry the step into the ball.
float exact_ball_clearance(float f, float d, float slope, float eps) {
  const float D = d + kExactClearanceCap;
  const float bend = D <= 1.5707963 ? 1e-6 : -cos(D) / sin(D);
  const float s = min(clearance_root(f - 0.5 * eps, slope, bend), kExactClearanceCap);
  return D < 3.0415927 ? max(f, s) : f;
}

// A ball's bound (sol::ball_terms): the terms d_xz - r, d_yz - r with
// S = sinh(d/2), d' = (S²)'/(S √(1 + S²)). Returns (distance bound,
// clearance along u, clearance back along -u). The half exponentials of q.z (`hz`) and c.z (`hc`) come from
// the caller (the quotient march takes q's once a step for all its
// candidates, and each candidate's centre's; the Sol march keeps each
// ball's per ray): no exponential and no division here but the slopes'.
vec3 ball_clearances(vec3 q, vec3 u, vec3 c, float radius, vec2 hz, vec2 hc) {
  const float dx = q.x - c.x, dy = q.y - c.y;
  const vec2 e = hz * hc, ec = hc * hc;  // e^{±(q.z + c.z)/2}, e^{±c.z}
  const float e2 = e.x * e.x, ie2 = e.y * e.y;  // e^{q.z + c.z}, its inverse
  const float sh = 0.5 * (hz.x * hc.y - hz.y * hc.x), sh2 = sh * sh, half_sinh_dz = sh * sqrt(1.0 + sh2);
  const vec2 s2 = vec2(sh2 + 0.25 * dx * dx * ie2, sh2 + 0.25 * dy * dy * e2);
  const vec2 rate = vec2(half_sinh_dz * u.z + 0.5 * dx * u.x * ec.y - 0.25 * dx * dx * ie2 * u.z,
                         half_sinh_dz * u.z + 0.5 * dy * u.y * ec.x + 0.25 * dy * dy * e2 * u.z);
  const vec2 s = sqrt(s2), root = sqrt(1.0 + s2);
  const vec2 h = 2.0 * log(s + root) - radius;  // 2 asinh s
  const vec2 slope = rate / max(s * root, 1e-30);
  const float distance = max(h.x, h.y);
  return vec3(distance, max(vec2(distance), max(clearance_roots(h.x, slope.x), clearance_roots(h.y, slope.y))));
}

// A tube's bound (sol::tube_terms): vertical, the slabs around x = x0 and
// y = y0; horizontal along h, the z slab and the across term asinh|G|,
// G = (h_y Δx - h_x Δy)/(|h_x| e^{-z} + |h_y| e^{z}) (a slab's along x or
// y); every term bends by at most 1. Returns (distance bound, clearance
// along u, clearance back along -u).
vec3 tube_clearances(vec3 q, vec3 u, vec3 through, int axis, vec2 h, float radius, vec2 hz) {
  // Both forms have two terms; the first is asinh(w) - r for either (w the
  // slab's |Δx| e^{-z}, or |G|), its slope w'/√(1 + w²), so one asinh
  // serves both: the inputs are chosen first (lavapipe runs both sides of
  // every choice, so a shared evaluation is cheaper than two).
  const bool vertical = axis == kTubeVertical;
  const vec3 d = q - through;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;  // e^{±q.z}, from the caller's half exponentials
  const float inv_D = 1.0 / (abs(h.x) * iez + abs(h.y) * ez);
  const float G = (h.y * d.x - h.x * d.y) * inv_D;
  const float rate_G = ((h.y * ez * u.x - h.x * iez * u.y) - G * (abs(h.y) * ez - abs(h.x) * iez) * u.z) * inv_D;
  const float wx = abs(d.x) * iez, rate_wx = (d.x >= 0.0 ? u.x : -u.x) - wx * u.z;
  const float wa = vertical ? wx : abs(G), rate_a = vertical ? rate_wx : (G >= 0.0 ? rate_G : -rate_G);
  const float wy = abs(d.y) * ez, rate_wy = (d.y >= 0.0 ? u.y : -u.y) + wy * u.z;
  const vec2 w = vec2(wa, wy);  // >= 0
  const vec2 root = sqrt(1.0 + w * w);  // shared by asinh w = log(w + root) and its slope
  const vec2 hw = log(w + root) - radius;
  const vec2 sw = vec2(rate_a, rate_wy) / root;
  // The second term: the slab around y = y0 (vertical), or |Δz| - r.
  const float hb = vertical ? hw.y : abs(d.z) - radius, sb = vertical ? sw.y : (d.z >= 0.0 ? u.z : -u.z);
  const float distance = max(hw.x, hb);
  return vec3(distance, max(vec2(distance), max(clearance_roots(hw.x, sw.x), clearance_roots(hb, sb))));
}

// A quotient image's tube bound from its record (Image::bound: the radius
// in the scale of h, the axis in the first word's sign). Both forms are
// two terms, the first asinh|G| - r, G = (h_y x - h_x y - c)/(|h_x| e^{-z}
// + |h_y| e^{z}): a vertical tube's slab around x = x0 is that term with
// h = (0, 1), c = x0, its second the slab around y = y0; a horizontal
// tube's second is |z - z0| - r. As tube_clearances, in four words.
vec3 tube_record_clearances(vec3 q, vec3 u, vec4 b, vec2 hz) {
  const bool vertical = b.x < 0.0;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;  // e^{±q.z}
  const float hx = vertical ? 0.0 : b.x, hy = vertical ? 1.0 : b.y, c = vertical ? b.y : b.z;  // hx >= 0
  const float radius = vertical ? -b.x : b.x + abs(b.y);
  const float inv_D = 1.0 / (hx * iez + abs(hy) * ez);
  const float G = (hy * q.x - hx * q.y - c) * inv_D;
  const float rate_G = ((hy * ez * u.x - hx * iez * u.y) - G * (abs(hy) * ez - hx * iez) * u.z) * inv_D;
  const float dy = q.y - b.z;  // vertical: the slab around y = y0
  const float wy = abs(dy) * ez, rate_wy = (dy >= 0.0 ? u.y : -u.y) + wy * u.z;
  const vec2 w = vec2(abs(G), wy);
  const vec2 root = sqrt(1.0 + w * w);  // shared by asinh w = log(w + root) and its slope
  const vec2 hw = log(w + root) - radius;
  const vec2 sw = vec2(G >= 0.0 ? rate_G : -rate_G, rate_wy) / root;
  const float dz = q.z - b.w;
  const float hb = vertical ? hw.y : abs(dz) - radius, sb = vertical ? sw.y : (dz >= 0.0 ? u.z : -u.z);
  const float distance = max(hw.x, hb);
  return vec3(distance, max(vec2(distance), max(clearance_roots(hw.x, sw.x), clearance_roots(hb, sb))));
}

// The object's distance (object_distance) and clearance, the larger of it
// and the second-order step of its bound (exact balls: the bound's ball,
// which holds the exact one, as object_distance). The objects of the
// quotient: planes z = c, balls and tubes. hz, hc: the half exponentials
// of q.z and (balls only) rel.z.
// object_clearances: the same with the clearance back along -u third (the
// quotient march's check of an over-relaxed step).
vec3 object_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  if ((HAS_BOUND_BALLS && type == kObjectBall) || (HAS_EXACT_BALLS && type == kObjectExactBall)) {
    return ball_clearances(q, u, rel.xyz, radius, hz, hc);
  }
  if (HAS_TUBES && type == kObjectTube) return tube_clearances(q, u, rel.xyz, int(rel.w), heading, radius, hz);
  const float d = object_distance(type, q, rel, heading, radius);
  const float rate = q.z >= rel.x ? u.z : -u.z;
  const vec2 plane_z = max(vec2(d), clearance_roots(d, rate));
  return type == kObjectPlaneZ ? vec3(d, plane_z) : vec3(d);
}

vec2 object_clearance(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return object_clearances(type, q, u, rel, heading, radius, hz, hc).xy;
}

// object_clearances of a quotient image from its bound record
// (Image::bound): balls (centre, radius), tubes (tube_record_clearances),
// planes z = c (c, ...).
vec3 image_clearances(int type, vec3 q, vec3 u, vec4 b, vec2 hz) {
  if ((HAS_BOUND_BALLS && type == kObjectBall) || (HAS_EXACT_BALLS && type == kObjectExactBall)) {
    return ball_clearances(q, u, b.xyz, b.w, hz, half_exp(b.z));
  }
  if (HAS_TUBES && type == kObjectTube) return tube_record_clearances(q, u, b, hz);
  return object_clearances(type, q, u, b, vec2(0.0), 0.0, hz, vec2(1.0));  // planes z = c: the record is (c, ...)
}

// A quotient image's distance (its bound's, image_clearances' first
// component, which the direction does not enter).
float image_distance(int type, vec3 q, vec4 b) { return image_clearances(type, q, vec3(0.0), b, half_exp(q.z)).x; }

// Unit gradient of the distance (sol/distance.hpp) at the hit q, facing the
// camera's side (the origin): the march stops within hit_epsilon, possibly
// just across the plane. Mirrors object_normal in libsol/src/render.cpp.
// The surface normal at q (frame components); planes face the side of `from`, the ray's origin.
vec3 plane_normal(int type, vec3 q, float c, vec4 rel, vec2 heading, float radius, vec3 from) {
  if (HAS_BALLS && type >= kObjectBall) {  // balls, tubes: central differences along E1, E2, E3 (as the CPU reference)
    float h = kNormalStep, ez = exp(q.z);
    vec3 e1 = vec3(h * ez, 0.0, 0.0), e2 = vec3(0.0, h / ez, 0.0), e3 = vec3(0.0, 0.0, h);
    vec3 g = vec3(object_distance(type, q + e1, rel, heading, radius) - object_distance(type, q - e1, rel, heading, radius),
                  object_distance(type, q + e2, rel, heading, radius) - object_distance(type, q - e2, rel, heading, radius),
                  object_distance(type, q + e3, rel, heading, radius) - object_distance(type, q - e3, rel, heading, radius));
    return length(g) > 0.0 ? normalize(g) : vec3(0.0, 0.0, 1.0);
  }
  const float own = type == kObjectPlaneX ? from.x : (type == kObjectPlaneY ? from.y : from.z);
  float side = own >= c ? 1.0 : -1.0;
  if (type == kObjectPlaneX) {
    float w = abs(q.x - c) * exp(-q.z), r = inversesqrt(1.0 + w * w);
    return vec3(side * r, 0.0, -w * r);
  }
  if (type == kObjectPlaneY) {
    float w = abs(q.y - c) * exp(q.z), r = inversesqrt(1.0 + w * w);
    return vec3(0.0, side * r, w * r);
  }
  return vec3(0.0, 0.0, side);
}

float pattern_factor(int pattern, float u, float v) {
  if (pattern == kPatternCircles) {
    float du = fract(u) - 0.5, dv = fract(v) - 0.5;
    return du * du + dv * dv < kCircleRadius * kCircleRadius ? 1.0 : kCircleDark;
  }
  if (pattern == kPatternChecker) return mod(floor(u) + floor(v), 2.0) == 0.0 ? 1.0 : kCheckerDark;
  return 1.0;
}

// Pattern coordinates on a ball or tube (sol::Ball::pattern_uv, sol::Tube::pattern_uv) of a point
// q given in the coordinates of the centre (axis point) `rel`: with
// w = rel⁻¹·q, balls (4/π)(longitude, latitude); tubes (4/π)(angle around
// the axis, coordinate along it / radius).
vec2 solid_coordinates(int type, vec3 q, vec4 rel, vec2 heading, float radius) {
  const float cells = kPatternCellsPerRadian;
  const float ez = exp(rel.z);
  const vec3 w = vec3((q.x - rel.x) / ez, (q.y - rel.y) * ez, q.z - rel.z);
  if (type == kObjectBall || type == kObjectExactBall) return cells * vec2(atan(w.y, w.x), atan(w.z, length(w.xy)));
  if (int(rel.w) == kTubeVertical) return cells * vec2(atan(w.y, w.x), w.z / radius);
  const vec2 h = normalize(vec2(heading.x / ez, heading.y * ez));
  return cells * vec2(atan(w.z, w.y * h.x - w.x * h.y), dot(w.xy, h) / radius);
}

// sol::cutout_gap_bound: a lower bound of the distance to the solid part of
// a cutout plane z = c (discs, light squares) from a point with world
// coordinates (u, v) (modulo 2) and e^{z} = ez; combined with |z - c| by max.
float cutout_gap_bound(int pattern, vec2 uv, float ez) {
  const vec2 f = fract(uv);
  if (pattern == kPatternChecker) {
    if (mod(floor(uv.x) + floor(uv.y), 2.0) == 0.0) return 0.0;  // on a light square
    return asinh(min(min(f.x, 1.0 - f.x) / ez, min(f.y, 1.0 - f.y) * ez));
  }
  const vec2 d = abs(f - 0.5);
  const float boxes = max(max(0.0, d.x - kCircleRadius) / ez, max(0.0, d.y - kCircleRadius) * ez);
  const float gap = max(0.0, length(d) - kCircleRadius);
  return asinh(max(boxes, min(ez, 1.0 / ez) * gap * 0.70710678));
}

// The plane's own world coordinates of a camera-relative point q: world =
// camera * q; the pattern takes the camera position modulo 2 (exact, from double).
vec2 plane_coordinates(int type, vec3 q, vec4 eye_camera, vec4 eye_frac) {
  const vec3 phase = eye_frac.xyz + vec3(eye_camera.w * q.x, eye_frac.w * q.y, q.z);
  return type == kObjectPlaneX ? phase.yz : (type == kObjectPlaneY ? phase.xz : phase.xy);
}

// Geodesic ODE in frame components: x' = e^{z}u1, y' = e^{-z}u2, z' = u3,
// u1' = u1 u3, u2' = -u2 u3, u3' = u2² - u1².
void geodesic_rhs(vec3 p, vec3 u, out vec3 dp, out vec3 du) {
  float ez = exp(p.z);
  dp = vec3(ez * u.x, u.y / ez, u.z);
  du = vec3(u.x * u.z, -u.y * u.z, u.y * u.y - u.x * u.x);
}

void rk4_advance(inout vec3 p, inout vec3 u, float length, float step) {
  int n = max(1, int(ceil(length / step)));
  float h = length / float(n);
  for (int i = 0; i < n; ++i) {
    vec3 p1, u1, p2, u2, p3, u3, p4, u4;
    geodesic_rhs(p, u, p1, u1);
    geodesic_rhs(p + 0.5 * h * p1, u + 0.5 * h * u1, p2, u2);
    geodesic_rhs(p + 0.5 * h * p2, u + 0.5 * h * u2, p3, u3);
    geodesic_rhs(p + h * p3, u + h * u3, p4, u4);
    p += h / 6.0 * (p1 + 2.0 * p2 + 2.0 * p3 + p4);
    u += h / 6.0 * (u1 + 2.0 * u2 + 2.0 * u3 + u4);
  }
}

// ---- The quotient Γ\Sol of the golden lattice (mirrors march_quotient in
// libsol/src/render.cpp and sol::Lattice::golden()) ----------------------------

// (s, r) = [γ1 γ2]^{-1} (x, y), γ1 = (φ, -1), γ2 = (1, φ): a point's lattice
// coordinates (multiplied by the constant 1/(φ² + 1): no division per step).
const float kInverseDet = 1.0 / (kPhi * kPhi + 1.0);
vec2 lattice_coordinates(vec3 p) { return vec2(kPhi * p.x - p.y, p.x + kPhi * p.y) * kInverseDet; }

bool in_domain(vec3 p) {
  const vec2 sr = lattice_coordinates(p);
  return sr.x >= 0.0 && sr.x < 1.0 && sr.y >= 0.0 && sr.y < 1.0 && p.z >= 0.0 && p.z < kLatticeHeight;
}

// The point of D equivalent to p under Γ: γ3^n fixes z (scaling x by φ^{2n},
// y by φ^{-2n}), then γ1, γ2 translate (x, y) into the parallelogram. With
// `step_end` (a constant at each call), p is the end of a march step from a
// point of D, less than kLatticeHeight long, so n is -1, 0 or 1 and φ^{±2n}
// a choice between constants (the march runs this at every step, masked:
// no pow there); else any n.
vec3 teleport(vec3 p, const bool step_end) {
  const float n = -floor(p.z / kLatticeHeight);
  const float phi2 = kPhi * kPhi;
  const float up = n > 0.5 ? phi2 : (n < -0.5 ? 1.0 / phi2 : 1.0);
  const float down = n > 0.5 ? 1.0 / phi2 : (n < -0.5 ? phi2 : 1.0);
  const float scale = step_end ? up : pow(kPhi, 2.0 * n);
  const float inverse_scale = step_end ? down : 1.0 / scale;
  vec3 q = vec3(scale * p.x, p.y * inverse_scale, p.z + n * kLatticeHeight);
  q.z = min(max(q.z, 0.0), kLatticeHeight * 0.9999999);
  const vec2 f = floor(lattice_coordinates(q));
  const float fs = f.x, fr = f.y;
  q.x -= fs * kPhi + fr;
  q.y -= -fs + fr * kPhi;
  return q;
}

// The field's cell of a point of D, as its index (sol::QuotientField::cell_of).
int field_cell(vec3 p) {
  const vec3 unit = clamp(vec3(lattice_coordinates(p), p.z * (1.0 / kLatticeHeight)), 0.0, 1.0);
  const vec3 g = unit * vec3(float(kFieldCells), float(kFieldCells), float(kFieldLayers));
  const int i = min(int(g.x), kFieldCells - 1), j = min(int(g.y), kFieldCells - 1), k = min(int(g.z), kFieldLayers - 1);
  return (k * kFieldCells + j) * kFieldCells + i;
}

// The cell's candidate images (8 bits each), or kFieldAllImages.
uint field_candidates(int cell) { return field_words[2 * cell]; }

// How many of a cell's candidate slots (not kFieldAllImages) are filled:
// they fill from the lowest byte.
int field_candidate_count(uint word) {
  int n = 0;
  for (int s = 0; s < kFieldCandidates; ++s) n += ((word >> uint(8 * s)) & 255u) != uint(kFieldEmpty) ? 1 : 0;
  return n;
}

// The cell's reach (sol::QuotientField::reach): no image but its
// candidates is within it of any point of the cell.
float field_reach(int cell) { return uintBitsToFloat(field_words[2 * cell + 1]); }

// An image's kind (object code). A quotient world of one kind of object
// (specialisation constants): every image's code is that kind's, and is not
// read (on lavapipe each word a step reads at a per-lane index is a gather
// of 8 loads). The quotient's marches and shading read the kind only here.
const bool ONE_KIND = (HAS_BOUND_BALLS ? 1 : 0) + (HAS_EXACT_BALLS ? 1 : 0) + (HAS_TUBES ? 1 : 0) + (HAS_PLANES_Z ? 1 : 0) == 1;
const int ONLY_KIND = HAS_BOUND_BALLS ? kObjectBall : (HAS_EXACT_BALLS ? kObjectExactBall : (HAS_TUBES ? kObjectTube : kObjectPlaneZ));
int image_type(Image m) { return ONE_KIND ? ONLY_KIND : int(m.info.x); }

// The s-th of a cell's `listed` candidates (its word, or every image when
// `all`; field_candidate_count): its image index `i`, its record `m` and
// its object_clearances from q along u (hz: q.z's half exponentials). Past
// the listed ones (a cell listing none: the one masked pass of the
// marches' do-while over the candidates) `m` is the first record and no
// object answers (1e30).
vec3 candidate_clearances(uint word, bool all, int s, int listed, vec3 q, vec3 u, vec2 hz, out int i, out Image m) {
  i = all ? s : int((word >> uint(8 * s)) & 255u);
  m = images[s < listed ? i : 0];
  // Its bound record alone (Image::bound); a ball's centre's half
  // exponentials taken here: two exponentials cost lavapipe less than two
  // more words read (docs/renderer.md).
  const vec3 dc = image_clearances(image_type(m), q, u, m.bound, hz);
  return s < listed ? dc : vec3(1e30);
}

vec2 candidate_clearance(uint word, bool all, int s, int listed, vec3 q, vec3 u, vec2 hz, out int i, out Image m) {
  return candidate_clearances(word, all, s, listed, q, u, hz, i, m).xy;
}

// ---- Shadows (sol::Light::shadows; the CPU's `blocked` in libsol/src/render.cpp)

// The objects of a scene in Sol as main() copied them from the uniforms
// (relative to the eye), for the shadow march.
int g_count;
int g_types[kMaxGpuObjects];
float g_radii[kMaxGpuObjects];
vec4 g_relative[kMaxGpuObjects];
vec2 g_headings[kMaxGpuObjects];
int g_cutouts[kMaxGpuObjects];
vec2 g_half_exp_z[kMaxGpuObjects];  // balls: the centre's half exponentials (as main()'s half_exp_z)
vec4 g_eye_camera, g_eye_frac;

// Whether the geodesic from q (a hit point, in the march's coordinates)
// along `direction` meets an object within `len`: the scene marched by
// every object's own distance (exact balls within kExactShell of their
// approach by their exact distance and its clearance), passing the
// objects within 2 hit_epsilon of q (the surface it leaves) until it is
// 2 hit_epsilon away from them, and the holes of cutout planes. (Unlike
// the CPU's, whose march is the camera rays' one, balls and tubes step by
// their bound, not their clearance: in this loop, inside the light's loop
// over its geodesics, one clearance a step made shadowed scenes 10-25 %
// slower on lavapipe though the steps fell tenfold.)
bool shadow_blocked(vec3 q, vec3 direction, float len) {
  const float eps = params.limits.y;
  const int max_steps = int(params.limits.w);
  const float limit = min(len, params.limits.x);
  vec3 exact_v = vec3(0.0);
  SolEnd exact_end = SolEnd(vec3(0.0), vec3(0.0, 0.0, 1.0));
  bool exact_known = false;
  mat3 exact_J = mat3(1.0);  // the last solve's Jacobian (sol_newton)
  if (QUOTIENT) {
    const int image_count = min(params.counts.x, kMaxGpuImages);
    vec3 origin = q;
    vec2 origin_scale = vec2(exp(origin.z), exp(-origin.z));  // sol_translate's, kept with origin
    // (No plane regime: see main()'s quotient march.)
    SolRay ray = sol_ray(sol_direction_off_plane_regime(direction));
    sol_ray_integrals(ray);
    float t = 0.0, local_t = 0.0;
    int exact_i = -1;
    // The images it leaves: up to four, by index.
    ivec4 passing = ivec4(-1);
    {
      const uint word = field_candidates(field_cell(q));
      const bool all = word == kFieldAllImages;
      int held = 0;
      for (int s = 0; s < (all ? image_count : kFieldCandidates); ++s) {
        const int i = all ? s : int((word >> uint(8 * s)) & 255u);
        if (i == kFieldEmpty || held == 4) continue;
        const Image m = images[i];
        if (image_distance(image_type(m), q, m.bound) < 2.0 * eps) passing[held++] = i;
      }
    }
    for (int step = 0; step < max_steps; ++step) {
      const SolForward forward = sol_forward(ray, local_t, false);
      vec3 p = sol_translate(origin, origin_scale, forward.position);
      const bool outside = !in_domain(p);
      if (outside) {
        origin = teleport(p, true);
        ray = sol_ray_restarted(ray, local_t, forward, false);
        local_t = 0.0;
        p = origin;
      }
      const vec2 hz = half_exp(p.z);  // shared by the candidates' clearances
      if (outside) origin_scale = hz * hz;
      const int cell = field_cell(p);
      const uint word = field_candidates(cell);
      const bool all = word == kFieldAllImages;
      float clear = 1e30, nearest_hit = 1e30;
      const int listed = all ? image_count : field_candidate_count(word);
      int s = 0;
      do {  // as main()'s candidates
        int i;
        Image m;
        const vec2 dc = candidate_clearance(word, all, s, listed, p, forward.direction, hz, i, m);
        float d = dc.x;
        if (HAS_EXACT_BALLS && image_type(m) == kObjectExactBall && d < kExactShell) {
          if (exact_i != i) exact_known = false;
          exact_i = i;
          d = exact_ball_sdf(p, m.bound.xyz, m.bound.w, exact_v, exact_end, exact_known, exact_J);
        }
        bool leaving = false;
        for (int h = 0; h < 4; ++h) {
          if (passing[h] == i) {
            if (d > 2.0 * eps) passing[h] = -1;
            else leaving = true;
          }
        }
        clear = min(clear, max(d, dc.y));
        if (!leaving) nearest_hit = min(nearest_hit, d);
      } while (++s < listed);
      if (nearest_hit < eps) return true;
      float step_length = min(clear, field_reach(cell));
      if (any(greaterThanEqual(passing, ivec4(0)))) step_length = max(step_length, 2.0 * eps);
      t += step_length;
      local_t += step_length;
      if (t > limit) return false;
    }
    return false;
  }
  SolRay ray = sol_ray(direction);
  sol_ray_integrals(ray);
  uint passing = 0u;
  for (int k = 0; k < g_count; ++k) {
    if (object_distance(g_types[k], q, g_relative[k], g_headings[k], g_radii[k]) < 2.0 * eps) passing |= 1u << uint(k);
  }
  // As main()'s march, with exact balls in rounds: the exact solve after
  // the inner loop (inside it lavapipe would run the solve, masked, at
  // every step), and the exact ball's clearance for its step.
  int exact_k = -1;
  float t = 0.0;
  int step = 0;
  bool alive = true;
  int round = 0;
  do {  // (loops tested at their end: see the top of this file)
    vec3 p = vec3(0.0), u = vec3(0.0);
    float nearest = 1e30, nearest_hit = 1e30, others = 1e30, second_hit = 1e30;
    int nearest_k = 0, nearest_any = 0, second_k = 0;
    bool shell = false;
    if (step < max_steps && alive) do {
      const SolForward forward = sol_forward(ray, t);
      p = sol_translate(q, forward.position);
      u = forward.direction;
      nearest = 1e30;
      nearest_hit = 1e30;
      others = 1e30;
      second_hit = 1e30;
      nearest_k = 0;
      nearest_any = 0;
      second_k = 0;
      const vec2 hz = half_exp(p.z);  // shared by the objects
      int k = 0;
      if (g_count > 0) do {
        float d = object_distance(g_types[k], p, g_relative[k], g_headings[k], g_radii[k], hz, g_half_exp_z[k]);
        if (HAS_CUTOUT && g_cutouts[k] != 0) {
          d = max(d, cutout_gap_bound(g_cutouts[k], plane_coordinates(2, p, g_eye_camera, g_eye_frac),
                                      g_eye_camera.w * exp(p.z)));
        }
        const uint bit = 1u << uint(k);
        if ((passing & bit) != 0u && d > 2.0 * eps) passing &= ~bit;
        if (d < nearest) {
          others = nearest;
          nearest_any = k;
        } else {
          others = min(others, d);
        }
        nearest = min(nearest, d);
        if ((passing & bit) == 0u && d < nearest_hit) {
          if (HAS_EXACT_BALLS) {
            second_hit = nearest_hit;
            second_k = nearest_k;
          }
          nearest_hit = d;
          nearest_k = k;
        } else if (HAS_EXACT_BALLS && (passing & bit) == 0u && d < second_hit) {
          second_hit = d;
          second_k = k;
        }
      } while (++k < g_count);
      shell = HAS_EXACT_BALLS && g_types[nearest_k] == kObjectExactBall && nearest_hit < kExactShell;
      if (shell) break;  // finished below
      if (nearest_hit < eps) {
        if (HAS_CUTOUT && g_cutouts[nearest_k] != 0) {
          const vec2 uv = plane_coordinates(g_types[nearest_k], p, g_eye_camera, g_eye_frac);
          if (pattern_factor(g_cutouts[nearest_k], uv.x, uv.y) != 1.0) {
            passing |= 1u << uint(nearest_k);  // between the discs: go through
            t += max(nearest, 2.0 * eps);
            alive = t <= limit;
            continue;
          }
        }
        return true;
      }
      t += passing != 0u ? max(nearest, 2.0 * eps) : nearest;
      alive = t <= limit;
    } while (++step < max_steps && alive);
    if (HAS_EXACT_BALLS && shell && alive) {
      // Near an exact ball: its exact distance, and its clearance for the step.
      if (exact_k != nearest_k) exact_known = false;
      exact_k = nearest_k;
      const float exact = exact_ball_sdf(p, g_relative[nearest_k].xyz, g_radii[nearest_k], exact_v, exact_end, exact_known, exact_J);
      float exact_step = exact;
      if (exact_known && exact > eps) {
        exact_step = exact_ball_clearance(exact, length(exact_v), dot(exact_end.tangent, u), eps);
      }
      nearest = min(nearest_any == nearest_k ? others : nearest, exact_step);
      if (exact <= second_hit) {
        nearest_hit = exact;
      } else {
        nearest_hit = second_hit;
        nearest_k = second_k;
      }
      if (nearest_hit < eps) {
        bool hole = false;  // the runner-up may be a cutout plane, passed between its discs
        if (HAS_CUTOUT && g_cutouts[nearest_k] != 0) {
          const vec2 uv = plane_coordinates(g_types[nearest_k], p, g_eye_camera, g_eye_frac);
          hole = pattern_factor(g_cutouts[nearest_k], uv.x, uv.y) != 1.0;
        }
        if (!hole) return true;
        passing |= 1u << uint(nearest_k);
      }
      t += passing != 0u ? max(nearest, 2.0 * eps) : nearest;
      alive = t <= limit;
      ++step;
    }
    alive = alive && step < max_steps;
  } while (HAS_EXACT_BALLS && ++round < max_steps && alive);
  return false;
}

// The quotient (sol::lights_at with the light's images): the connections
// from q (world, in D) to light i's images of length up to d + reach, d the
// least distance to any image. Images are taken in order of their distance
// lower bound from q while that is within the least length found + reach
// (at most kMaxLightImageSolves of them), their connections solved and
// kept (the shortest SOL_FOUND_SLOTS), then those longer than the least + reach
// dropped (with 2e-3 of it for the float lengths).
int quotient_light_connections(int light, vec3 q, float reach, out vec4 kept[SOL_FOUND_SLOTS]) {
  const int first = params.light_image_first[light], count = params.light_image_count[light];
  float best = 1e30, last = -1.0;
  int last_k = -1, n = 0;
  const vec2 hq = half_exp(q.z);  // shared by the images' bounds
  for (int round = 0; round < kMaxLightImageSolves; ++round) {
    // The next image by (lower bound, index) after the last one solved.
    float lo = 1e30;
    int lo_k = -1;
    for (int k = 0; k < count; ++k) {
      const vec3 image = light_images[first + k].xyz;
      const float b = distance_lower_bound(q, image, hq, half_exp(image.z));
      const bool after = b > last || (b == last && k > last_k);
      if (after && b < lo) {
        lo = b;
        lo_k = k;
      }
    }
    if (lo_k < 0 || lo > best + reach) break;
    last = lo;
    last_k = lo_k;
    const vec3 d = light_images[first + lo_k].xyz - q;
    vec4 found[SOL_FOUND_SLOTS];
    const int paths = sol_connections(vec3(exp(-q.z) * d.x, exp(q.z) * d.y, d.z), reach, found);
    for (int j = 0; j < paths; ++j) {
      best = min(best, found[j].w);
      if (n < SOL_FOUND_SLOTS) {
        kept[n++] = found[j];
      } else {  // full: replace the longest if this one is shorter
        int longest = 0;
        for (int m = 1; m < SOL_FOUND_SLOTS; ++m) longest = kept[m].w > kept[longest].w ? m : longest;
        if (found[j].w < kept[longest].w) kept[longest] = found[j];
      }
    }
  }
  int m = 0;
  for (int j = 0; j < n; ++j) {
    if (kept[j].w <= best + reach + 2e-3 * max(1.0, best)) kept[m++] = kept[j];
  }
  return m;
}

// Planes x = c and y = c in Sol, met as roots instead of marched. Along a
// geodesic whose frame components start as (a, b, ·), the momenta conjugate
// to x and y are conserved: x' = a e^{2z}, y' = b e^{-2z} (z relative to the
// start; docs/mathematics.md). So x(t) and y(t) are monotone, such a plane
// is crossed at most once, and its crossing is the one root of x(t) - c (or
// y(t) - c). All of them are solved together, one closed-form position per
// iteration: Newton's step (the derivative is the formula above, from the
// height alone) from the latest point, taken towards the least root it
// predicts, kept inside the bracket [lo, hi] where lo is the latest point
// past no plane and hi the earliest past some (bisection where Newton leaves
// it). It ends as the march does: at a point within `eps` of a plane and
// past no other; or at the limit with none crossed (monotone: none is
// crossed before it). March sphere tracing towards a plane met obliquely
// takes many steps (the sheets preset: 11.8 on average), this a few. When it
// does not end within kPlaneRootIterations the planes are marched as before:
// by the caller's march (`solved` false), or, when every object is such a
// plane (PLANES_XY_ONLY), here, from lo, by their exact distances, within
// `max_steps` more positions. The kernel then has no march loop at all: on
// lavapipe a loop that never runs still costs: its body runs once (sheets:
// 53.8 -> 43.7 ms).
const int kPlaneRootIterations = 16;
struct PlaneRoot {
  bool solved;  // else: march the planes
  int k;        // the plane hit (-1: none within the limit)
  float t;      // its arc length
  vec3 q;       // the point there (coordinates of the march's q)
};
PlaneRoot plane_xy_roots(SolRay ray, vec3 start, int count, int types[kMaxGpuObjects], float constants[kMaxGpuObjects],
                         float limit, float eps, int max_steps, inout int steps) {
  PlaneRoot r;
  r.solved = true;
  r.k = -1;
  r.t = 1e30;
  r.q = vec3(0.0);
  // x' at q = e^{z_s} a e^{2(q.z - z_s)} = a e^{2 q.z} / e^{z_s}, y' = b e^{z_s} / e^{2 q.z}
  // (the ray starts at `start`, a column's eye, with frame components there).
  const vec3 d = ray.direction;
  const float e_start = exp(start.z);
  uint ahead_mask = 0u;  // the planes ahead of the ray, coming nearer
  float lo = 0.0, hi = limit, t = 0.0;
  bool bracketed = false;  // some plane crossed at hi
  vec3 q = start;
  const int iterations = kPlaneRootIterations + (PLANES_XY_ONLY ? max_steps : 0);
  for (int it = 0; it < iterations; ++it) {
    if (it > 0) {
      q = sol_position_forward(ray, t);
      if (HAS_ODS) q = sol_translate(start, q);
      ++steps;
    }
    const float ez = exp(q.z), ez2 = ez * ez;
    const bool marching = PLANES_XY_ONLY && it >= kPlaneRootIterations;
    float least = 1e30;  // the least size over every plane, and its plane: the march's step
    int least_k = -1;
    bool crossed = false, far_crossed = false;
    int near_k = -1;
    float near = eps, ahead = 1e30, behind = 1e30;  // Newton's least predicted root, from before and from past planes
    for (int k = 0; k < count; ++k) {
      const bool is_x = types[k] == kObjectPlaneX;
      if (!is_x && types[k] != kObjectPlaneY) continue;
      const uint bit = 1u << uint(k);
      const float speed = is_x ? d.x : d.y;
      const float gap = (is_x ? q.x : q.y) - constants[k];
      const float f = speed < 0.0 ? -gap : gap;      // rises along the ray; the crossing at f = 0
      const float size = abs(gap) * (is_x ? 1.0 / ez : ez);  // sinh of the distance to the plane
      if (PLANES_XY_ONLY && size < least) {
        least = size;
        least_k = k;
      }
      if (it == 0) {
        if (size < eps) {  // on it at the start: hit there, as the march's first step
          near = size;
          near_k = k;
        }
        if (f < 0.0 && speed != 0.0) ahead_mask |= bit;
      }
      if ((ahead_mask & bit) == 0u) continue;
      const float rate = abs(speed) * (is_x ? ez2 / e_start : e_start / ez2);
      const float root = t - f / rate;
      // Within eps of the plane, as the march's hits, and within eps of its
      // crossing in arc length by Newton's estimate (an oblique ray's point
      // within eps of the plane may lie eps/sin(angle) from it along the ray).
      const bool close = size < eps && abs(f) < rate * eps;
      if (close && size < near) {
        near = size;
        near_k = k;
      }
      if (f >= 0.0) {
        crossed = true;
        far_crossed = far_crossed || !close;
        behind = min(behind, root);
      } else {
        ahead = min(ahead, root);
      }
    }
    if (marching) {
      // Unsettled: the planes marched from lo (past none) by their exact
      // distances asinh(size), as the caller's march would.
      const float nearest = asinh(least);
      if (nearest < eps) {
        r.k = least_k;
        r.t = t;
        r.q = q;
        return r;
      }
      t += nearest;
      if (t > limit) return r;
      continue;
    }
    if (near_k >= 0 && !far_crossed) {  // within eps of a plane, past no other
      r.k = near_k;
      r.t = t;
      r.q = q;
      return r;
    }
    if (ahead_mask == 0u) return r;  // no plane ahead
    if (crossed) {
      hi = t;
      bracketed = true;
    } else {
      if (t >= limit) return r;  // none crossed within the limit
      lo = t;
    }
    float next = crossed ? behind : ahead;
    if (PLANES_XY_ONLY && it + 1 == kPlaneRootIterations) {  // the march from lo next
      t = lo;
      continue;
    }
    if (bracketed) {
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    } else {
      next = min(next, limit);  // no bracket yet: at most the limit
      if (!(next > lo)) next = 0.5 * (lo + limit);
    }
    t = next;
  }
  r.solved = PLANES_XY_ONLY;  // there: out of steps, a miss (as the march)
  return r;
}

// Colour of a hit on object k with unit normal n (frame components), plane
// coordinates uv, arc length t; q and the eye's light positions are in the
// same coordinates (camera-relative in Sol, world in the quotient). Lights
// as sol::lights_at: point lights by the coordinate difference in frame
// components at the hit and 1/(1 + r²) on the distance bound; exact point
// lights (HAS_EXACT_LIGHTS, light_color.w = 2, reach in lights[i].w) along
// each geodesic from q to the light up to the shortest + reach, each with
// 1/J (kLightExactGeodesic) or 1/(1 + L²) on its length L, or as a point
// light where none is found; with shadows, each geodesic marched to the
// light first (shadow_blocked).
vec4 shade_hit(int k, vec3 n, vec2 uv, float t, vec3 q, int eye) {
  const float ambient = params.shading.x;
  const int light_count = min(int(params.shading.z), kMaxLights);
  vec3 light = vec3(0.0);
  int i = 0;
  if (light_count > 0) do {  // (tested at its end, as the paths': see the top of this file)
    const vec4 lc = params.light_color[i];
    const vec4 lp = params.eyes[eye].lights[i];
    vec3 l = lp.xyz;
    float attenuation = 1.0;
    if (HAS_POINT_LIGHTS) {
      const vec3 diff = lp.xyz - q;
      // q⁻¹·light: the light seen from q, in frame components at q.
      const vec3 towards = vec3(exp(-q.z) * diff.x, exp(q.z) * diff.y, diff.z);
      if (HAS_EXACT_LIGHTS && (lc.w == float(kLightExactPoint) || lc.w == float(kLightExactGeodesic))) {
        vec4 found[SOL_FOUND_SLOTS];
        const int paths = QUOTIENT ? quotient_light_connections(i, q, lp.w, found) : sol_connections(towards, lp.w, found);
        int j = 0;
        if (paths > 0) do {
          // found[j]: the geodesic's direction at q and its length; its J seen
          // from q is its J seen from the light (reciprocity).
          const float cosine = max(0.0, dot(n, found[j].xyz));
          if (cosine == 0.0) continue;
          if (HAS_SHADOWS && params.light_shadows[i] != 0 && shadow_blocked(q, found[j].xyz, found[j].w)) continue;
          const float spread = lc.w == float(kLightExactGeodesic)
                                   ? max(sol_sphere_area_density(found[j].xyz, found[j].w), kMinSpreading)
                                   : 1.0 + found[j].w * found[j].w;
          light += lc.rgb * (cosine / spread);
        } while (++j < paths);
        if (paths > 0) continue;
      }
      const float r = distance_lower_bound(q, lp.xyz);
      const bool directional = lc.w == float(kLightDirectional);
      l = directional ? lp.xyz : (length(towards) > 0.0 ? normalize(towards) : vec3(0.0, 0.0, 1.0));
      attenuation = directional ? 1.0 : 1.0 / (1.0 + r * r);
    }
    light += lc.rgb * (attenuation * max(0.0, dot(n, l)));
  } while (++i < light_count);
  const vec3 surface = params.objects[k].color.rgb * pattern_factor(int(params.objects[k].plane.z), uv.x, uv.y) *
                       (ambient + (1.0 - ambient) * light);
  const float transmittance = HAS_FOG ? exp(-params.shading.y * t) : 1.0;
  return vec4(params.fog_color.rgb + (surface - params.fog_color.rgb) * transmittance, 1.0);
}

// The end of a march step whose nearest object (for a hit) is nearest_k at
// nearest_hit and whose step is `nearest`: a hit (`hit` set), a pass
// between a cutout plane's discs, or the advance. Returns whether the march
// goes on.
bool march_step_end(float nearest, float nearest_hit, int nearest_k, vec3 q, int type, vec4 eye_camera, vec4 eye_frac,
                    float hit_epsilon, float max_distance, inout uint passing, inout float t, inout int hit) {
  if (nearest_hit < hit_epsilon) {
    if (HAS_CUTOUT && params.objects[nearest_k].plane.w != 0.0) {
      const vec2 uv = plane_coordinates(type, q, eye_camera, eye_frac);  // full positions whenever the scene has cutouts
      if (pattern_factor(int(params.objects[nearest_k].plane.z), uv.x, uv.y) != 1.0) {
        passing |= 1u << uint(nearest_k);  // between the discs: go through
        t += max(nearest, 2.0 * hit_epsilon);
        return !(t > max_distance);
      }
    }
    hit = nearest_k + 1;
    return false;
  }
  t += (HAS_CUTOUT && passing != 0u) ? max(nearest, 2.0 * hit_epsilon) : nearest;
  return !(t > max_distance);
}

// The objects of eye `eye` for the shadow march (g_count and the rest).
void load_shadow_objects(int eye) {
  g_count = min(params.counts.x, kMaxGpuObjects);
  for (int k = 0; k < kMaxGpuObjects; ++k) {
    g_types[k] = int(params.objects[k].plane.x);
    g_cutouts[k] = HAS_CUTOUT && g_types[k] == kObjectPlaneZ && params.objects[k].plane.w != 0.0
                       ? int(params.objects[k].plane.z)
                       : 0;
    g_radii[k] = params.objects[k].plane.y;
    g_relative[k] = params.eyes[eye].relative[k];
    g_headings[k] = params.eyes[eye].heading[k].xy;
    g_half_exp_z[k] = HAS_BALLS ? half_exp(g_relative[k].z) : vec2(1.0);
  }
  g_eye_camera = params.eyes[eye].camera;
  g_eye_frac = params.eyes[eye].camera_frac;
}

// The shade pass: the hits the march pass listed (defer_shading), shaded
// into their pixels as the march would have (shade_hit; the pattern's
// coordinates from the hit point, as main()).
void shade_pass() {
  const int slot = queue_slot();
  if (slot >= queue.shade.w) return;
  const int at = kQueueResumeRecord * queue_capacity() + kQueueShadeRecord * slot;
  const uvec4 a = queue_records[at], b = queue_records[at + 1];
  const ivec2 pixel = unpack_pixel(b.z);
  const int eye = pixel.x >= params.counts.y ? 1 : 0;
  const vec3 q = uintBitsToFloat(a.xyz);
  const float t = uintBitsToFloat(a.w);
  const vec3 n = octahedral_decode(uintBitsToFloat(b.xy));
  const int index = int(b.w);
  int k = index;
  vec2 uv;
  if (QUOTIENT) {
    const Image m = images[index];
    const int type = image_type(m);
    k = int(m.info.z);
    uv = type >= kObjectBall ? solid_coordinates(type, q, m.geometry, m.heading.xy, m.info.y) : q.xy;
  } else {
    const int type = int(params.objects[k].plane.x);
    uv = (HAS_BALLS && type >= kObjectBall)
             ? solid_coordinates(type, q, params.eyes[eye].relative[k], params.eyes[eye].heading[k].xy,
                                 params.objects[k].plane.y)
             : plane_coordinates(type, q, params.eyes[eye].camera, params.eyes[eye].camera_frac);
    if (HAS_SHADOWS) load_shadow_objects(eye);
  }
  const vec4 color = shade_hit(k, n, uv, t, q, eye);
  imageStore(color_image, pixel, output_color(accumulate(pixel, color, params.pixel_sample.z)));
}

// The quotient camera march's positions (sol_forward_zeta where the ray's
// μ is at least kZetaLeastMu, `by_zeta`, else sol_forward), its set-up
// and its restarts. With the resume pass (DEFER_SMALL_MU) each pass holds
// one of the two alone (constants); in one dispatch both are there and
// each ray takes its own.
const bool QUOTIENT_ZETA_ONLY = DEFER_SMALL_MU && PASS == kPassMarch;
const bool QUOTIENT_CARLSON_ONLY = DEFER_SMALL_MU && PASS == kPassResume;

void quotient_ray_prepared(inout SolRay g) {
  if (!QUOTIENT_CARLSON_ONLY) sol_ray_zeta(g);
  if (!QUOTIENT_ZETA_ONLY) sol_ray_integrals(g);
}

SolForward quotient_forward(SolRay g, float t, bool by_zeta) {
  if (QUOTIENT_ZETA_ONLY) return sol_forward_zeta(g, t);
  if (QUOTIENT_CARLSON_ONLY) return sol_forward(g, t, false);
  return by_zeta ? sol_forward_zeta(g, t) : sol_forward(g, t, false);
}

SolRay quotient_ray_restarted(SolRay g, float t0, SolForward f, bool by_zeta) {
  if (QUOTIENT_ZETA_ONLY) return sol_ray_restarted_zeta(g, f);
  if (QUOTIENT_CARLSON_ONLY) return sol_ray_restarted(g, t0, f, false);
  return by_zeta ? sol_ray_restarted_zeta(g, f) : sol_ray_restarted(g, t0, f, false);
}

void main() {
  if (PASS == kPassShade) {
    shade_pass();
    return;
  }
  // Uniform values copied to locals once: lavapipe does not hoist uniform loads out of loops.
  // This dispatch's tile of the image (the whole image unless rendered in tiles).
  const ivec4 tile = params.tile;
  // The resume pass: the ray of a record of the march pass (defer_exact),
  // which goes on from where that pass left it.
  uvec4 resumed = uvec4(0u);
  ivec2 pixel;
  if (PASS == kPassResume) {
    const int slot = queue_slot();
    if (slot >= queue.resume.w) return;
    resumed = queue_records[kQueueResumeRecord * slot];
    pixel = unpack_pixel(resumed.x);
  } else {
    const ivec2 invocation = ivec2(gl_WorkGroupID.xy) * kGroupSize + group_pixel(int(gl_LocalInvocationIndex));
    if (any(greaterThanEqual(invocation, tile.zw))) return;
    pixel = tile.xy + invocation;
  }
  const int width = params.counts.y, height = params.counts.z;
  if (pixel.x >= width * params.counts.w || pixel.y >= height) return;
  const int eye = pixel.x >= width ? 1 : 0;
  const ivec2 local = ivec2(pixel.x - eye * width, pixel.y);
  const vec4 eye_right = params.eyes[eye].right, eye_up = params.eyes[eye].up, eye_forward = params.eyes[eye].forward;
  const vec4 eye_camera = params.eyes[eye].camera, eye_frac = params.eyes[eye].camera_frac;
  const int count = min(params.counts.x, kMaxGpuObjects);
  const bool heights_only = HEIGHTS_ONLY;
  int types[kMaxGpuObjects];
  float constants[kMaxGpuObjects], radii[kMaxGpuObjects];
  vec4 relative[kMaxGpuObjects];
  vec2 headings[kMaxGpuObjects];
  int cutouts[kMaxGpuObjects];  // cutout planes z = c: their pattern code; else kPatternNone
  vec2 half_exp_z[kMaxGpuObjects];  // balls: the centre's half exponentials, for object_distance and object_clearance
  for (int k = 0; k < kMaxGpuObjects; ++k) {
    types[k] = int(params.objects[k].plane.x);
    cutouts[k] = HAS_CUTOUT && types[k] == kObjectPlaneZ && params.objects[k].plane.w != 0.0 ? int(params.objects[k].plane.z) : 0;
    radii[k] = params.objects[k].plane.y;
    relative[k] = params.eyes[eye].relative[k];
    headings[k] = params.eyes[eye].heading[k].xy;
    constants[k] = relative[k].x;
    half_exp_z[k] = HAS_BALLS ? half_exp(relative[k].z) : vec2(1.0);
  }
  if (HAS_SHADOWS && !DEFER_SHADING) load_shadow_objects(eye);
  const float max_distance = params.limits.x, hit_epsilon = params.limits.y;
  const int max_steps = int(params.limits.w);
  const float rk4_step = eye_forward.w;

  // The camera convention of docs/conventions.md (or the eye's off-axis window), per eye.
  const vec4 window = params.eyes[eye].window;
  // The point of the pixel this dispatch samples (the centre without anti-aliasing).
  const vec4 sample_at = params.pixel_sample;
  const bool write_aovs = WRITE_AOVS && sample_at.w != 0.0;
  const float sx = window.x + (window.y - window.x) * (float(local.x) + sample_at.x) / float(width);
  const float sy = window.z + (window.w - window.z) * (float(local.y) + sample_at.y) / float(height);
  vec3 direction = normalize(sx * eye_right.xyz + sy * eye_up.xyz + eye_forward.xyz);
  // The other projections (sol::camera_ray): equirectangular and fisheye.
  const vec4 projection = params.eyes[eye].projection;
  const vec2 at = vec2(float(local.x) + sample_at.x, float(local.y) + sample_at.y);
  if (HAS_PROJECTIONS && projection.x == float(kProjectionEquirectangular)) {
    const float longitude = (at.x / float(width) - 0.5) * 6.28318530717958648;
    const float latitude = (0.5 - at.y / float(height)) * 3.14159265358979324;
    direction = normalize(cos(latitude) * sin(longitude) * eye_right.xyz + sin(latitude) * eye_up.xyz +
                          cos(latitude) * cos(longitude) * eye_forward.xyz);
  } else if (HAS_PROJECTIONS && projection.x == float(kProjectionFisheye)) {
    const vec2 p = vec2(at.x - 0.5 * float(width), 0.5 * float(height) - at.y) / (0.5 * float(min(width, height)));
    const float r = length(p);
    if (r > 1.0) {  // outside the image circle: no ray
      imageStore(color_image, pixel, output_color(accumulate(pixel, vec4(0.0, 0.0, 0.0, 1.0), sample_at.z)));
      if (write_aovs) {
        imageStore(aov_hit, pixel, vec4(0.0));
        imageStore(aov_point, pixel, vec4(0.0));
      }
      return;
    }
    const float theta = r * projection.y;
    direction = r > 0.0 ? normalize(sin(theta) * (p.x / r * eye_right.xyz + p.y / r * eye_up.xyz) + cos(theta) * eye_forward.xyz)
                        : eye_forward.xyz;
  }
  // Where the ray starts relative to the eye's camera: there, except for an
  // omnidirectional stereo eye, whose column has its own eye (sol::column_eye:
  // the start `offset`, the direction transported there).
  vec3 start = vec3(0.0);
  if (HAS_ODS) {
    const Column column = columns[eye * width + local.x];
    start = column.offset.xyz;
    direction = normalize(mat3(column.transport[0].xyz, column.transport[1].xyz, column.transport[2].xyz) * direction);
  }

  if (QUOTIENT) {
    // The march of libsol's march_quotient: rays in D, teleported back when a
    // step ends outside. Each step is the least clearance along the ray
    // (object_clearance) of the cell's candidate images (sol::QuotientField:
    // every image that can be nearer than kFieldNear there, or else the
    // nearest), capped at the cell's reach (field_reach: every other image
    // is farther; one read instead of every image's bound), and the
    // candidate that comes within hit_epsilon is the object hit. Steps stay
    // within the world's longest step (sol::quotient_max_step), the reach of
    // the listed images, which the reaches are capped at.
    const int image_count = min(params.counts.x, kMaxGpuImages);
    vec3 origin = eye_camera.xyz;  // the eye, already in D (from double)
    if (HAS_ODS) {  // the column's eye, teleported into D
      origin = sol_translate(origin, start);
      if (!in_domain(origin)) origin = teleport(origin, false);
    }
    vec2 origin_scale = vec2(exp(origin.z), exp(-origin.z));  // sol_translate's, kept with origin
    // The ray's direction off the plane regime (sol_direction_off_plane_regime,
    // a change far below float rounding), so that no step evaluates that
    // regime's position for every ray.
    SolRay qray = sol_ray(sol_direction_off_plane_regime(direction));
    // Its positions by the zeta function, or by Carlson's integrals where μ
    // is small (quotient_forward); those rays left to the resume pass.
    const bool by_zeta = qray.mu >= kZetaLeastMu;
    if (DEFER_SMALL_MU && PASS == kPassMarch && !by_zeta) {
      defer_exact(pixel, 0.0, 0u, 0);  // this ray in the resume pass, by Carlson's integrals
      return;
    }
    quotient_ray_prepared(qray);
    float t = 0.0, local_t = 0.0;
    int hit_image = -1, steps = 0;
    vec3 q = origin;
    int exact_i = -1;           // the exact ball image whose geodesic from the centre exact_v holds
    vec3 exact_v = vec3(0.0);
    SolEnd exact_end = SolEnd(vec3(0.0), vec3(0.0, 0.0, 1.0));
    bool exact_known = false;  // exact_v, exact_end: a solution to start from
    mat3 exact_J = mat3(1.0);  // the last solve's Jacobian (sol_newton)
    // Over-relaxation (march_quotient's): `proposal` is the step from q, the
    // last point the march moved to, and `covered` the part of it q's own
    // bounds clear; a longer proposal is kept where the clearance back from
    // its end e covers the rest, else the march steps `covered` from q.
    float proposal = 0.0, covered = 0.0;
    for (int step = 0; step < max_steps; ++step) {
      const SolForward forward = quotient_forward(qray, local_t + proposal, by_zeta);
      vec3 e = sol_translate(origin, origin_scale, forward.position);
      const bool outside = !in_domain(e);
      if (outside) e = teleport(e, true);
      const int cell = field_cell(e);
      steps = step + 1;
      const uint word = field_candidates(cell);
      const bool all = word == kFieldAllImages;
      const vec2 hz = half_exp(e.z);  // shared by the candidates' clearances
      float nearest = 1e30;
      int nearest_i = -1;
      float second = 1e30;  // the least distance but the nearest's, and its image
      int second_i = -1;
      // The clearances (object_clearances) of the nearest and the least of
      // the others' ahead, and the least back.
      float clear_nearest = 1e30, clear_rest = 1e30, back = 1e30;
      // (A do-while, tested at its end: see the top of this file and
      // candidate_clearances.)
      const int listed = all ? image_count : field_candidate_count(word);
      int s = 0;
      do {
        int i;
        Image m;
        const vec3 dc = candidate_clearances(word, all, s, listed, e, forward.direction, hz, i, m);
        const float d = dc.x;
        back = min(back, dc.z);
        if (d < nearest) {
          second = nearest;
          second_i = nearest_i;
          nearest = d;
          nearest_i = i;
          clear_rest = min(clear_rest, clear_nearest);
          clear_nearest = dc.y;
        } else {
          clear_rest = min(clear_rest, dc.y);
          if (d < second) {
            second = d;
            second_i = i;
          }
        }
      } while (++s < listed);
      if (HAS_EXACT_BALLS && nearest_i >= 0 && image_type(images[nearest_i]) == kObjectExactBall && nearest < kExactShell) {
        // Near an exact ball's image: its exact distance (as in Sol).
        if (exact_i != nearest_i) exact_known = false;
        exact_i = nearest_i;
        const float exact = exact_ball_sdf(e, images[nearest_i].bound.xyz, images[nearest_i].bound.w, exact_v, exact_end, exact_known, exact_J);
        nearest_i = exact <= second ? nearest_i : second_i;
        nearest = min(exact, second);
        clear_nearest = max(clear_nearest, exact);
      }
      const float reach = field_reach(cell);
      if (proposal > covered && covered + min(back, reach) < proposal) {
        proposal = covered;  // not covered: the plain step instead
        continue;
      }
      // The march moves to e. The same geodesic goes on from a teleported
      // point, restarted from what quotient_forward found there
      // (quotient_ray_restarted).
      t += proposal;
      if (outside) {
        origin = e;
        origin_scale = hz * hz;  // e^{±z} of e
        qray = quotient_ray_restarted(qray, local_t + proposal, forward, by_zeta);
        local_t = 0.0;
      } else {
        local_t += proposal;
      }
      q = e;
      if (nearest < hit_epsilon) {
        hit_image = nearest_i;
        break;
      }
      const float clear = min(clear_nearest, clear_rest);
      const float step_length = min(clear, reach);
      if (t + step_length > max_distance) break;
      covered = step_length;
      proposal = reach < clear ? min(max(step_length, min(kQuotientOverRelax * step_length, kQuotientMaxStep)), max_distance - t)
                               : step_length;
    }
    vec4 color = vec4(0.0, 0.0, 0.0, 1.0);
    vec4 hit_aov = vec4(0.0, 0.0, float(steps), 0.0);
    vec4 point_aov = vec4(0.0);
    if (hit_image >= 0) {
      const vec4 geom = images[hit_image].geometry, info = images[hit_image].info;
      const vec2 heading = images[hit_image].heading.xy;
      const int k = int(info.z), type = image_type(images[hit_image]);
      // Planes face the side of the segment's origin (the ray's side); the
      // bounds of balls and tubes are left-invariant, so their gradients
      // along the frame are taken in world coordinates.
      const vec3 n = HAS_EXACT_BALLS && type == kObjectExactBall && exact_i == hit_image
                         ? exact_ball_normal(exact_end)
                         : plane_normal(type, q, geom.x, geom, heading, info.y, origin);
      // Planes z = c: their own coordinates are (x, y); balls, tubes: the image's own.
      const vec2 uv = type >= kObjectBall ? solid_coordinates(type, q, geom, heading, info.y) : q.xy;
      if (DEFER_SHADING) {
        defer_shading(pixel, q, t, n, hit_image);
      } else {
        color = shade_hit(k, n, uv, t, q, eye);
      }
      hit_aov.x = float(k + 1);
      hit_aov.y = t;
      point_aov = vec4(q, 0.0);
    }
    // (A hit's colour comes from the shade pass.)
    if (!DEFER_SHADING || hit_image < 0) imageStore(color_image, pixel, output_color(accumulate(pixel, color, sample_at.z)));
    if (write_aovs) {
      imageStore(aov_hit, pixel, hit_aov);
      imageStore(aov_point, pixel, point_aov);
    }
    return;
  }

  SolRay ray;
  bool zeta_round = false;  // this round's positions by the zeta function (SOL_ZETA)
  if (INTEGRATOR == 0) {
    ray = sol_ray(direction);
    zeta_round = SOL_ZETA && ray.mu >= kZetaLeastMu;
    if (SOL_ZETA_ONLY && !zeta_round) {
      defer_exact(pixel, 0.0, 0u, 0);  // this ray in the resume pass, by Carlson's integrals
      return;
    }
    if (!heights_only || HAS_CUTOUT) sol_ray_integrals(ray);
    if (SOL_ZETA) sol_ray_zeta(ray);
  }
  vec3 rk_p = vec3(0.0), rk_u = direction;
  float rk_t = 0.0;

  int hit = 0, steps = 0;
  uint passing = resumed.z;  // (the resume pass: the march pass's state)
  int exact_k = -1;           // the exact ball whose geodesic from the centre exact_v holds
  vec3 exact_v = vec3(0.0);
  SolEnd exact_end = SolEnd(vec3(0.0), vec3(0.0, 0.0, 1.0));
  bool exact_known = false;  // exact_v, exact_end: a solution to start from
  mat3 exact_J = mat3(1.0);  // the last solve's Jacobian (sol_newton)
  float t = uintBitsToFloat(resumed.y);
  vec3 q = vec3(0.0);
  // Exact culling for planes z = c (as the CPU reference): a ray whose whole
  // z-range misses every plane by more than the hit epsilon never hits.
  bool reachable = true;
  if (HEIGHTS_ONLY && INTEGRATOR == 0) {
    vec2 range = sol_height_range(ray) + start.z + vec2(-hit_epsilon, hit_epsilon);
    reachable = false;
    for (int k = 0; k < count; ++k) reachable = reachable || (constants[k] >= range.x && constants[k] <= range.y);
  }
  // Planes x = c, y = c: their first crossing solved (plane_xy_roots); the
  // march then takes the other objects up to it, or is not needed.
  PlaneRoot xy;
  xy.solved = false;
  xy.k = -1;
  int root_steps = 0;
  if (HAS_PLANES_XY && INTEGRATOR == 0) {
    xy = plane_xy_roots(ray, start, count, types, constants, max_distance, hit_epsilon, max_steps, root_steps);
    if (PLANES_XY_ONLY) {
      steps = root_steps;
      if (xy.k >= 0) {
        hit = xy.k + 1;
        t = xy.t;
        q = xy.q;
      }
    }
  }
  // The march. With exact balls it runs in rounds: the inner loop marches
  // by the objects' distances (exact balls by their bound, object_distance)
  // until the ray comes within kExactShell of an exact
  // ball; that step is finished after the inner loop by the exact distance
  // (exact_ball_sdf), and the next round goes on. lavapipe executes the body
  // of every if, and of every loop at least once, for all its lanes, masked,
  // whichever way they go: inside the loop the exact solve (a Newton loop
  // around the closed form) cost every step of every ray; here once a round.
  bool alive = reachable && !PLANES_XY_ONLY;
  int step = int(resumed.w);
  // One step's findings. With exact balls, the runners-up too: the least
  // distance to the other objects (`others`, any object: for the step) and
  // the next candidate hit (`second_hit`, `second_k`), for when the nearest
  // is an exact ball.
  float nearest = 1e30, nearest_hit = 1e30, others = 1e30, second_hit = 1e30;
  int nearest_k = 0, nearest_any = 0, second_k = 0;
  bool shell = false;  // the step's nearest is an exact ball within kExactShell: finished exactly
  vec3 u = vec3(0.0);  // the ray's tangent at q (frame components), for the clearances
  // (Without exact balls one round, a loop the compiler unrolls; with
  // PLANES_XY_ONLY none: the roots did all, and a loop whose condition is
  // not a constant would run its body once.)
  // (The march pass of a deferred world stops at the first exact ball's
  // shell: one round, its exact block left to the resume pass.)
  // (Loops tested at their end: see the top of this file.)
  const bool rounds = HAS_EXACT_BALLS && !(DEFER_EXACT && PASS == kPassMarch);
  int round = 0;
  if (!PLANES_XY_ONLY) do {
    if (step < max_steps && alive) do {
      if (INTEGRATOR == 0) {
        // Cutout planes need the full position for their gap bounds.
        if (HAS_BALLS) {
          const SolForward forward = SOL_ZETA_ONLY ? sol_forward_zeta(ray, t)
                                     : (SOL_ZETA && zeta_round ? sol_forward_zeta(ray, t) : sol_forward(ray, t));
          q = forward.position;
          u = forward.direction;
        } else {
          q = (heights_only && !HAS_CUTOUT) ? vec3(0.0, 0.0, sol_height(ray, t)) : sol_position_forward(ray, t);
        }
      } else {
        rk4_advance(rk_p, rk_u, t - rk_t, rk4_step);
        rk_t = t;
        q = rk_p;
        u = rk_u;
      }
      if (HAS_ODS) q = sol_translate(start, q);  // from the column's eye
      nearest = 1e30;
      nearest_hit = 1e30;
      nearest_k = 0;
      others = 1e30;
      second_hit = 1e30;
      nearest_any = 0;
      second_k = 0;
      const vec2 hz = HEIGHTS_ONLY ? vec2(1.0) : half_exp(q.z);  // shared by the objects
      int k = 0;
      if (count > 0) do {
        float d = HEIGHTS_ONLY ? abs(q.z - constants[k])
                               : object_distance(types[k], q, relative[k], headings[k], radii[k], hz, half_exp_z[k]);
        if (HAS_PLANES_XY && xy.solved && (types[k] == kObjectPlaneX || types[k] == kObjectPlaneY)) {
          d = k == xy.k ? max(xy.t - t, 0.0) : 1e30;  // solved: the arc length left to its crossing
        }
        if (HAS_CUTOUT && cutouts[k] != 0) {
          d = max(d, cutout_gap_bound(cutouts[k], plane_coordinates(2, q, eye_camera, eye_frac), eye_camera.w * exp(q.z)));
        }
        // Cutout planes being passed through (between their discs) are not hits
        // until the ray is 2 hit_epsilon away again (as the CPU reference).
        const uint bit = 1u << uint(k);
        if (HAS_CUTOUT && (passing & bit) != 0u && d > 2.0 * hit_epsilon) passing &= ~bit;
        if (d < nearest) {
          others = nearest;
          nearest_any = k;
        } else {
          others = min(others, d);
        }
        nearest = min(nearest, d);
        if ((!HAS_CUTOUT || (passing & bit) == 0u) && d < nearest_hit) {
          if (HAS_EXACT_BALLS) {
            second_hit = nearest_hit;
            second_k = nearest_k;
          }
          nearest_hit = d;
          nearest_k = k;
        } else if (HAS_EXACT_BALLS && (!HAS_CUTOUT || (passing & bit) == 0u) && d < second_hit) {
          second_hit = d;
          second_k = k;
        }
      } while (++k < count);
      // The nearest object, where it is a ball or a tube, lets the step be
      // its clearance along the ray (object_clearance) up to the others'
      // least distance (as the CPU's march_cover: one clearance a step).
      if (HAS_BALLS && types[nearest_any] >= kObjectBall) {
        nearest = min(others, object_clearance(types[nearest_any], q, u, relative[nearest_any], headings[nearest_any],
                                               radii[nearest_any], hz, half_exp_z[nearest_any]).y);
      }
      shell = HAS_EXACT_BALLS && types[nearest_k] == kObjectExactBall && nearest_hit < kExactShell;
      if (shell) break;  // finished below
      steps = root_steps + step + 1;
      alive = march_step_end(nearest, nearest_hit, nearest_k, q, types[nearest_k], eye_camera, eye_frac, hit_epsilon,
                             max_distance, passing, t, hit);
    } while (++step < max_steps && alive);
    if (DEFER_EXACT && PASS == kPassMarch) {
      if (shell && alive) {  // the rest of this ray in the resume pass
        defer_exact(pixel, t, passing, step);
        return;
      }
    } else if (SOL_ZETA && zeta_round && shell && alive) {
      zeta_round = false;  // this step again, by Carlson's integrals (as the resume pass)
      shell = false;
    } else if (HAS_EXACT_BALLS && shell && alive) {
      // Near an exact ball: its exact distance (steps, and hits on the true
      // sphere), against the least distance to every other object.
      if (exact_k != nearest_k) exact_known = false;
      exact_k = nearest_k;
      const float exact =
          exact_ball_sdf(q, relative[nearest_k].xyz, radii[nearest_k], exact_v, exact_end, exact_known, exact_J);
      // The step: beyond the exact distance by the ball's clearance along
      // the ray (its rate from the sphere's normal, the gradient of d).
      float exact_step = exact;
      if (exact_known && exact > hit_epsilon) {
        const float slope = dot(exact_end.tangent, u);
        exact_step = exact_ball_clearance(exact, length(exact_v), slope, hit_epsilon);
      }
      nearest = min(nearest_any == nearest_k ? others : nearest, exact_step);
      if (exact <= second_hit) {
        nearest_hit = exact;
      } else {
        nearest_hit = second_hit;
        nearest_k = second_k;
      }
      steps = root_steps + step + 1;
      alive = march_step_end(nearest, nearest_hit, nearest_k, q, types[nearest_k], eye_camera, eye_frac, hit_epsilon,
                             max_distance, passing, t, hit);
      shell = false;
      ++step;
    }
    alive = alive && step < max_steps;
  } while (rounds && ++round < max_steps && alive);

  vec4 color = vec4(0.0, 0.0, 0.0, 1.0);
  vec4 hit_aov = vec4(float(hit), 0.0, float(steps), 0.0);
  vec4 point_aov = vec4(0.0);
  if (hit != 0) {
    if (INTEGRATOR == 0 && heights_only && !HAS_CUTOUT) {
      sol_ray_integrals(ray);
      q = sol_position_forward(ray, t);
      if (HAS_ODS) q = sol_translate(start, q);
    }
    const int k = hit - 1;
    const int type = types[k];
    const vec3 n = HAS_EXACT_BALLS && type == kObjectExactBall && exact_k == k
                       ? exact_ball_normal(exact_end)
                       : plane_normal(type, q, constants[k], relative[k], headings[k], radii[k], start);
    // World coordinates: camera * q = (x_c + e^{z_c} q.x, y_c + e^{-z_c} q.y, z_c + q.z);
    // the pattern takes the camera position modulo 2 (exact, from double).
    const vec3 scaled = vec3(eye_camera.w * q.x, eye_frac.w * q.y, q.z);
    const vec2 uv = (HAS_BALLS && type >= kObjectBall) ? solid_coordinates(type, q, relative[k], headings[k], radii[k])
                                             : plane_coordinates(type, q, eye_camera, eye_frac);
    if (DEFER_SHADING) {
      defer_shading(pixel, q, t, n, k);
    } else {
      color = shade_hit(k, n, uv, t, q, eye);
    }
    hit_aov.y = t;
    point_aov = vec4(eye_camera.xyz + scaled, 0.0);
  }
  // (A hit's colour comes from the shade pass.)
  if (!DEFER_SHADING || hit == 0) imageStore(color_image, pixel, output_color(accumulate(pixel, color, sample_at.z)));
  if (write_aovs) {
    imageStore(aov_hit, pixel, hit_aov);
    imageStore(aov_point, pixel, point_aov);
  }
}
