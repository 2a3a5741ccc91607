// Boxes in the kernels (libsol: sol/objects/box.hpp): center · ([-a, a] x
// [-b, b] x [-c, c]), the coordinate box [x0 ± A] x [y0 ± B] x [z0 ± c] with
// A = a e^{z0}, B = b e^{-z0}. Its bound is the largest of the signed exact
// distances to its three slabs, asinh(s_x e^{-z}), asinh(s_y e^{z}) and
// s_z (s = |Δ| - half width), each the distance to a plane where positive,
// which bends by at most 1 (sol/clearance.hpp). A box's record: rel =
// (centre, c), heading = (A, B) in the record's coordinates (from double),
// radius 0; a quotient image's bound (centre, c), its heading word (A, B).
#ifndef SOL_KINDS_BOX_GLSL
#define SOL_KINDS_BOX_GLSL

// The bound's terms at q about `center` with half widths (A, B, c): (the
// bound, its clearance along u, its clearance back along -u).
vec3 box_bound_clearances(vec3 q, vec3 u, vec3 center, vec3 half_width, vec2 hz) {
  const vec3 d = q - center;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;  // e^{±q.z}
  const vec2 w = vec2((abs(d.x) - half_width.x) * iez, (abs(d.y) - half_width.y) * ez);
  const vec2 root = sqrt(1.0 + w * w);  // shared by asinh w and its slope
  const vec2 hw = sign(w) * log(abs(w) + root);  // asinh w, odd: no cancellation inside the slab
  const vec2 sw = vec2((d.x >= 0.0 ? u.x : -u.x) - w.x * u.z, (d.y >= 0.0 ? u.y : -u.y) + w.y * u.z) / root;
  const float hz_term = abs(d.z) - half_width.z, sz = d.z >= 0.0 ? u.z : -u.z;
  const float distance = max(max(hw.x, hw.y), hz_term);
  return vec3(distance, max(vec2(distance), max(max(clearance_roots(hw.x, sw.x), clearance_roots(hw.y, sw.y)),
                                                  clearance_roots(hz_term, sz))));
}

// Seen from inside (sol::Box::inside_terms): its six faces, each a plane's
// signed distance, bend 1. Returns (least g, ahead, back, the nearest
// face's rate).
vec4 box_inside_clearances(vec3 q, vec3 u, vec3 center, vec3 half_width, vec2 hz) {
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;
  vec4 least = vec4(1e30, 1e30, 1e30, 0.0);
  inside_least(least, face_x(q, u, center.x + half_width.x, -1.0, iez), 1.0, 1e30);
  inside_least(least, face_x(q, u, center.x - half_width.x, 1.0, iez), 1.0, 1e30);
  inside_least(least, face_y(q, u, center.y + half_width.y, -1.0, ez), 1.0, 1e30);
  inside_least(least, face_y(q, u, center.y - half_width.y, 1.0, ez), 1.0, 1e30);
  inside_least(least, vec2(center.z + half_width.z - q.z, -u.z), 1.0, 1e30);
  inside_least(least, vec2(q.z - center.z + half_width.z, u.z), 1.0, 1e30);
  return least;
}

float box_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return box_bound_clearances(q, vec3(0.0), rel.xyz, vec3(heading, rel.w), hz).x;
}
SOL_SOLID_NORMAL(box)

vec3 box_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return box_bound_clearances(q, u, rel.xyz, vec3(heading, rel.w), hz);
}

vec3 box_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  return box_bound_clearances(q, u, m.bound.xyz, vec3(m.heading.xy, m.bound.w), hz);
}

// The bound's gradient by central differences (as the CPU reference).
vec3 box_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return box_solid_normal(q, rel, heading, radius);
}

// On the face nearest q (the slab whose term is largest, in the box's own
// frame w = centre⁻¹·q, where its half widths are a, b, c), the two
// coordinates of w along it, in cells of half the smallest half size.
vec2 box_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  const vec3 half_size = vec3(heading.x * exp(-rel.z), heading.y * exp(rel.z), rel.w);
  return sol_box_pattern_uv(solid_relative(q, rel), half_size);  // sol/patterns.h
}

// Seen from the eye at p (sol::Box::seen_from): its centre p⁻¹·c; its
// coordinate half widths (a e^{c_z}, b e^{-c_z}) with c_z - p_z for c_z.
void box_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  rel.xyz = seen_point(rel.xyz, camera, camera_frac);
  heading *= vec2(camera_frac.w, camera.w);
}

#endif  // SOL_KINDS_BOX_GLSL
