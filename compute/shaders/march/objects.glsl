// The objects as the march sees them, in float: each kind's distance
// (exact for planes, a lower bound for solids: sol/distance.hpp), its
// clearances along a ray (sol/clearance.hpp), normal and pattern
// coordinates, in its own file under compute/shaders/kinds/, and here what
// they share and the dispatch by kind, generated from the list of kinds
// (sol/object_kinds.h): a kind listed there without its functions does not
// compile. Also the patterns, the gaps of cutout planes, and the objects of
// a world relative to an eye. The GLSL twin of libsol's objects; the
// kernel's codes and constants come from sol/kernel_constants.h, the
// patterns' formulas from sol/patterns.h (shared with libsol).
#ifndef SOL_MARCH_OBJECTS_GLSL
#define SOL_MARCH_OBJECTS_GLSL

#include "sol/patterns.h"  // the patterns and the kinds' pattern coordinates, shared with libsol
#include "sol/texture.h"   // image textures' mapping, shared with libsol

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

// ---- Seen from inside a solid (sol/clearance.hpp, "Seen from inside a
// solid"): each face a distance g > 0 with rate g' and g'' >= -bend for
// steps up to `reach`; its clearances ahead and back, the larger of g and
// the first root of g ± g' s - ½ bend s² (at most the reach). A bend of
// 1e30 (no established bound): g alone.
vec2 inside_face(float g, float slope, float bend, float reach) {
  const float big = abs(slope) + sqrt(slope * slope + 2.0 * bend * max(g, 0.0));
  const float small = 2.0 * g / max(big, 1e-30);
  const vec2 s = slope >= 0.0 ? vec2(big / bend, small) : vec2(small, big / bend);
  return max(vec2(g), min(s, vec2(reach)));
}

// The face of the plane x = c seen from inside, `side` +1 where the solid
// lies at x > c: (g, g') of side · asinh((x - c) e^{-z}) (iez = e^{-z}).
vec2 face_x(vec3 q, vec3 u, float c, float side, float iez) {
  const float w = (q.x - c) * iez, root = sqrt(1.0 + w * w);
  return side * vec2(sign(w) * log(abs(w) + root), (u.x - w * u.z) / root);
}

// The same for y = c: side · asinh((y - c) e^{z}) (ez = e^{z}).
vec2 face_y(vec3 q, vec3 u, float c, float side, float ez) {
  const float w = (q.y - c) * ez, root = sqrt(1.0 + w * w);
  return side * vec2(sign(w) * log(abs(w) + root), (u.y + w * u.z) / root);
}

// A face's (g, g') and bend into the least clearances so far (x: g, yz:
// ahead and back, w: the rate of the nearest face, sol::InsideClearances).
void inside_least(inout vec4 least, vec2 face, float bend, float reach) {
  least.w = face.x < least.x ? face.y : least.w;
  least.xyz = min(least.xyz, vec3(face.x, inside_face(face.x, face.y, bend, reach)));
}

// A slab |σ| <= r about a signed distance (σ, σ'): its faces r - σ and r + σ.
void inside_slab(inout vec4 least, vec2 sigma, float r, float bend) {
  inside_least(least, vec2(r - sigma.x, -sigma.y), bend, 1e30);
  inside_least(least, vec2(r + sigma.x, sigma.y), bend, 1e30);
}

// A solid's normal at q: the gradient of its bound by central differences
// along E1, E2, E3 (kNormalStep; as the CPU reference). A kind's file
// defines its normal by SOL_SOLID_NORMAL(prefix) below its prefix_distance:
// the six evaluations call that kind's bound alone, not the dispatch over
// every kind, which the driver would inline six times per kind before
// folding the kind away; and they are one loop, whose body holds the bound
// once (the driver inlines every call; kept rolled, the loop costs six
// iterations of one copy where six copies cost six compiles). Component i
// >> 1 of the gradient is the bound at q + e less the bound at q - e, in
// that order.
#define SOL_NORMAL_BOUND(prefix, p) prefix##_distance(p, rel, heading, radius, half_exp((p).z), half_exp(rel.z))
#define SOL_SOLID_NORMAL(prefix)                                                                        \
  vec3 prefix##_solid_normal(vec3 q, vec4 rel, vec2 heading, float radius) {                            \
    const float h = kNormalStep, ez = exp(q.z);                                                         \
    vec3 g = vec3(0.0);                                                                                 \
    int i = 0;                                                                                          \
    [[dont_unroll]] do {                                                                                \
      const int axis = i >> 1;                                                                          \
      const vec3 e = axis == 0 ? vec3(h * ez, 0.0, 0.0) : (axis == 1 ? vec3(0.0, h / ez, 0.0) : vec3(0.0, 0.0, h)); \
      const bool back = (i & 1) != 0;                                                                   \
      const float d = SOL_NORMAL_BOUND(prefix, back ? q - e : q + e);                                   \
      g[axis] = back ? g[axis] - d : d;                                                                 \
    } while (++i < 6);                                                                                  \
    return length(g) > 0.0 ? normalize(g) : vec3(0.0, 0.0, 1.0);                                        \
  }

