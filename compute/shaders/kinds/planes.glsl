// The planes x = c, y = c and z = c in the kernels (libsol: sol/objects/planes.hpp).
// Each kind's functions, as compute/shaders/kinds/kinds.glsl lists them;
// a plane's record holds c in its first word (rel, and a quotient image's
// bound: (c, 0, 0, 0)).
#ifndef SOL_KINDS_PLANES_GLSL
#define SOL_KINDS_PLANES_GLSL

// ---- plane_x: asinh(|x - c| e^{-z}), a totally geodesic hyperbolic plane

float plane_x_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return asinh(abs(q.x - rel.x) * hz.y * hz.y);
}

// (The march solves its crossing instead, plane_roots.glsl: its distance alone.)
vec3 plane_x_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return vec3(plane_x_distance(q, rel, heading, radius, hz, hc));
}

vec3 plane_x_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
  return plane_x_clearances(q, u, b, vec2(0.0), 0.0, hz, vec2(1.0));
}

// The unit gradient of the distance at the hit q, facing the side of
// `from`, the ray's (segment's) start: the march stops within hit_epsilon,
// possibly just across the plane. Mirrors sol::PlaneX::normal.
vec3 plane_x_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  const float c = rel.x;
  float side = from.x >= c ? 1.0 : -1.0;
  float w = abs(q.x - c) * exp(-q.z), r = inversesqrt(1.0 + w * w);
  return vec3(side * r, 0.0, -w * r);
}

// Its own coordinates (y, z) of the world point (`phase`: modulo 2).
vec2 plane_x_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) { return phase.yz; }

// Seen from the eye at p (sol::PlaneX::seen_from): c -> e^{-p_z} (c - p_x).
void plane_x_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  rel.x = (rel.x - camera.x) * camera_frac.w;
}

// ---- plane_y: asinh(|y - c| e^{z})

float plane_y_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return asinh(abs(q.y - rel.x) * hz.x * hz.x);
}

vec3 plane_y_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  return vec3(plane_y_distance(q, rel, heading, radius, hz, hc));
}

vec3 plane_y_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
  return plane_y_clearances(q, u, b, vec2(0.0), 0.0, hz, vec2(1.0));
}

vec3 plane_y_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  const float c = rel.x;
  float side = from.y >= c ? 1.0 : -1.0;
  float w = abs(q.y - c) * exp(q.z), r = inversesqrt(1.0 + w * w);
  return vec3(0.0, side * r, w * r);
}

vec2 plane_y_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) { return phase.xz; }

// c -> e^{p_z} (c - p_y).
void plane_y_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) {
  rel.x = (rel.x - camera.y) * camera.w;
}

// How far a ray stays more than hit_epsilon from the plane x = c or y = c
// (`type`): the first root of its distance asinh|G| - hit_epsilon, which
// bends by at most 1 along a geodesic (as a tube's slab about such a
// plane, sol::tube_terms), G = (x - c) e^{-z} (rate u_x - G u_z) or
// (y - c) e^{z} (rate u_y + G u_z): the march's step where the plane is the
// nearest object and its crossing is not solved (a ray other than a
// camera ray: one arriving at a grazing angle crawled by the distance).
float plane_xy_step(vec3 q, vec3 u, int type, float c, float hit_epsilon) {
  const bool across_x = type == kObjectPlaneX;
  const float G = across_x ? (q.x - c) * exp(-q.z) : (q.y - c) * exp(q.z);
  const float rate = across_x ? u.x - G * u.z : u.y + G * u.z;
  const float root = sqrt(1.0 + G * G);
  return clearance_roots(log(abs(G) + root) - hit_epsilon, (G >= 0.0 ? rate : -rate) / root).x;
}

// ---- plane_z: |z - c|, flat

float plane_z_distance(vec3 q, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) { return abs(q.z - rel.x); }

// Its one term |z - c| bends by at most 1 along a geodesic (z'' = u2² - u1²):
// clearance_roots of it, ahead and back.
vec3 plane_z_clearances(vec3 q, vec3 u, vec4 rel, vec2 heading, float radius, vec2 hz, vec2 hc) {
  const float d = plane_z_distance(q, rel, heading, radius, hz, hc);
  const float rate = q.z >= rel.x ? u.z : -u.z;
  return vec3(d, max(vec2(d), clearance_roots(d, rate)));
}

// How far the ray stays more than hit_epsilon from the plane z = c: the
// first root of |z - c| - hit_epsilon (sol::plane_z_step), the march's step
// where the plane is the nearest object.
float plane_z_step(vec3 q, vec3 u, float c, float hit_epsilon) {
  return clearance_roots(abs(q.z - c) - hit_epsilon, q.z >= c ? u.z : -u.z).x;
}

// plane_z_step where only |u_z| (`speed`) is known: the ray taken as
// heading for the plane, so a safe step whichever way it goes (one
// passing a plane near the top or the bottom of its climb, u_z ≈ 0, steps
// about √(2 (|z - c| - hit_epsilon)) rather than |z - c|).
float plane_z_step_heading(float d, float speed, float hit_epsilon) { return clearance_roots(d - hit_epsilon, -speed).x; }

vec3 plane_z_record_clearances(vec3 q, vec3 u, Image m, vec2 hz) {
  const vec4 b = m.bound;
  return plane_z_clearances(q, u, b, vec2(0.0), 0.0, hz, vec2(1.0));
}

vec3 plane_z_normal(vec3 q, vec4 rel, vec2 heading, float radius, vec3 from) {
  return vec3(0.0, 0.0, from.z >= rel.x ? 1.0 : -1.0);
}

vec2 plane_z_pattern_uv(vec3 q, vec3 phase, vec4 rel, vec2 heading, float radius) { return phase.xy; }

// c -> c - p_z.
void plane_z_seen_from(inout vec4 rel, inout vec2 heading, vec4 camera, vec4 camera_frac) { rel.x -= camera.z; }

#endif  // SOL_KINDS_PLANES_GLSL
