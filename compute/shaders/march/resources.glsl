// The march kernel's resources: its workgroup, its specialisation constants
// (what a world uses is compiled in, the rest folded away) and the
// constants derived from them, and its bindings. The numbers are those of
// sol/vk/march_interface.h, which the host (compute/src/march.cpp) shares.
// Included first by every entry file of the kernel (march.comp).
#ifndef SOL_MARCH_RESOURCES_GLSL
#define SOL_MARCH_RESOURCES_GLSL

// Bindings, specialisation-constant ids, limits, codes and the uniform
// layout: sol/vk/march_interface.h, shared with the host (compute/src/march.cpp).
layout(local_size_x = kGroupSize, local_size_y = kGroupSize, local_size_z = 1) in;
layout(constant_id = kSpecIntegrator) const int INTEGRATOR = 0;
// The deferred passes (sol/vk/march_interface.h, docs/renderer.md): which
// pass this pipeline runs.
layout(constant_id = kSpecPass) const int PASS = kPassMarch;
// What the world uses (sol/march_features.h), each a boolean
// specialisation constant, not a uniform: lavapipe evaluates both sides of
// every branch, so only a compile-time branch saves the other side's cost.
// Each is also `feature_<member>`, the name the kinds' list
// (sol/object_kinds.h) gives it. The host sets them all.
#define SOL_FEATURE_CONSTANT(member, constant, id) \
  layout(constant_id = id) const bool constant = false; \
  const bool feature_##member = constant;
SOL_MARCH_FEATURES(SOL_FEATURE_CONSTANT)
#undef SOL_FEATURE_CONSTANT
// The variant's flags (SOL_KERNEL_VARIANT_FLAGS): the outputs, the eyes'
// projections and ODS columns, what the march pass leaves to the others.
#define SOL_VARIANT_CONSTANT(member, constant, id) layout(constant_id = id) const bool constant = false;
SOL_KERNEL_VARIANT_FLAGS(SOL_VARIANT_CONSTANT)
#undef SOL_VARIANT_CONSTANT
// The quotient's lattice (SOL_LATTICE_CONSTANTS; march/quotient.glsl).
#define SOL_LATTICE_CONSTANT(constant, id) layout(constant_id = id) const float constant = 1.0;
SOL_LATTICE_CONSTANTS(SOL_LATTICE_CONSTANT)
#undef SOL_LATTICE_CONSTANT
// Every object a plane x = c or y = c: their crossing solved
// (plane_xy_roots) is the whole march. (The roots need the closed form:
// with RK4 such a world is marched.)
const bool PLANES_XY_ONLY = PLANES_XY_ONLY_WORLD && INTEGRATOR == 0;
// Exact point lights with a reach (the longer connections): only they look
// for the partners of connections near a fold (sol_connections), code that
// costs the kernel even where it never runs.
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

layout(std430, set = 0, binding = kBindingParams) readonly buffer ParamsBlock {
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
// (Read too: a later sample adds its marches that ran out of steps to w.)
layout(set = 0, binding = kBindingHit, rgba32f) uniform image2D aov_hit;      // object, distance, steps, out of steps
layout(set = 0, binding = kBindingPoint, rgba32f) uniform writeonly image2D aov_point;  // Px, Py, Pz, 0
// (The guides' albedo and emission read too: each sample joins their mean.)
layout(set = 0, binding = kBindingAlbedo, rgba32f) uniform image2D aov_albedo;  // R, G, B, 0
layout(set = 0, binding = kBindingEmission, rgba32f) uniform image2D aov_emission;  // R, G, B, the light moment
layout(set = 0, binding = kBindingNormal, rgba32f) uniform writeonly image2D aov_normal;  // frame components, 0
// The scene objects' appearance and kind (Object records, one per object).
layout(std430, set = 0, binding = kBindingObjects) readonly buffer SceneObjects {
  Object scene_objects[];
};
// The objects' image textures, one after another (Object::texture; a
// single texel where no object has one).
layout(std430, set = 0, binding = kBindingTextures) readonly buffer Textures {
  vec4 texels[];
};

// A crowd (CROWD): its tree of bounds and its objects in leaf order, in
// world coordinates (march/crowd.glsl).
layout(std430, set = 0, binding = kBindingCrowdNodes) readonly buffer CrowdNodes {
  CrowdNode crowd_nodes[];
};
layout(std430, set = 0, binding = kBindingCrowdItems) readonly buffer CrowdItems {
  CrowdItem crowd_items[];
};

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

// What the frame's rays counted (Stats; report_out_of_steps).
layout(std430, set = 0, binding = kBindingStats) buffer FrameStats {
  Stats stats;
};

// The marches of this invocation's ray (and its bounces, paths and shadow
// rays) that stopped at max_steps before they met an object or reached
// their limit (march_sol, march_quotient): counted into Stats and the
// pixel's AOV (report_out_of_steps), never a silent miss alone.
int g_out_of_steps = 0;

#endif  // SOL_MARCH_RESOURCES_GLSL
