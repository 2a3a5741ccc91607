// Every kind of object's functions in the kernels, one file per kind's
// struct. A kind of sol/object_kinds.h (its line gives the prefix) provides
//   float prefix_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc)
//       its distance (a lower bound for solids);
//   vec3 prefix_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc)
//       (distance, clearance along u, clearance back along -u);
//   vec3 prefix_record_clearances(vec3 q, vec3 u, Image m, vec2 hz)
//       the same from its quotient image's record (m.bound is
//       sol::KernelShape::bound; m.heading its heading);
//   vec3 prefix_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from)
//   vec2 prefix_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius)
//   void prefix_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac)
//       its record (world coordinates) seen from the eye (a crowd's,
//       march/crowd.glsl; the host does a listed world's in double)
// with rel, heading and radius from sol::KernelShape (geometry, heading,
// radius), q and rel in the same coordinates, hz and hc the half
// exponentials of q.z and rel.z. march/objects.glsl dispatches to them and
// provides what they share (half_exp, distance_lower_bound,
// clearance_roots, SOL_SOLID_NORMAL (a solid's normal by central
// differences of its prefix_distance), solid_relative, seen_point). A new
// kind's file is included here.
#ifndef SOL_KINDS_GLSL
#define SOL_KINDS_GLSL

#include "planes.glsl"
#include "ball.glsl"
#include "tube.glsl"
#include "box.glsl"

#endif  // SOL_KINDS_GLSL