// w = rel⁻¹·q: the point q relative to a solid's centre (axis point) `rel`,
// where its pattern's coordinates are taken.
vec3 solid_relative(vec3 q, vec4 rel) {
  const float ez = exp(rel.z);
  return vec3((q.x - rel.x) / ez, (q.y - rel.y) * ez, q.z - rel.z);
}

// A world point seen from the eye at p (p⁻¹·w): camera = (p, e^{p_z}),
// camera_frac.w = e^{-p_z} (Eye::camera, Eye::camera_frac).
vec3 seen_point(vec3 w, vec4 camera, vec4 camera_frac) {
  return vec3((w.x - camera.x) * camera_frac.w, (w.y - camera.y) * camera.w, w.z - camera.z);
}

#include "../kinds/kinds.glsl"

// The eye of load_objects (below): camera = (p, e^{p_z}), camera_frac.w =
// e^{-p_z} (Eye::camera, Eye::camera_frac).
vec4 g_eye_camera, g_eye_frac;

// ---- The dispatch by kind. Each kind only when the world has it (its
// feature's specialisation constant): lavapipe evaluates every branch.
// An object's record: `rel` (planes (c, 0, 0, 0); solids their centre or
// axis point), `heading`, `radius`, in the coordinates of q (relative to
// the eye in Sol, world coordinates in the quotient); hz, hc: the half
// exponentials (half_exp) of q.z and rel.z, which a march step shares
// among its objects. The kind_* functions dispatch over the list's kinds
// (sol/object_kinds.h), the object_* and image_* functions below over
// those and composites (march/composites.glsl, which draws its parts by
// the kind_* functions: GLSL has no recursion).

// Distance (planes: exact; solids: the bound). Exact balls are approached
// by their bound too (the true sphere lies inside the bound's), and within
// kExactShell of it marched by their exact distance (exact_ball_sdf) and
// its clearance (exact_ball_clearance).
#define SOL_KIND_DISTANCE(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) return prefix##_distance(q, rel, heading, radius, hz, hc);
float kind_bound(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  SOL_OBJECT_KINDS(SOL_KIND_DISTANCE)
  return 1e30;  // no kind of this world's
}
#undef SOL_KIND_DISTANCE

// An object's record (world coordinates) as seen from the eye at p
// (camera, camera_frac: seen_point's), as the host's Eye::relative and
// Eye::heading hold a listed world's (there in double). (A composite's
// record is its parts' index: its parts are seen from the eye as they are
// read.)
#define SOL_KIND_SEEN_FROM(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) prefix##_seen_from(rel, heading, camera, camera_frac);
void object_seen_from(int type, inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  SOL_OBJECT_KINDS(SOL_KIND_SEEN_FROM)
}
#undef SOL_KIND_SEEN_FROM

// Whether the object is a solid (sol/object_kinds.h; composites are).
#define SOL_KIND_SOLID(Type, code_name, code, prefix, feature, solid) || (solid && feature_##feature && type == code_name)
bool object_is_solid(int type) { return (HAS_COMPOSITES && type == kObjectComposite) SOL_OBJECT_KINDS(SOL_KIND_SOLID); }
#undef SOL_KIND_SOLID

// The guards that rule out code (composites, solids seen from inside) are
// macros, not functions: the host's folding of the specialisation
// constants (sol::vk::specialize_spirv) propagates constants within a
// function only, so a guard returned by a function would keep the code it
// rules out (a world without composites would still compile them).
#define is_composite(type) (HAS_COMPOSITES && (type) == kObjectComposite)

// Solids seen from inside (HAS_INSIDE, a frame whose eye is inside a
// solid: a ray that starts outside every solid meets a surface before it
// is inside one). A solid's bound is 1-Lipschitz and the solid is where
// it is <= 0 (sol::seen_distance in libsol/src/render.cpp), so inside,
// where it is d < 0, the wall is at least -d away: the march's distance
// and clearances (the outside's clearance does not hold there) are -d.
// Exact balls have their own inside (exact_ball_inside, the exact solve).
#define inside_by_bound(type) (HAS_INSIDE && (type) != kObjectExactBall && object_is_solid(type))

