// Tubes in the kernels (libsol: sol/objects/tube.hpp): the points within
// a radius of a vertical line or of a horizontal one along a unit
// coordinate direction h. A tube's record: rel = (point of the axis, axis
// code: kTubeVertical or not), heading = h, radius; a quotient image's
// bound the four words of tube_record_clearances.
#ifndef SOL_KINDS_TUBE_GLSL
#define SOL_KINDS_TUBE_GLSL

// Tubes: the bounds of sol::sdf_tube (axis z: the two coordinate planes
// containing it) and sol::sdf_tube_horizontal (a horizontal line along the
// unit coordinate direction h: max(|Δz|, asinh(|h_y Δx - h_x Δy| / (|h_x| e^{-z} + |h_y| e^{z})))).
float tube_bound(vec3 q, vec3 through, int axis, vec2 h, float radius, vec2 hz) {
  const vec3 d = q - through;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;
  if (axis == kTubeVertical) return max(asinh(abs(d.x) * iez), asinh(abs(d.y) * ez)) - radius;
  const float across = abs(h.y * d.x - h.x * d.y) / (abs(h.x) * iez + abs(h.y) * ez);
  return max(asinh(across), abs(d.z)) - radius;
}

// A tube's bound (sol::tube_terms): vertical, the slabs around x = x0 and
// y = y0; horizontal along h, the z slab and the across term asinh|G|,
// G = (h_y Δx - h_x Δy)/(|h_x| e^{-z} + |h_y| e^{z}) (a slab's along x or
// y); every term bends by at most 1. Returns (distance bound, clearance
// along u, clearance back along -u).
vec3 tube_bound_clearances(vec3 q, vec3 u, vec3 through, int axis, vec2 h, float radius, vec2 hz) {
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
vec3 tube_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
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

// Seen from inside (sol::tube_inside_terms): vertical, the faces of the
// slabs about x = x0 and y = y0 (bend 1); horizontal along h, the faces of
// the across term asinh G (bend 1 along x or y, where it is a plane's
// distance; else no established bound: g alone) and of |Δz| (bend 1).
// `G` and its rate as tube_bound_clearances computes them.
vec4 tube_faces_inside(vec3 q, vec3 u, bool vertical, vec2 G, vec2 sigma_y, float dz, float radius, float across_bend) {
  vec4 least = vec4(1e30, 1e30, 1e30, 0.0);
  const float root = sqrt(1.0 + G.x * G.x);
  inside_slab(least, vec2(sign(G.x) * log(abs(G.x) + root), G.y / root), radius, vertical ? 1.0 : across_bend);
  inside_slab(least, vertical ? sigma_y : vec2(dz, u.z), radius, 1.0);
  return least;
}

vec4 tube_inside_clearances(vec3 q, vec3 u, vec3 through, bool vertical, vec2 h, float radius, vec2 hz) {
  const vec3 d = q - through;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;
  // Vertical: G = Δx e^{-z} (the slab about x = x0 as an across term with h = (0, 1)).
  const vec2 hh = vertical ? vec2(0.0, 1.0) : h;
  const float inv_D = 1.0 / (abs(hh.x) * iez + abs(hh.y) * ez);
  const float G = (hh.y * d.x - hh.x * d.y) * inv_D;
  const float rate_G = ((hh.y * ez * u.x - hh.x * iez * u.y) - G * (abs(hh.y) * ez - abs(hh.x) * iez) * u.z) * inv_D;
  return tube_faces_inside(q, u, vertical, vec2(G, rate_G), face_y(q, u, through.y, 1.0, ez), d.z, radius,
                           h.x == 0.0 || h.y == 0.0 ? 1.0 : 1e30);
}

// The same from a quotient image's record (tube_record_clearances' words).
vec4 tube_record_inside_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
  const bool vertical = b.x < 0.0;
  const float ez = hz.x * hz.x, iez = hz.y * hz.y;
  const float hx = vertical ? 0.0 : b.x, hy = vertical ? 1.0 : b.y, c = vertical ? b.y : b.z;
  const float radius = vertical ? -b.x : b.x + abs(b.y);
  const float inv_D = 1.0 / (hx * iez + abs(hy) * ez);
  const float G = (hy * q.x - hx * q.y - c) * inv_D;
  const float rate_G = ((hy * ez * u.x - hx * iez * u.y) - G * (abs(hy) * ez - hx * iez) * u.z) * inv_D;
  return tube_faces_inside(q, u, vertical, vec2(G, rate_G), face_y(q, u, b.z, 1.0, ez), q.z - b.w, radius,
                           hx == 0.0 || hy == 0.0 ? 1.0 : 1e30);
}

float tube_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return tube_bound(q, rel.xyz, int(rel.w), heading, radius, hz);
}
SOL_SOLID_NORMAL(tube)

vec3 tube_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return tube_bound_clearances(q, u, rel.xyz, int(rel.w), heading, radius, hz);
}

// The bound's gradient by central differences (as the CPU reference).
vec3 tube_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return tube_solid_normal(q, rel, heading, radius);
}

// With w = through⁻¹·q, (4/π)(angle around the axis, coordinate along it / radius).
vec2 tube_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  const float ez = exp(rel.z);
  const bool vertical = int(rel.w) == kTubeVertical;
  const vec2 h = vertical ? vec2(0.0) : normalize(vec2(heading.x / ez, heading.y * ez));
  return sol_tube_pattern_uv(solid_relative(q, rel), vertical, h, radius);  // sol/patterns.h
}

// Seen from the eye at p (sol::Tube::seen_from): its axis point p⁻¹·a, a
// horizontal axis's direction (h_x, h_y) scaled to (e^{-p_z} h_x, e^{p_z} h_y), a unit vector again.
void tube_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  rel.xyz = seen_point(rel.xyz, camera, camera_frac);
  if (int(rel.w) != kTubeVertical) heading = normalize(heading * vec2(camera_frac.w, camera.w));
}

#endif  // SOL_KINDS_TUBE_GLSL
