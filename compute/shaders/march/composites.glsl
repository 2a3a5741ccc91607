// Composites (kObjectComposite; sol::Composite, libsol/src/objects/composite.cpp,
// the double reference): the union, intersection or difference of two
// solids A and B of the list's kinds. Every solid's bound is 1-Lipschitz
// and <= 0 exactly on the solid, so min(d_A, d_B), max(d_A, d_B) and
// max(d_A, -d_B) are such bounds of the composed sets: the march steps by
// them on either side. The clearances, the normal and the pattern are
// the parts': those of the part whose term is the bound at the point (the
// active part; B's normal turned in a difference). A composite's record
// is (its first part's index in the parts' buffer, its operation): the
// parts are read there (binding kBindingParts, world coordinates) and, in
// Sol, seen from the eye as a crowd's objects are.
#ifndef SOL_MARCH_COMPOSITES_GLSL
#define SOL_MARCH_COMPOSITES_GLSL

layout(std430, set = 0, binding = kBindingParts) readonly buffer CompositeParts {
  Part composite_parts[];
};

// A part as the march sees it: its kind's record in the coordinates of q.
struct CompositePart {
  int type;
  vec4 rel;
  vec2 heading;
  float radius;
  vec2 hc;  // rel.z's half exponentials
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
  return c;
}

// The parts at q: their bounds, the composite's, and which is active.
struct CompositeAt {
  CompositePart a, b;
  float da, db, bound;
  bool active_b;  // B's term is the bound
  bool turned;    // ... negated (a difference's)
};

CompositeAt composite_at(vec3 q, vec4 rel, vec2 hz) {
  CompositeAt c;
  const int first = int(rel.x), op = int(rel.y);
  c.a = composite_part(first);
  c.b = composite_part(first + 1);
  c.da = kind_bound(c.a.type, q, c.a.rel, c.a.heading, c.a.radius, hz, c.a.hc);
  c.db = kind_bound(c.b.type, q, c.b.rel, c.b.heading, c.b.radius, hz, c.b.hc);
  const float b = op == kCompositeDifference ? -c.db : c.db;
  c.active_b = op == kCompositeUnion ? b < c.da : b > c.da;
  c.bound = op == kCompositeUnion ? min(c.da, b) : max(c.da, b);
  c.turned = op == kCompositeDifference && c.active_b;
  return c;
}

float composite_bound(vec3 q, vec4 rel, vec2 hz) { return composite_at(q, rel, hz).bound; }

// How far the ray goes (ahead, back) before it can reach part p, q outside
// it (bound d > 0), or leave it, q inside (d < 0): its clearances from
// outside or inside, at least |d|.
vec2 part_reaching(CompositePart p, vec3 q, vec3 u, vec2 hz, float d) {
  return max(vec2(d), kind_bound_clearances(p.type, q, u, p.rel, p.heading, p.radius, hz, p.hc).yz);
}

vec2 part_leaving(CompositePart p, vec3 q, vec3 u, vec2 hz, float d) {
  return max(vec2(-d), kind_inside_clearances(p.type, q, u, p.rel, p.heading, p.radius, hz, p.hc, -d).yz);
}

// From outside (bound > 0): (bound, ahead, back). A union is reached no
// sooner than its nearer part; an intersection than each part q is
// outside of; a difference than A (q outside A) and than the ray leaves B
// (q inside B). Inside (bound <= 0): the bound alone (object_clearances
// then takes composite_inside_clearances).
vec3 composite_bound_clearances(vec3 q, vec3 u, vec4 rel, vec2 hz) {
  const CompositeAt c = composite_at(q, rel, hz);
  const int op = int(rel.y);
  if (c.bound <= 0.0) return vec3(c.bound);
  vec2 s = vec2(c.bound);
  if (op == kCompositeUnion) {
    s = min(part_reaching(c.a, q, u, hz, c.da), part_reaching(c.b, q, u, hz, c.db));
  } else {
    if (c.da > 0.0) s = max(s, part_reaching(c.a, q, u, hz, c.da));
    if (op == kCompositeIntersection && c.db > 0.0) s = max(s, part_reaching(c.b, q, u, hz, c.db));
    if (op == kCompositeDifference && c.db < 0.0) s = max(s, part_leaving(c.b, q, u, hz, c.db));
  }
  return vec3(c.bound, s);
}

vec3 composite_normal_of(CompositeAt c, vec3 q, vec3 from) {
  const CompositePart p = c.active_b ? c.b : c.a;
  const vec3 n = kind_normal(p.type, q, p.rel, p.heading, p.radius, from);
  return c.turned ? -n : n;
}

// From inside (the depth d = -bound given): (d, ahead, back, the depth's
// rate along u). A union is left no sooner than each part q is inside of;
// an intersection than the first part is left; a difference than the
// first of leaving A and reaching B.
vec4 composite_inside_clearances(vec3 q, vec3 u, vec4 rel, vec2 hz, float d) {
  const CompositeAt c = composite_at(q, rel, hz);
  const int op = int(rel.y);
  vec2 s = vec2(max(-c.bound, 0.0));
  if (c.bound < 0.0) {
    if (op == kCompositeUnion) {
      if (c.da < 0.0) s = max(s, part_leaving(c.a, q, u, hz, c.da));
      if (c.db < 0.0) s = max(s, part_leaving(c.b, q, u, hz, c.db));
    } else if (op == kCompositeIntersection) {
      s = max(s, min(part_leaving(c.a, q, u, hz, c.da), part_leaving(c.b, q, u, hz, c.db)));
    } else {
      s = max(s, min(part_leaving(c.a, q, u, hz, c.da), part_reaching(c.b, q, u, hz, c.db)));
    }
  }
  return vec4(d, max(vec2(d), s), -dot(composite_normal_of(c, q, q), u));
}

vec3 composite_normal(vec3 q, vec4 rel, vec3 from) { return composite_normal_of(composite_at(q, rel, half_exp(q.z)), q, from); }

vec2 composite_pattern_uv(vec3 q, vec3 phase, vec4 rel) {
  const CompositeAt c = composite_at(q, rel, half_exp(q.z));
  const CompositePart p = c.active_b ? c.b : c.a;
  return kind_pattern_uv(p.type, q, phase, p.rel, p.heading, p.radius);
}

#endif  // SOL_MARCH_COMPOSITES_GLSL