// How deep inside a solid it passes (hit_epsilons, by its bound) a ray must
// be before its pass ends where it heads for a face (the passes' `heads`):
// a ray leaving a face met from outside almost tangentially runs along the
// surface, where float's bound dips below 0 by rounding while the ray
// heads for the face it leaves; ending its pass there met the same solid
// again at once (a diffuse bounce off a glowing bound ball, in a world with
// glass: its emission again at every bounce, in one path in 250), where
// the CPU's double stays outside and passes it until 2 hit_epsilon away.
const float kHeadsDepth = 0.5;

// Whether a ray passing a solid it leaves (its bound d from the ray's
// point), where solids drawn by their bound are not seen from inside, has
// gone 2 hit_epsilon into it: a ray that leaves a face at a grazing angle
// and bends back into the solid is blocked there, not passed through it 2
// hit_epsilon a step until it runs out of steps. Exact balls keep their
// own rule (their exact solves).
bool passed_into(int type, float d, float hit_epsilon) {
  return HAS_SOLIDS && !HAS_INSIDE && type != kObjectExactBall && d < -2.0 * hit_epsilon;
}

// Whether passed_into's solid, where the ray is inside it by less (d < 0),
// ends its pass where the ray heads away from its nearest face (sinks_into:
// that face's distance seen from inside rising). Without it a ray that
// leaves a face at a grazing angle and bends back into the solid passed it
// 2 hit_epsilon a step until 2 hit_epsilon deep: connections from a
// glowing box's top towards points of its sides, skimming the top, sank
// too slowly and ran out of steps (the CPU sees the solid from inside and
// steps by its faces; docs/renderer.md).
bool may_sink_into(int type, float d) {
  return HAS_SOLIDS && !HAS_INSIDE && d < 0.0 && type != kObjectExactBall && object_is_solid(type);
}

// The rule itself, from the solid's clearances seen from inside (w: the
// nearest face's rate g').
bool sinks_into(vec4 inside) { return inside.w > 0.0; }

float seen_from_inside(int type, float d) { return inside_by_bound(type) && d < 0.0 ? -d : d; }

// Inside a solid drawn by its bound (the bound -d < 0 given): its faces'
// clearances (-d, ahead, back) and the rate of its nearest face
// (sol::shape_inside_clearances). An object's record, or a quotient image's.
vec4 kind_inside_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc, float d) {
  vec4 c = vec4(d, d, d, 0.0);
  if (feature_bound_balls && type == kObjectBall) c = ball_inside_clearances(q, u, rel.xyz, radius, hz, hc);
  if (feature_boxes && type == kObjectBox) c = box_inside_clearances(q, u, rel.xyz, vec3(heading, rel.w), hz);
  if (feature_tubes && type == kObjectTube) c = tube_inside_clearances(q, u, rel.xyz, int(rel.w) == kTubeVertical, heading, radius, hz);
  return vec4(d, max(vec2(d), c.yz), c.w);
}

vec4 kind_image_inside_clearances(int type, vec3 q, vec3 u, Image m, vec2 hz, float d) {
  vec4 c = vec4(d, d, d, 0.0);
  if (feature_bound_balls && type == kObjectBall) c = ball_inside_clearances(q, u, m.bound.xyz, m.bound.w, hz, half_exp(m.bound.z));
  if (feature_boxes && type == kObjectBox) c = box_inside_clearances(q, u, m.bound.xyz, vec3(m.heading.xy, m.bound.w), hz);
  if (feature_tubes && type == kObjectTube) c = tube_record_inside_clearances(q, u, m, hz);
  return vec4(d, max(vec2(d), c.yz), c.w);
}

// The object's bound and clearances: (bound, clearance along u, clearance
// back along -u), each clearance the larger of the distance and the
// second-order step of its bound (exact balls: the bound's ball, which
// holds the exact one, as object_distance); the clearance back is the
// quotient march's check of an over-relaxed step.
#define SOL_KIND_CLEARANCES(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) return prefix##_clearances(q, u, rel, heading, radius, hz, hc);
vec3 kind_bound_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  SOL_OBJECT_KINDS(SOL_KIND_CLEARANCES)
  return vec3(1e30);
}
#undef SOL_KIND_CLEARANCES

