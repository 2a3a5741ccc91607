// The objects as the march sees them, in float: distances (exact for planes,
// the lower bound of sol/distance.hpp for balls and tubes), clearances
// along a ray (sol/clearance.hpp), normals, pattern coordinates and the
// gaps of cutout planes. The GLSL twin of libsol's objects.cpp; the
// kernel's codes and constants come from sol/kernel_constants.h.
#ifndef SOL_MARCH_OBJECTS_GLSL
#define SOL_MARCH_OBJECTS_GLSL

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

// ---- The objects of a world in Sol, relative to one eye (its uniforms
// copied once: lavapipe does not hoist uniform loads out of loops).

int g_count;
int g_types[kMaxGpuObjects];
float g_constants[kMaxGpuObjects];  // planes: c
float g_radii[kMaxGpuObjects];
vec4 g_relative[kMaxGpuObjects];
vec2 g_headings[kMaxGpuObjects];
int g_cutouts[kMaxGpuObjects];      // cutout planes z = c: their pattern code; else kPatternNone
vec2 g_half_exp_z[kMaxGpuObjects];  // balls: the centre's half exponentials (half_exp)
vec4 g_eye_camera, g_eye_frac;
float g_rk4_step;  // RK4's substep (INTEGRATOR = 1)

void load_objects(int eye) {
  g_count = min(params.counts.x, kMaxGpuObjects);
  for (int k = 0; k < kMaxGpuObjects; ++k) {
    g_types[k] = int(params.objects[k].plane.x);
    g_cutouts[k] = HAS_CUTOUT && g_types[k] == kObjectPlaneZ && params.objects[k].plane.w != 0.0
                       ? int(params.objects[k].plane.z)
                       : 0;
    g_radii[k] = params.objects[k].plane.y;
    g_relative[k] = params.eyes[eye].relative[k];
    g_headings[k] = params.eyes[eye].heading[k].xy;
    g_constants[k] = g_relative[k].x;
    g_half_exp_z[k] = HAS_BALLS ? half_exp(g_relative[k].z) : vec2(1.0);
  }
  g_eye_camera = params.eyes[eye].camera;
  g_eye_frac = params.eyes[eye].camera_frac;
  g_rk4_step = params.eyes[eye].forward.w;
}

#endif  // SOL_MARCH_OBJECTS_GLSL
