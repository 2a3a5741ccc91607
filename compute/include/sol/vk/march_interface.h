// The interface between the march kernel (march.comp) and its host
// (compute/src/march.cpp), written once: binding numbers, specialisation-
// constant ids, limits, and the layout of the parameters' block and of the
// quotient's image buffer. Valid GLSL and C++: march.comp includes it as it
// is; in C++ it declares the same names in namespace sol::vk::kernel, with
// vec4 = glm::vec4 (std140 and std430 lay out arrays of vec4 without
// padding, like C++; the static_asserts below hold the offsets). The
// numbers shared with libsol (codes, tables, the lattice) come from
// sol/kernel_constants.h. The shaders find it as "sol/vk/march_interface.h"
// (cmake: compute/include is on their include path).
#ifndef SOL_MARCH_INTERFACE_H
#define SOL_MARCH_INTERFACE_H

#include "sol/kernel_constants.h"
#include "sol/march_features.h"

// (kListedObjects of sol/kernel_constants.h, named so in both languages:
// in C++ sol::kListedObjects, libsol's size_t, is in scope too.)
#ifdef __cplusplus
#define SOL_LISTED_OBJECTS sol::kernel::kListedObjects
#else
#define SOL_LISTED_OBJECTS kListedObjects
#endif

#ifdef __cplusplus
#include <cstddef>
#include <glm/vec4.hpp>
namespace sol::vk::kernel {
using namespace sol::kernel;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
#endif

// ---- Descriptor bindings (set 0)
SOL_CONSTANT(int, kBindingParams, 0);       ///< storage buffer (read-only): Params
SOL_CONSTANT(int, kBindingColor, 1);        ///< storage image: linear RGBA (or sRGB-encoded UNORM bytes)
SOL_CONSTANT(int, kBindingHit, 2);          ///< storage image: object, distance, steps, 0 (AOVs)
SOL_CONSTANT(int, kBindingPoint, 3);        ///< storage image: the hit point Px, Py, Pz, 0 (AOVs)
SOL_CONSTANT(int, kBindingImages, 4);       ///< storage buffer: the quotient's Image records
// (Binding 5 held a table of d(0, ·) for exact balls, no longer read.)
SOL_CONSTANT(int, kBindingSeeds, 6);        ///< storage buffer: sol::ConnectionTable::seeds
SOL_CONSTANT(int, kBindingField, 7);        ///< storage buffer: sol::QuotientField::words
SOL_CONSTANT(int, kBindingColumns, 8);      ///< storage buffer: the ODS eyes' Column records
SOL_CONSTANT(int, kBindingLightImages, 9);  ///< storage buffer: the quotient's light images (vec4, xyz world)
SOL_CONSTANT(int, kBindingQueue, 10);       ///< storage buffer: the deferred passes' lists (QueueHeader, then records)
SOL_CONSTANT(int, kBindingStats, 11);       ///< storage buffer: Stats, what the frame's rays counted
SOL_CONSTANT(int, kBindingObjects, 12);     ///< storage buffer (read-only): the scene objects' Object records
SOL_CONSTANT(int, kBindingCrowdNodes, 13);  ///< storage buffer (read-only): a crowd's tree of bounds (CrowdNode)
SOL_CONSTANT(int, kBindingCrowdItems, 14);  ///< storage buffer (read-only): a crowd's objects in leaf order (CrowdItem)
SOL_CONSTANT(int, kBindingParts, 15);       ///< storage buffer (read-only): the composites' parts (Part)
SOL_CONSTANT(int, kBindingAlbedo, 16);      ///< storage image: the hits' albedo R, G, B, 0, the samples' mean (the denoiser's guide)
SOL_CONSTANT(int, kBindingNormal, 17);      ///< storage image: the hit's normal, frame components, 0 (AOVs, the denoiser's guide)
SOL_CONSTANT(int, kBindingTextures, 18);    ///< storage buffer (read-only): the objects' image textures' texels (vec4, rgb linear)
SOL_CONSTANT(int, kBindingEmission, 19);    ///< storage image: what the hits emit towards the eye R, G, B and the light moment (the squared luminance of the colour less the emission), the samples' means (the denoiser's guides)
/// The number of bindings (the last one's, plus one).
SOL_CONSTANT(int, kBindingCount, 20);

// ---- Specialisation constants: what a scene uses is compiled in, the rest
// folded away. The world's features are sol/march_features.h (their ids
// there); these choose the kernel's variant per frame (its outputs, its
// eyes, its passes).
SOL_CONSTANT(int, kSpecIntegrator, 0);      ///< int: 0 the closed form, 1 RK4
SOL_CONSTANT(int, kSpecPass, 18);           ///< int: which pass this pipeline runs (kPass*)
/// The variant's flags, each X(member of the host's KernelVariant, the
/// kernel's boolean constant, its id), as SOL_MARCH_FEATURES.
// clang-format off
#define SOL_KERNEL_VARIANT_FLAGS(X)                                                                     \
  X(aovs,          WRITE_AOVS,      7)  /* write the AOV images (bindings 2, 3); off for presenters */      \
  X(projections,   HAS_PROJECTIONS, 13) /* an eye's projection is equirectangular or fisheye */             \
  X(ods,           HAS_ODS,         14) /* omnidirectional stereo eyes (binding 8) */                       \
  X(defer_shading, DEFER_SHADING,   19) /* hits shaded by the shade pass (exact lights) */                  \
  X(resume,        RESUME_WORLD,    20) /* the march pass leaves rays to the resume pass (exact balls in Sol, small μ in the quotient) */ \
  X(inside,        HAS_INSIDE,      45) /* an eye inside a solid: solids seen from inside */ \
  X(path,          PATH_TRACING,    47) /* light transport by paths (march/paths.glsl), else direct light */ \
  X(from_eye, FROM_EYE_WORLD, 48) /* the camera ray the first segment of a path or of radiance's rays: one pipeline, one march */ \
  X(lens,          HAS_LENS,        49) /* a thin lens (depth of field): camera rays from the lens point (Params::lens) */
// clang-format on

/// The quotient's lattice (sol::Lattice), each X(the kernel's float
/// constant, its id): the host rounds each from its double value (so that
/// the golden lattice's are the numbers its kernel once folded from
/// kPhi and kLatticeHeight). γ1 = (G1X, G1Y, 0), γ2 = (G2X, G2Y, 0);
/// LATTICE_INV_DET = 1 / det[γ1 γ2]; LATTICE_HEIGHT = h, the z of γ3;
/// LATTICE_TOP = h (1 - 1e-7), the largest z a teleport leaves;
/// LATTICE_INV_HEIGHT = 1 / h; LATTICE_LAMBDA = λ = e^h (γ3 scales x by
/// it), LATTICE_INV_LAMBDA = 1 / λ, LATTICE_SQRT_LAMBDA = √λ;
/// LATTICE_TURN = -1 where γ3 also turns the fibre by the half-turn (a
/// negative trace: sol::Lattice::turns), else 1; LATTICE_LOOPS = 0 for a
/// compact quotient, 1 for a z loop (D = R² × [0, h): no γ1, γ2, whose
/// constants are then the unit vectors, unused), 2 for xy loops (D = P × R:
/// no γ3, whose constants are then those of h = 1, unused)
/// (sol::Lattice::Loops).
// clang-format off
#define SOL_LATTICE_CONSTANTS(X)   \
  X(LATTICE_G1X,         30)       \
  X(LATTICE_G1Y,         31)       \
  X(LATTICE_G2X,         32)       \
  X(LATTICE_G2Y,         33)       \
  X(LATTICE_INV_DET,     34)       \
  X(LATTICE_HEIGHT,      35)       \
  X(LATTICE_TOP,         36)       \
  X(LATTICE_INV_HEIGHT,  37)       \
  X(LATTICE_LAMBDA,      38)       \
  X(LATTICE_INV_LAMBDA,  39)       \
  X(LATTICE_SQRT_LAMBDA, 40)       \
  X(LATTICE_TURN,        41)       \
  X(LATTICE_LOOPS,       42)
// clang-format on

// ---- Passes (kSpecPass). Without deferral one dispatch of kPassMarch does
// everything. With it (docs/renderer.md "Deferred passes"), the march pass
// lists the pixels whose ray reached an exact ball's shell in Sol, or whose
// ray has μ = |ab| below kZetaLeastMu in the quotient (kSpecResume), and
// the hits to shade (kSpecDeferShading) in binding kBindingQueue; the
// resume pass goes on with the first list's rays, the shade pass shades the
// second list's hits: each an indirect dispatch over its list alone, so
// that the pixels that need none of that work do not pay for it (lavapipe
// runs every branch of a SIMD group, masked, whatever its lanes take).
// What a dispatch's sample writes besides the colour (Params::pixel_sample.w).
SOL_CONSTANT(int, kSampleColourOnly, 0);     ///< the colour alone
SOL_CONSTANT(int, kSampleAovs, 1);           ///< the AOVs too (sample 0, the centre)
SOL_CONSTANT(int, kSampleAovsAndGuides, 2);  ///< the AOVs and the guides (sample 0 of render())
SOL_CONSTANT(int, kSampleJoinsGuides, 3);    ///< the guides' albedo and emission joined to their means (any other sample)

SOL_CONSTANT(int, kPassMarch, 0);
SOL_CONSTANT(int, kPassResume, 1);
SOL_CONSTANT(int, kPassShade, 2);

/// Params::path.w: how paths reach glowing balls (sol::PathSampling's order):
/// both ways combined, reflection sampling alone, next-event estimation alone.
SOL_CONSTANT(int, kPathSamplingCombined, 0);
SOL_CONSTANT(int, kPathSamplingReflectionOnly, 1);
SOL_CONSTANT(int, kPathSamplingGlowOnly, 2);

/// The quotient march's positions: by Jacobi's zeta function
/// (sol_forward_zeta in sol_forward.glsl) for rays of μ = |ab| at least
/// this, whose float rounding, about 2e-7/μ relative to the scale of the
/// position, is then below 2e-5; by Carlson's integrals (sol_forward) for
/// the others (with the resume pass, in that pass).
SOL_CONSTANT(SOL_REAL, kZetaLeastMu, 0.01);

// ---- Limits
// (A Sol world holds up to sol::kMaxObjects objects on the kernel as on the
// CPU: up to kListedObjects (sol/kernel_constants.h) relative to each eye
// in its Eye record, more through the tree of bounds, bindings
// kBindingCrowdNodes and kBindingCrowdItems.)
/// Most images of the objects around the domain in a quotient scene
/// (sol::quotient_images; lattice-balls has 50, lattice-pillars 27; a
/// world with more than kQuotientLongStepImages takes the short step):
/// the CPU's limit (sol::QuotientField::kMaxImages), the records a storage
/// buffer.
SOL_CONSTANT(int, kMaxGpuImages, kMaxQuotientImages);
/// Most images of the lights in a quotient scene (sol::quotient_light_images,
/// all lights together; about 300 for a light with reach 0, 2000 with reach 1).
SOL_CONSTANT(int, kMaxGpuLightImages, 4096);
/// Most images a pixel solves connections to, per light, nearest (by the
/// distance lower bound) first.
SOL_CONSTANT(int, kMaxLightImageSolves, 16);
/// The workgroup of march.comp: kGroupSize x kGroupSize pixels (8: march/camera.glsl's
/// group_pixel lays the invocations out in 2 x 4 blocks of an 8 x 8 group).
SOL_CONSTANT(int, kGroupSize, 8);

// ---- The parameters (binding kBindingParams: a read-only storage buffer, std430;
// vec4 and ivec4 members only, so no padding and the offsets of std140)

/// A scene object's appearance and kind (binding kBindingObjects, std430;
/// one per scene object, whatever the world's size).
struct Object {
  vec4 plane;     ///< x: object code (kObject*), y: radius, z: pattern code (kPattern*), w: 1 for a cutout
  vec4 color;     ///< rgb: linear colour; w: 0
  vec4 material;  ///< rgb: emitted radiance (linear); w: the material's code (kMaterial*, sol/material_kinds.h)
  vec4 params;    ///< the material's parameters (sol_material_lobes): x the diffuse material's mirror share
  vec4 glow;      ///< x: a glowing exact ball's glow_reach (next-event estimation); yzw: 0
  /// Its image texture (sol/texture.h): x its first texel in binding
  /// kBindingTextures, y its width, z its height (0: no texture), w 0 ...
  ivec4 texture;
  vec4 texture_cells;  ///< ... and xy the pattern cells one copy spans; zw: 0
};

/// One eye: a mono image has one, a side-by-side stereo image two, rendered
/// in one dispatch (the left eye's pixels are x < the eye's width).
struct Eye {
  vec4 right;        ///< xyz: camera right (frame components)
  vec4 up;           ///< xyz: camera up
  vec4 forward;      ///< xyz: camera forward; w: the RK4 step
  vec4 camera;       ///< xyz: camera position (world; in the quotient, teleported into D); w: e^{z}
  vec4 camera_frac;  ///< xyz: camera position modulo sol::kTexturePhase (the patterns and textures' phase, from double); w: e^{-z}
  vec4 window;       ///< sol::image_window: s_x at the left and right edges, s_y at the top and bottom
  vec4 projection;   ///< x: kProjection* code, y: a fisheye's half angle across its image circle (radians)
  /// A listed world's objects (at most kListedObjects; a crowd's are in
  /// bindings 13 and 14) relative to the eye: sol::KernelShape's geometry
  /// and heading of the object seen from the eye (computed in double).
  vec4 relative[SOL_LISTED_OBJECTS];
  vec4 heading[SOL_LISTED_OBJECTS];
  vec4 lights[kMaxLights];        ///< directional: unit direction; point: position relative to the eye
                                  ///< (world in the quotient); w: an exact light's reach
};

struct Params {
  Eye eyes[2];
  vec4 shading;    ///< x: ambient, y: fog density, z: light count
  vec4 fog_color;  ///< rgb
  vec4 limits;     ///< x: max distance, y: hit epsilon, z: max bounces (mirrors), w: max steps
  ivec4 counts;    ///< x: objects (the quotient: images), y: eye width, z: height, w: eyes (1 or 2)
  /// This dispatch's sample of every pixel: xy its point in the pixel (from
  /// the top-left corner; 0.5, 0.5 the centre), z its weight in the colour
  /// already in the image (1: overwrite; 1/(k + 1) for a running mean of
  /// k + 1 samples), w what it writes besides the colour (kSampleColourOnly
  /// ... kSampleJoinsGuides; the guides are render()'s, never a presenter's).
  vec4 pixel_sample;
  /// This dispatch's tile of the (side-by-side) image: xy its first pixel,
  /// zw its size; the dispatch covers it, pixels outside it are left alone.
  ivec4 tile;
  /// Light i casts shadows where component i is 1 (kMaxLights = 4 components).
  ivec4 light_shadows;
  /// The quotient: light i's images are light_images[first_i .. first_i + count_i) (binding 9).
  ivec4 light_image_first;
  ivec4 light_image_count;
  vec4 light_color[kMaxLights];  ///< rgb: colour times intensity; w: light code (kLight*)
  /// Path tracing (PATH_TRACING, march/paths.glsl): xy the seed's low and high 32 bits, z this
  /// dispatch's sample (the index of the pixel's path), w the sampling of
  /// glowing balls (kPathSampling*).
  ivec4 path;
  /// The 8-bit output's display (SOL_OUTPUT_SRGB_UNORM, sol::Display): x
  /// the exposure's scale 2^stops, y the tone curve's code (sol/tone.h).
  vec4 display;
  /// Depth of field (HAS_LENS, sol/lens.hpp): xy this dispatch's point of
  /// the unit disk (sol::lens_sample), z the aperture, w the focus distance.
  vec4 lens;
  /// A crowd's targets of next-event estimation (sol::glow_target_objects,
  /// at most SOL_LISTED_OBJECTS): their crowd items (leaf order), -1 after
  /// the last (march/glow.glsl).
  ivec4 crowd_targets[SOL_LISTED_OBJECTS / 4];
};

// ---- The quotient's images of the objects around D (binding 4, std430), world coordinates
struct Image {
  vec4 geometry;  ///< ball: centre; tube: (point of the axis, axis code); plane z = c: (c, 0, 0, 0)
  vec4 info;      ///< x: object code, y: radius, z: the scene object it images (0-based)
  vec4 heading;   ///< horizontal tubes: xy the axis's unit coordinate direction; zw: 0 (unused)
  /// The object's bound as the march's candidates read it (march/objects.glsl's
  /// image_clearances; four words, as each word a step reads at a per-lane
  /// index is a gather on lavapipe): balls (centre, radius); planes z = c
  /// (c, 0, 0, 0); tubes (vertical: (-radius, x0, y0, 0); horizontal along
  /// the unit coordinate direction h through (x0, y0, z0):
  /// (k h_x, k h_y, k (h_y x0 - h_x y0), z0), k = ±radius / (|h_x| + |h_y|)
  /// with the sign that makes k h_x >= 0: the bound's across term is
  /// invariant under scaling h, so the scale carries the radius,
  /// |k h_x| + |k h_y|, and the first word's sign the axis).
  vec4 bound;
};

// ---- A crowd (a Sol world of more than kListedObjects objects): its tree
// of bounds (sol::BoundsTree, depth-first: an inner node's first child is
// the next node), binding kBindingCrowdNodes, and its objects in the
// tree's leaf order, binding kBindingCrowdItems, in world coordinates
// (the kernel sees them from the eye as it reads them:
// march/crowd.glsl). Indices and counts are floats, exact below 2^24
// (sol::kMaxObjects is 2^20).
struct CrowdNode {
  vec4 lo;  ///< xyz: the node's coordinate box's least corner (±1e30 where unbounded); w: a leaf's first item, an inner node's second child
  vec4 hi;  ///< xyz: its largest corner; w: a leaf's item count, 0 for an inner node
};
struct CrowdItem {
  vec4 geometry;  ///< sol::KernelShape::geometry (world coordinates)
  vec4 shape;     ///< xy: sol::KernelShape::heading; z: radius; w: object code (kObject*)
  vec4 info;      ///< x: the scene object (0-based); y: a cutout plane's pattern code, else kPatternNone;
                  ///< zw: e^{z/2}, e^{-z/2} of geometry.z (solids' centres and axis points; 1 for planes)
};

// ---- The composites' parts (binding kBindingParts, std430), world
// coordinates: each composite's chain ((P0 op1 P1) op2 P2) ... (its parts
// b of the list's kinds, nested composites as its parts a) one part after
// the other, the composites (of the scene objects in Sol, of the images in
// the quotient) one after the other; its record's geometry is (the index
// of P0, the number of parts, 0, 0) (march/composites.glsl).
struct Part {
  vec4 geometry;  ///< sol::KernelShape::geometry
  vec4 shape;     ///< xy: sol::KernelShape::heading; z: radius; w: object code (kObject*, a kind of the list)
  vec4 info;      ///< x: the operation (kComposite*) that joins it to the chain before it (P0: none)
};

// ---- The deferred passes' lists (binding kBindingQueue, std430): the
// header, then for a dispatch of n pixels (Params::tile: n = tile.z ·
// tile.w) n resume records (uvec4: pixel, t, passing mask, march step) and
// n shade records (3 uvec4: the hit point and t; the normal's octahedral
// code, the pixel, the scene object; the pattern's coordinates and the
// ray's unit tangent's octahedral code). A list's dispatch (x, y, z) counts
// its workgroups of kGroupSize² records: the march pass adds one for every
// kGroupSize²-th record it appends. The host resets the header each frame
// (QueueHeader{} with y = z = 1).
struct QueueHeader {
  ivec4 resume;  ///< xyz: the resume pass's VkDispatchIndirectCommand; w: its records
  ivec4 shade;   ///< the same for the shade pass
};
/// The records' sizes in uvec4s: a resume record, a shade record.
SOL_CONSTANT(int, kQueueResumeRecord, 1);
SOL_CONSTANT(int, kQueueShadeRecord, 3);

// ---- What a frame's rays counted (binding kBindingStats, std430): the
// host zeroes it before a render and reads it after (RenderResult).
struct Stats {
  /// Marches that stopped at max_steps before they met an object or
  /// reached max_distance (RenderResult::rays_out_of_steps); x alone, yzw 0.
  uvec4 out_of_steps;
};

// ---- An omnidirectional stereo eye's column (binding 8, std430): sol::column_eye
struct Column {
  vec4 offset;        ///< xyz: where the column's rays start, relative to the eye's camera
  vec4 transport[3];  ///< xyz: the columns of the frame transport to there
};

#ifdef __cplusplus
/// Every specialisation constant's id, the features' and the variant's.
inline constexpr int kSpecIds[] = {
#define SOL_SPEC_ID(member, constant, id) id,
#define SOL_LATTICE_SPEC_ID(constant, id) id,
    SOL_MARCH_FEATURES(SOL_SPEC_ID) SOL_KERNEL_VARIANT_FLAGS(SOL_SPEC_ID) SOL_LATTICE_CONSTANTS(SOL_LATTICE_SPEC_ID)
#undef SOL_SPEC_ID
#undef SOL_LATTICE_SPEC_ID
        kSpecIntegrator, kSpecPass};
constexpr bool distinct_spec_ids() {
  for (int a : kSpecIds) {
    int n = 0;
    for (int b : kSpecIds) n += a == b ? 1 : 0;
    if (n != 1) return false;
  }
  return true;
}
static_assert(distinct_spec_ids(), "two specialisation constants share an id (sol/march_features.h, SOL_KERNEL_VARIANT_FLAGS)");
static_assert(kMaxLights == 4, "Params::light_shadows holds one component per light");
static_assert(SOL_LISTED_OBJECTS % 4 == 0, "Params::crowd_targets holds four items a vector");
static_assert(sizeof(Object) == 7 * 16 && sizeof(CrowdNode) == 2 * 16 && sizeof(CrowdItem) == 3 * 16 && sizeof(Part) == 3 * 16 && sizeof(Image) == 4 * 16 && sizeof(Column) == 4 * 16 && sizeof(QueueHeader) == 2 * 16 &&
                  sizeof(Stats) == 16,
              "vec4 records");
static_assert(offsetof(Eye, projection) == 6 * 16 && offsetof(Eye, relative) == 7 * 16 &&
                  offsetof(Eye, heading) == (7 + SOL_LISTED_OBJECTS) * 16 &&
                  offsetof(Eye, lights) == (7 + 2 * SOL_LISTED_OBJECTS) * 16 &&
                  sizeof(Eye) == (7 + 2 * SOL_LISTED_OBJECTS + kMaxLights) * 16,
              "std140 layout of Eye");
static_assert(offsetof(Params, shading) == 2 * sizeof(Eye) && offsetof(Params, counts) == 2 * sizeof(Eye) + 3 * 16 &&
                  offsetof(Params, pixel_sample) == 2 * sizeof(Eye) + 4 * 16 &&
                  offsetof(Params, tile) == 2 * sizeof(Eye) + 5 * 16 &&
                  offsetof(Params, light_shadows) == 2 * sizeof(Eye) + 6 * 16 &&
                  offsetof(Params, light_image_count) == 2 * sizeof(Eye) + 8 * 16 &&
                  offsetof(Params, light_color) == 2 * sizeof(Eye) + 9 * 16 &&
                  offsetof(Params, path) == 2 * sizeof(Eye) + (9 + kMaxLights) * 16 &&
                  offsetof(Params, display) == 2 * sizeof(Eye) + (10 + kMaxLights) * 16 &&
                  offsetof(Params, lens) == 2 * sizeof(Eye) + (11 + kMaxLights) * 16 &&
                  offsetof(Params, crowd_targets) == 2 * sizeof(Eye) + (12 + kMaxLights) * 16 &&
                  sizeof(Params) == 2 * sizeof(Eye) + (12 + kMaxLights) * 16 + SOL_LISTED_OBJECTS * 4,
              "std140 layout of Params");
}  // namespace sol::vk::kernel
#endif

#endif  // SOL_MARCH_INTERFACE_H