// The same of a quotient image from its record: its bound (Image::bound,
// sol::KernelShape::bound: four words, as each word a step reads at a
// per-lane index is a gather on lavapipe; a kind that needs more reads its
// heading word too, and only its worlds load it).
#define SOL_KIND_RECORD(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) return prefix##_record_clearances(q, u, m, hz);
vec3 kind_image_bound_clearances(int type, vec3 q, vec3 u, Image m, vec2 hz) {
  SOL_OBJECT_KINDS(SOL_KIND_RECORD)
  return vec3(1e30);
}
#undef SOL_KIND_RECORD

// The surface normal at a hit q (frame components); planes face the side
// of `from`, the start of the ray's segment.
#define SOL_KIND_NORMAL(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) return prefix##_normal(q, rel, heading, radius, from);
vec3 kind_normal(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  SOL_OBJECT_KINDS(SOL_KIND_NORMAL)
  return vec3(0.0, 0.0, 1.0);
}
#undef SOL_KIND_NORMAL

// The coordinates the object's pattern is drawn in at q: planes their own
// coordinates of the world point (`phase`, pattern_phase), solids those of
// q relative to them.
#define SOL_KIND_PATTERN_UV(Type, code_name, code, prefix, feature, solid) \
  if (feature_##feature && type == code_name) return prefix##_pattern_uv(q, phase, rel, heading, radius);
vec2 kind_pattern_uv(int type, vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  SOL_OBJECT_KINDS(SOL_KIND_PATTERN_UV)
  return vec2(0.0);
}
#undef SOL_KIND_PATTERN_UV

#include "composites.glsl"

// ---- Objects and images of every kind, composites too.

float object_bound(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return is_composite(type) ? composite_bound(q, rel, hz) : kind_bound(type, q, rel, heading, radius, hz, hc);
}

vec4 object_inside_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc, float d) {
  return is_composite(type) ? composite_inside_clearances(q, u, rel, hz, d)
                            : kind_inside_clearances(type, q, u, rel, heading, radius, hz, hc, d);
}

vec4 image_inside_clearances(int type, vec3 q, vec3 u, Image m, vec2 hz, float d) {
  return is_composite(type) ? composite_inside_clearances(q, u, m.geometry, hz, d)
                            : kind_image_inside_clearances(type, q, u, m, hz, d);
}

// The distance the march steps by: the bound, seen from inside where the ray is.
float object_distance(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return seen_from_inside(type, object_bound(type, q, rel, heading, radius, hz, hc));
}

float object_distance(int type, vec3 q, vec4 rel, vec2 heading, float radius) {
  return object_distance(type, q, rel, heading, radius, half_exp(q.z), half_exp(rel.z));
}

vec3 object_bound_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return is_composite(type) ? composite_bound_clearances(q, u, rel, hz)
                            : kind_bound_clearances(type, q, u, rel, heading, radius, hz, hc);
}

// The object's distance and clearances, seen from inside where the ray is.
vec3 object_clearances(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  const vec3 c = object_bound_clearances(type, q, u, rel, heading, radius, hz, hc);
  return inside_by_bound(type) && c.x < 0.0 ? object_inside_clearances(type, q, u, rel, heading, radius, hz, hc, -c.x).xyz : c;
}

vec2 object_clearance(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return object_clearances(type, q, u, rel, heading, radius, hz, hc).xy;
}

vec3 image_bound_clearances(int type, vec3 q, vec3 u, Image m, vec2 hz) {
  return is_composite(type) ? composite_bound_clearances(q, u, m.geometry, hz) : kind_image_bound_clearances(type, q, u, m, hz);
}

// object_clearances of a quotient image from its record.
vec3 image_clearances(int type, vec3 q, vec3 u, Image m, vec2 hz) {
  const vec3 c = image_bound_clearances(type, q, u, m, hz);
  return inside_by_bound(type) && c.x < 0.0 ? image_inside_clearances(type, q, u, m, hz, -c.x).xyz : c;
}

// A quotient image's distance (its bound's, image_clearances' first
// component, which the direction does not enter).
float image_distance(int type, vec3 q, Image m) { return image_clearances(type, q, vec3(0.0), m, half_exp(q.z)).x; }

// Whether a ray from q along u, q within 2 hit_epsilon of a solid's
// surface, leaves the solid through that face: q inside it (by its bound)
// and the ray heading for its nearest face (the CPU's leaving_sign). Exact
// balls and composites have rules of their own (their leave signs).
bool leaves_through_start(int type, vec3 q, vec3 u, vec4 rel, vec2 heading, float radius) {
  if (!inside_by_bound(type) || is_composite(type)) return false;
  const vec2 hz = half_exp(q.z), hc = half_exp(rel.z);
  const float raw = object_bound(type, q, rel, heading, radius, hz, hc);
  return raw < 0.0 && object_inside_clearances(type, q, u, rel, heading, radius, hz, hc, -raw).w < 0.0;
}

