// Balls in the kernels (libsol: sol/objects/ball.hpp): drawn with their
// distance bound (ball) or as the true geodesic sphere (exact_ball, which
// the march approaches by the same bound and finishes by its exact distance
// within kExactShell: march/exact_balls.glsl). A ball's record: rel =
// (centre, 0), radius; a quotient image's bound (centre, radius).
#ifndef SOL_KINDS_BALL_GLSL
#define SOL_KINDS_BALL_GLSL

// A ball's bound (sol::ball_terms): the terms d_xz - r, d_yz - r with
// S = sinh(d/2), d' = (S²)'/(S √(1 + S²)). Returns (distance bound,
// clearance along u, clearance back along -u). The half exponentials of q.z (`hz`) and c.z (`hc`) come from
// the caller (the quotient march takes q's once a step for all its
// candidates, and each candidate's centre's; the Sol march keeps each
// ball's per ray): no exponential and no division here but the slopes'.
vec3 ball_bound_clearances(vec3 q, vec3 u, vec3 c, float radius, vec2 hz, vec2 hc) {
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

// Seen from inside the bound's ball (sol::ball_inside_terms): the faces r
// - d_xz and r - d_yz, d the projections' distances to the centre's, each
// with bend coth(d/2) for steps of at most d/2. Returns (least g, ahead,
// back, the nearest face's rate).
vec4 ball_inside_clearances(vec3 q, vec3 u, vec3 c, float radius, vec2 hz, vec2 hc) {
  const float dx = q.x - c.x, dy = q.y - c.y;
  const vec2 e = hz * hc, ec = hc * hc;
  const float e2 = e.x * e.x, ie2 = e.y * e.y;
  const float sh = 0.5 * (hz.x * hc.y - hz.y * hc.x), sh2 = sh * sh, half_sinh_dz = sh * sqrt(1.0 + sh2);
  const vec2 s2 = vec2(sh2 + 0.25 * dx * dx * ie2, sh2 + 0.25 * dy * dy * e2);
  const vec2 rate = vec2(half_sinh_dz * u.z + 0.5 * dx * u.x * ec.y - 0.25 * dx * dx * ie2 * u.z,
                         half_sinh_dz * u.z + 0.5 * dy * u.y * ec.x + 0.25 * dy * dy * e2 * u.z);
  const vec2 s = sqrt(s2), root = sqrt(1.0 + s2);
  const vec2 d = 2.0 * log(s + root);  // the projections' distances
  const vec2 slope = rate / max(s * root, 1e-30);
  // coth(d/2) = √(1 + S²)/S with S = sinh(d/2) = s.
  const vec2 bend = root / max(s, 1e-30);
  vec4 least = vec4(1e30, 1e30, 1e30, 0.0);
  inside_least(least, vec2(radius - d.x, -slope.x), bend.x, 0.5 * d.x);
  inside_least(least, vec2(radius - d.y, -slope.y), bend.y, 0.5 * d.y);
  return least;
}

// ---- ball: sol::sdf_ball, the distance lower bound to the centre less the radius

float ball_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return distance_lower_bound(q, rel.xyz, hz, hc) - radius;
}
SOL_SOLID_NORMAL(ball)

vec3 ball_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return ball_bound_clearances(q, u, rel.xyz, radius, hz, hc);
}

vec3 ball_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
  return ball_bound_clearances(q, u, b.xyz, b.w, hz, half_exp(b.z));
}

// The bound's gradient by central differences (as the CPU reference).
vec3 ball_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return ball_solid_normal(q, rel, heading, radius);
}

// With w = centre⁻¹·q, (4/π)(longitude atan2(w_y, w_x), latitude atan2(w_z, |w_xy|)).
vec2 ball_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  return sol_ball_pattern_uv(solid_relative(q, rel));  // sol/patterns.h
}

// Seen from the eye at p (sol::Ball::seen_from): its centre p⁻¹·c.
void ball_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  rel.xyz = seen_point(rel.xyz, camera, camera_frac);
}

// ---- exact_ball: approached as a ball; its exact distance, normal and
// clearance near the sphere are march/exact_balls.glsl's

// Seen from inside (sol::sdf_ball_exact's sign; HAS_INSIDE, a frame whose
// eye is inside a solid: no ray that starts outside every solid gets
// inside one, it meets the surface first): where q lies inside for
// certain, the sphere is at least r - L away, L the length of any curve
// from the centre c to q, which bounds the distance from above. The curve:
// the straight coordinate segment from c to q, in c's frame w = c⁻¹·q,
// w(s) = s w for s in [0, 1], whose length in the metric e^{-2z} dx² +
// e^{2z} dy² + dz² is ∫ √(e^{-2 s w_z} w_x² + e^{2 s w_z} w_y² + w_z²) ds
// <= √(w_x² E(-2 w_z) + w_y² E(2 w_z) + w_z²) (Cauchy-Schwarz), E(a) =
// (e^a - 1)/a the mean of e^{s a}. Returns
// r - that bound: positive only inside for certain, else <= 0 (then the
// bound outside, or the exact solve near the sphere, decides).
float exact_ball_inside(vec3 q, vec4 rel, float radius, vec2 hz, vec2 hc) {
  const vec2 e = hz * hc.yx;  // e^{±(q.z - c.z)/2}
  const float wz = q.z - rel.z, a = 2.0 * wz;
  const float up = e.x * e.x * e.x * e.x, down = e.y * e.y * e.y * e.y;  // e^{±2 w_z}
  const float mean_up = abs(a) < 1e-3 ? 1.0 + 0.5 * a : (up - 1.0) / a;
  const float mean_down = abs(a) < 1e-3 ? 1.0 - 0.5 * a : (1.0 - down) / a;
  const vec2 hc2 = hc * hc;  // e^{±c.z}
  const float wx = (q.x - rel.x) * hc2.y, wy = (q.y - rel.y) * hc2.x;
  return radius - sqrt(wx * wx * mean_down + wy * wy * mean_up + wz * wz);
}

float exact_ball_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  float d = ball_distance(q, rel, heading, radius, hz, hc);
  if (HAS_INSIDE && d < 0.0) {
    const float inside = exact_ball_inside(q, rel, radius, hz, hc);
    if (inside > 0.0) d = inside;
  }
  return d;
}
SOL_SOLID_NORMAL(exact_ball)

// (Inside for certain: no clearance, the distance alone.)
vec3 exact_ball_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  vec3 c = ball_clearances(q, u, rel, heading, radius, hz, hc);
  if (HAS_INSIDE && c.x < 0.0) {
    const float inside = exact_ball_inside(q, rel, radius, hz, hc);
    if (inside > 0.0) c = vec3(inside);
  }
  return c;
}

vec3 exact_ball_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  vec3 c = ball_record_clearances(q, u, m, hz);
  if (HAS_INSIDE && c.x < 0.0) {
    const float inside = exact_ball_inside(q, vec4(m.bound.xyz, 0.0), m.bound.w, hz, half_exp(m.bound.z));
    if (inside > 0.0) c = vec3(inside);
  }
  return c;
}

// Where the march's last exact solve did not reach this ball: the bound's.
vec3 exact_ball_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return exact_ball_solid_normal(q, rel, heading, radius);
}

vec2 exact_ball_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) {
  return ball_pattern_uv(q, phase, rel, heading, radius);
}

void exact_ball_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  ball_seen_from(rel, heading, camera, camera_frac);
}

#endif  // SOL_KINDS_BALL_GLSL
