// Composites (kObjectComposite; sol::Composite, libsol/src/objects/composite.cpp,
// the double reference): the union, intersection or difference of two
// solids A and B, drawn as a chain ((P0 op1 P1) op2 P2) ... of parts of the
// list's kinds (sol::composite_chain: composites nested as parts A). Every
// solid's bound is 1-Lipschitz and <= 0 exactly on the solid, so
// min(d_A, d_B), max(d_A, d_B) and max(d_A, -d_B) are such bounds of the
// composed sets: the march steps by them on either side. The clearances,
// the normal and the pattern are the parts': those of the part whose term
// is the bound at the point (the active part; B's normal turned in a
// difference). A composite's record is (its first part's index in the
// parts' buffer, its number of parts): the parts are read there (binding
// kBindingParts, world coordinates) and, in Sol, seen from the eye as a
// crowd's objects are.
#ifndef SOL_MARCH_COMPOSITES_GLSL
#define SOL_MARCH_COMPOSITES_GLSL

layout(std430, set = 0, binding = kBindingParts) readonly buffer CompositeParts {
  Part composite_parts[];
};

// A part as the march sees it: its kind's record in the coordinates of q,
// and the operation joining it to the chain before it.
struct CompositePart {
  int type;
  vec4 rel;
  vec2 heading;
  float radius;
  vec2 hc;  // rel.z's half exponentials
  int op;
};

CompositePart composite_part(int i) {
  const Part p = composite_parts[i];
  CompositePart c;
  c.type = int(p.shape.w);
  c.rel = p.geometry;
  c.heading = p.shape.xy;
  c.radius = p.shape.z;
  if (!QUOTIENT) object_seen_from(c.type, c.rel, c.heading, g_eye_camera, g_eye_frac);
  c.hc = half_exp(c.rel.z);
  c.op = int(p.info.x);
  return c;
}

float part_bound(CompositePart p, vec3 q, vec2 hz) { return kind_bound(p.type, q, p.rel, p.heading, p.radius, hz, p.hc); }

// How far the ray goes (ahead, back) before it can reach part p, q outside
// it (bound d > 0), or leave it, q inside (d < 0): its clearances from
// outside or inside, at least |d|.
vec2 part_reaching(CompositePart p, vec3 q, vec3 u, vec2 hz, float d) {
  return max(vec2(d), kind_bound_clearances(p.type, q, u, p.rel, p.heading, p.radius, hz, p.hc).yz);
}

vec2 part_leaving(CompositePart p, vec3 q, vec3 u, vec2 hz, float d) {
  return max(vec2(-d), kind_inside_clearances(p.type, q, u, p.rel, p.heading, p.radius, hz, p.hc, -d).yz);
}

// The chain ((P0 op1 P1) op2 P2) ... at q, part after part (a composite
// of composites as its parts a is one; sol::Composite::chain): its bound,
// the part whose term it is (the active `part`, an index of the parts' buffer) and
// whether that term enters negated (`turned`: a difference's B); with
// `clear`, also how far along u (and back) the ray goes before it can
// reach the chain, q outside it (`reach`), or leave it, q inside
// (`leave`), as sol::Composite's clearances and inside clearances: a
// union is reached no sooner than its nearer side and left no sooner than
// each side q is inside of; an intersection is reached no sooner than each
// side q is outside of and left no sooner than the first side is; a
// difference A \ B is reached no sooner than A (q outside A) and than the
// ray leaves B (q inside B), and left no sooner than the first of leaving
// A and reaching B.
struct CompositeAt {
  float bound;
  vec2 reach, leave;
  int part;  // the active part
  bool turned;
};

CompositeAt composite_at(vec3 q, vec3 u, vec4 rel, vec2 hz, const bool clear) {
  const int first = int(rel.x), count = int(rel.y);
  // P0 joins by a union to the empty chain (bound 1e30, reached nowhere):
  // one copy of the parts' code in the loop, not two.
  CompositeAt c = CompositeAt(1e30, vec2(1e30), vec2(0.0), first, false);
  for (int i = first; i < first + count; ++i) {
    const CompositePart p = composite_part(i);
    const float d = part_bound(p, q, hz), f = c.bound;
    const vec2 reach = clear && d > 0.0 ? part_reaching(p, q, u, hz, d) : vec2(0.0);
    const vec2 leave = clear && d < 0.0 ? part_leaving(p, q, u, hz, d) : vec2(0.0);
    const vec2 reach_f = f > 0.0 ? c.reach : vec2(0.0), leave_f = f < 0.0 ? c.leave : vec2(0.0);
    const float b = p.op == kCompositeDifference ? -d : d;
    const bool takes = p.op == kCompositeUnion ? b < f : b > f;
    if (p.op == kCompositeUnion) {
      c.reach = min(c.reach, reach);
      c.leave = max(leave_f, d < 0.0 ? leave : vec2(0.0));
    } else if (p.op == kCompositeIntersection) {
      c.reach = max(reach_f, d > 0.0 ? reach : vec2(0.0));
      c.leave = min(c.leave, leave);
    } else {
      c.reach = max(reach_f, d < 0.0 ? leave : vec2(0.0));
      c.leave = min(c.leave, reach);
    }
    c.bound = p.op == kCompositeUnion ? min(f, b) : max(f, b);
    c.reach = max(c.reach, vec2(c.bound));
    c.leave = max(c.leave, vec2(-c.bound));
    c.part = takes ? i : c.part;
    c.turned = takes ? p.op == kCompositeDifference : c.turned;
  }
  return c;
}

float composite_bound(vec3 q, vec4 rel, vec2 hz) { return composite_at(q, vec3(0.0), rel, hz, false).bound; }

// From outside (bound > 0): (bound, ahead, back); inside (bound <= 0): the
// bound alone (object_clearances then takes composite_inside_clearances).
vec3 composite_bound_clearances(vec3 q, vec3 u, vec4 rel, vec2 hz) {
  const CompositeAt c = composite_at(q, u, rel, hz, true);
  return c.bound > 0.0 ? vec3(c.bound, c.reach) : vec3(c.bound);
}

vec3 composite_normal_of(CompositeAt c, vec3 q, vec3 from) {
  const CompositePart p = composite_part(c.part);
  const vec3 n = kind_normal(p.type, q, p.rel, p.heading, p.radius, from);
  return c.turned ? -n : n;
}

// From inside (the depth d = -bound given): (d, ahead, back, the depth's rate along u).
vec4 composite_inside_clearances(vec3 q, vec3 u, vec4 rel, vec2 hz, float d) {
  const CompositeAt c = composite_at(q, u, rel, hz, true);
  const vec2 s = c.bound < 0.0 ? c.leave : vec2(0.0);
  return vec4(d, max(vec2(d), s), -dot(composite_normal_of(c, q, q), u));
}

vec3 composite_normal(vec3 q, vec4 rel, vec3 from) {
  return composite_normal_of(composite_at(q, vec3(0.0), rel, half_exp(q.z), false), q, from);
}

vec2 composite_pattern_uv(vec3 q, vec3 phase, vec4 rel) {
  const CompositePart p = composite_part(composite_at(q, vec3(0.0), rel, half_exp(q.z), false).part);
  return kind_pattern_uv(p.type, q, phase, p.rel, p.heading, p.radius);
}

#endif  // SOL_MARCH_COMPOSITES_GLSL