bool image_leaves_through_start(int type, vec3 q, vec3 u, Image m) {
  if (!inside_by_bound(type) || is_composite(type)) return false;
  const vec2 hz = half_exp(q.z);
  const float raw = image_bound_clearances(type, q, u, m, hz).x;
  return raw < 0.0 && image_inside_clearances(type, q, u, m, hz, -raw).w < 0.0;
}

vec3 object_normal(int type, vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return is_composite(type) ? composite_normal(q, rel, from) : kind_normal(type, q, rel, heading, radius, from);
}

vec2 object_pattern_uv(int type, vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  return is_composite(type) ? composite_pattern_uv(q, phase, rel) : kind_pattern_uv(type, q, phase, rel, heading, radius);
}

// ---- Patterns

float pattern_factor(int pattern, float u, float v) { return sol_pattern_factor(pattern, u, v); }

// The world point of a camera-relative point q, modulo 2 (the common period
// of the circles, 1, and the checkerboard's parity, 2): world = camera * q,
// with the camera position modulo 2 from double.
vec3 pattern_phase(vec3 q, vec4 eye_camera, vec4 eye_frac) {
  return eye_frac.xyz + vec3(eye_camera.w * q.x, eye_frac.w * q.y, q.z);
}

// sol::cutout_gap_bound: a lower bound of the distance to the solid part of
// a cutout plane z = c (discs, light squares) from a point with world
// coordinates (u, v) (modulo 2) and e^{z} = ez; combined with |z - c| by max.
float cutout_gap_bound(int pattern, vec2 uv, float ez) { return sol_cutout_gap_bound(pattern, uv.x, uv.y, ez); }

// ---- The objects of a world in Sol, relative to one eye (its uniforms
// copied once: lavapipe does not hoist uniform loads out of loops).

// A crowd's target i of next-event estimation: its crowd item (Params::crowd_targets; -1 after the last).
int crowd_target_item(int i) { return params.crowd_targets[i >> 2][i & 3]; }

int g_count;  // a listed world's objects (0 for a crowd: march/crowd.glsl)
int g_crowd_targets;  // a crowd's targets of next-event estimation (Params::crowd_targets before the first -1)
int g_types[kListedObjects];
float g_constants[kListedObjects];  // planes: c
float g_radii[kListedObjects];
vec4 g_relative[kListedObjects];
vec2 g_headings[kListedObjects];
int g_cutouts[kListedObjects];      // cutout planes z = c: their pattern code; else kPatternNone
vec2 g_half_exp_z[kListedObjects];  // balls: the centre's half exponentials (half_exp)
vec2 g_eye_half_exp;  // e^{-z/2}, e^{z/2} of the eye's z (a crowd's objects' half exponentials: march/crowd.glsl)
float g_rk4_step;  // RK4's substep (INTEGRATOR = 1)

void load_objects(int eye) {
  // (The host pads the objects' records to kListedObjects.)
  g_count = CROWD ? 0 : min(params.counts.x, kListedObjects);
  g_crowd_targets = 0;
  while (CROWD && g_crowd_targets < kListedObjects && crowd_target_item(g_crowd_targets) >= 0) {
    ++g_crowd_targets;
  }
  for (int k = 0; k < (CROWD ? 0 : kListedObjects); ++k) {
    g_types[k] = int(scene_objects[k].plane.x);
    g_cutouts[k] = HAS_CUTOUT && g_types[k] == kObjectPlaneZ && scene_objects[k].plane.w != 0.0
                       ? int(scene_objects[k].plane.z)
                       : 0;
    g_radii[k] = scene_objects[k].plane.y;
    g_relative[k] = params.eyes[eye].relative[k];
    g_headings[k] = params.eyes[eye].heading[k].xy;
    g_constants[k] = g_relative[k].x;
    g_half_exp_z[k] = HAS_SOLIDS ? half_exp(g_relative[k].z) : vec2(1.0);
  }
  g_eye_camera = params.eyes[eye].camera;
  g_eye_frac = params.eyes[eye].camera_frac;
  g_eye_half_exp = CROWD ? sqrt(vec2(g_eye_frac.w, g_eye_camera.w)) : vec2(1.0);
  g_rk4_step = params.eyes[eye].forward.w;
}

#endif  // SOL_MARCH_OBJECTS_GLSL
