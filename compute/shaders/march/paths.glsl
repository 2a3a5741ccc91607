// Path tracing (PATH_TRACING; path_radiance in libsol/src/render.cpp, the
// same estimator with the same random numbers): one path per pixel and
// dispatch, from the camera ray's hit, in the shade pass (the march pass
// lists the hits), so that the camera rays' pipelines never hold a path's
// march nor its connection solves. docs/lighting.md, "Path tracing".
#ifndef SOL_MARCH_PATHS_GLSL
#define SOL_MARCH_PATHS_GLSL

// A direction about the unit normal n with density cos θ / π, in frame
// components (as the CPU's cosine_direction: the same basis, the same two numbers).
vec3 cosine_direction(vec3 n, inout uvec2 state) {
  const float sign = n.z >= 0.0 ? 1.0 : -1.0;
  const float a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  const vec3 t = vec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  const vec3 b = vec3(c, sign + n.y * n.y * a, -n.y);
  const float r = sqrt(path_uniform(state)), phi = 2.0 * SOL_PI * path_uniform(state);
  const float x = r * cos(phi), y = r * sin(phi);
  return normalize(x * t + y * b + sqrt(max(0.0, 1.0 - x * x - y * y)) * n);
}

// ---- Next-event estimation to glowing exact balls (glow_sample and
// glow_density in libsol/src/render.cpp, with the same numbers): a target
// (in Sol a glowing ball, in a quotient one of its images around D) picked
// by glow_pick_weight at x, a point y = c·exp(r w) of its sphere, w uniform
// on S² (area density 1 / (4π J_c(w, r))), connected to the diffuse point x
// by its geodesics up to the distance plus the ball's glow_reach
// (scene_objects[k].glow.x; sol_connections, 0: the minimisers), each
// weighed by its own J (sol_sphere_area_density) and counted where the
// march along it first meets that ball at its length; combined with
// reflection sampling by the balance heuristic.
const bool GLOW_SAMPLING = HAS_EMISSION && HAS_EXACT_BALLS;

// Scene object k (from the uniforms: a quotient's march loads no g_types).
bool glowing(int k) {
  return int(scene_objects[k].plane.x) == kObjectExactBall && scene_objects[k].material.rgb != vec3(0.0);
}

// The targets: Sol's objects, or the quotient's images.
int glow_target_slots() { return QUOTIENT ? params.counts.x : g_count; }

// Target i: whether it is one, and its scene object, centre (march
// coordinates) and radius.
bool glow_target(int i, out int object, out vec3 centre, out float radius) {
  if (QUOTIENT) {
    const Image m = images[i];
    object = int(m.info.z);
    centre = m.geometry.xyz;
    radius = m.info.y;
    return image_type(m) == kObjectExactBall && scene_objects[object].material.rgb != vec3(0.0);
  }
  object = i;
  centre = g_relative[i].xyz;
  radius = g_radii[i];
  return glowing(i);
}

int glowing_count() {
  int n = 0, object;
  vec3 centre;
  float radius;
  for (int i = 0; i < glow_target_slots(); ++i) n += glow_target(i, object, centre, radius) ? 1 : 0;
  return n;
}

// The geodesic from q to p (march coordinates) as the connection solver
// takes it: p seen from q, in frame components at q.
vec3 seen_from(vec3 q, vec3 p) {
  const vec3 d = p - q;
  return vec3(exp(-q.z) * d.x, exp(q.z) * d.y, d.z);
}

// The weight with which x picks a target of centre c and radius r, about
// its solid angle: r² / (r² + |x⁻¹c|²) (glow_pick_weight).
float glow_pick_weight(vec3 x, vec3 c, float r) {
  const vec3 v = seen_from(x, c);
  return r * r / (r * r + dot(v, v));
}

float glow_pick_total(vec3 x) {
  float total = 0.0, radius;
  int object;
  vec3 centre;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (glow_target(i, object, centre, radius)) total += glow_pick_weight(x, centre, radius);
  }
  return total;
}

// The density in solid angle at x with which glow_sample picks direction d
// whose geodesic first meets the glowing scene object k after L, at y on
// the sphere of one of its targets (the nearest; in Sol the hit point, in
// a quotient x exp(L d) in the cover; cos_y: the cosine there with its
// normal): 0 where none holds y, or where that geodesic is longer than the
// distance plus the ball's reach. Its two connection solves (x to y, and
// the target's centre c to y) are path_radiance's (kSolveDensity*), between
// glow_density_target, which finds y, c and r (false: no target holds y),
// and glow_density_of, which takes the second solve's minimiser. Both are
// often known without a solve (glow_density_known): the geodesic from x
// is the minimiser where it is shorter than its period (`minimiser`), and
// the march that met the sphere solved the geodesic from its centre to
// the hit (`from_centre`: its unit direction and length; w = 0: unknown).
struct GlowDensity {
  int k;
  vec3 x, d, y, c;
  float L, r, cos_y;
  bool minimiser;
  vec4 from_centre;
};

// What the march that met the ball at h already shows (GlowDensity's
// `minimiser` and `from_centre`): a geodesic of length L shorter than its
// period by the float margin is the unique minimiser (Coiculescu–Schwartz;
// sol_connections' certificate), whatever the reach; and the march's last
// exact solve, where it is the hit's and lands on the sphere (its length
// the radius within the density's tolerance below), is the minimiser from
// the centre: in a quotient from the image the march met, whose frame may
// be turned by Γ (a half turn, under which J is unchanged).
void glow_density_known(MarchHit h, inout GlowDensity q) {
  q.minimiser = q.L < (1.0 - kMinimiserMargin) * sol_cut_time(q.d);
  const float len = length(h.exact_v);
  const bool solved = h.exact_k >= 0 && h.exact_k == h.k && abs(len - q.r) <= 1e-3 * max(1.0, q.r);
  q.from_centre = solved ? vec4(h.exact_v / len, len) : vec4(0.0);
}

bool glow_density_target(int k, vec3 x, vec3 d, float L, vec3 hit, float cos_y, out GlowDensity q) {
  q.k = k;
  q.x = x;
  q.d = d;
  q.L = L;
  q.cos_y = cos_y;
  q.minimiser = false;
  q.from_centre = vec4(0.0);
  q.y = QUOTIENT ? sol_translate(x, sol_spread(d, L).position) : hit;
  q.c = vec3(0.0);
  q.r = 0.0;
  vec3 centre;
  float radius, nearest = 1e30;
  int object;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (!glow_target(i, object, centre, radius) || object != k) continue;
    const vec3 v = seen_from(centre, q.y);
    if (dot(v, v) < nearest) {
      nearest = dot(v, v);
      q.c = centre;
      q.r = radius;
    }
  }
  return nearest < 1e30;
}

// The first solve's verdict: whether the geodesic of length L is within the
// ball's reach of the minimiser from x to y (`count` connections, found[0]
// the shortest).
bool glow_density_reached(GlowDensity q, int count, vec4 shortest) {
  return count > 0 && !(q.L > (shortest.w + scene_objects[q.k].glow.x) * (1.0 + 1e-3) + 1e-4);
}

// The density from the second solve (the minimiser from c to y).
float glow_density_of(GlowDensity q, int count, vec4 shortest) {
  if (count == 0 || abs(shortest.w - q.r) > 1e-3 * max(1.0, q.r) || !(q.cos_y > 0.0)) return 0.0;
  // The spreading from the centre to y, then from x to y: one call of
  // sol_sphere_area_density in a loop whose count the compiler cannot fold.
  float spreading[2];
  int i = 0;
  do {
    spreading[i] = sol_sphere_area_density(i == 0 ? shortest.xyz : q.d, i == 0 ? q.r : q.L);
  } while (++i < count + 1 && spreading[0] > 0.0 && i < 2);
  const float j_centre = spreading[0];
  if (!(j_centre > 0.0)) return 0.0;
  const float pick = glow_pick_weight(q.x, q.c, q.r) / glow_pick_total(q.x);
  return pick * spreading[1] / (4.0 * SOL_PI * j_centre * q.cos_y);
}

// One sampled point of one glowing ball seen from a diffuse hit: the
// ball (its scene object k), the normal at x and at y, the area density,
// the path's weight times the albedo there, and the geodesics to y within
// reach, which path_radiance marches one by one (glow_connection).
struct GlowSample {
  int k;
  vec3 n;         // the normal at x, facing the ray that came
  vec3 normal_y;  // the sphere's outward normal at y
  float area;     // the density of y per unit area (with the pick's)
  vec3 factor;    // the path's weight times the albedo at x
  vec3 towards;   // y seen from x (frame components at x): the target of its connections' solve
  int count;      // geodesics in `ways`
  vec4 ways[SOL_FOUND_SLOTS];
  bool enclosed;  // x lies on the ball's sphere seen from inside, the ball convex (glow_enclosed)
};

// Whether the hit h lies on the inner wall of an exact ball of radius
// below kConvexBallRadius (in Sol among listed objects: MARCH_SKIPS).
bool on_convex_ball_inside(MarchHit h) {
  return MARCH_SKIPS && h.k >= 0 && h.exact_k == h.k && h.exact_inside && g_types[h.k] == kObjectExactBall &&
         g_radii[h.k] < kConvexBallRadius;
}

// A ball of radius below kConvexBallRadius (< π/2) is strongly convex
// (sectional curvatures at most 1, the injectivity radius at least √2π:
// docs/lighting.md, "Enclosures"): the minimising geodesic between two
// of its points stays inside it. A path's vertex x on the inner wall of a
// glowing exact ball that small reaches a sampled point y of its sphere
// along its minimisers (reach 0) without meeting that sphere before y, so
// the march along them leaves the ball out (MarchResume::skip) and stops
// short of y by the connection's tolerance: only the other objects can be
// in the way.
bool glow_enclosed(MarchHit h, int k, float radius) {
  return on_convex_ball_inside(h) && h.k == k && !(scene_objects[k].glow.x > 0.0);
}

// How far the march along a connection of length L goes where the ball is
// left out: to the tolerance within which a hit counts as the sphere's.
float glow_enclosed_limit(float L) { return L - 1e-3 * max(1.0, L); }

// Draws a target and a point y of its sphere at the diffuse hit h (normal
// n); the geodesics from h to y within its reach are path_radiance's solve
// (kSolveGlowSample).
GlowSample glow_sample(MarchHit h, vec3 n, vec3 factor, inout uvec2 state) {
  GlowSample g;
  g.n = n;
  g.factor = factor;
  const float total = glow_pick_total(h.q);
  float left = path_uniform(state) * total, weight_k = 0.0;
  int object;
  vec3 c = vec3(0.0), centre;
  float r = 0.0, radius;
  g.k = -1;
  for (int i = 0; i < glow_target_slots(); ++i) {
    if (!glow_target(i, object, centre, radius)) continue;
    const float w = glow_pick_weight(h.q, centre, radius);
    if (g.k < 0 || left >= 0.0) {  // the first target, then each the remaining share still reaches
      g.k = object;
      c = centre;
      r = radius;
      weight_k = w;
    }
    left -= w;
  }
  const float u = 2.0 * path_uniform(state) - 1.0, phi = 2.0 * SOL_PI * path_uniform(state);
  const float s = sqrt(max(0.0, 1.0 - u * u));
  const vec3 w = vec3(s * cos(phi), s * sin(phi), u);
  const SolSpread on_sphere = sol_spread(w, r);  // the point, its normal and its J in one integration
  const vec3 y = sol_translate(c, on_sphere.position);
  g.normal_y = on_sphere.direction;
  g.area = weight_k / total / (4.0 * SOL_PI * max(on_sphere.density, 1e-30));
  g.towards = seen_from(h.q, y);
  g.count = 0;
  g.enclosed = glow_enclosed(h, g.k, r);
  return g;
}

// A path's connection solves, numbered: 0, the density's from x to y
// (glow_density_reached), 1, the density's from c to y (skipped when 0
// failed), 2, the sample's from x to its point (kept in g.ways), and 3, the
// lights' (light_gather_step's kGatherSolve). path_radiance makes them at
// one call of sol_connections, a solve a turn: the driver inlines each call,
// and a solve is the dearest code of the path kernel.
const int kSolveDensityFromX = 0, kSolveDensityFromCentre = 1, kSolveGlowSample = 2, kSolveLight = 3;

// Solve i (kSolve*) of a path's turn, at the path kernel's one call of
// sol_connections: a light's (light_gather_solved), or the vertex's, `solve`
// then the vertex's next (the density's from c to y skipped where the one
// from x to y failed), `glow_density` the density once its solves are in.
void path_solve(int i, GlowDensity dq, inout GlowSample g, inout LightGather lights, inout int solve,
                inout float glow_density) {
  const vec3 target = i == kSolveDensityFromX ? seen_from(dq.x, dq.y)
                    : (i == kSolveDensityFromCentre ? seen_from(dq.c, dq.y)
                                                    : (i == kSolveGlowSample ? g.towards : lights.target));
  const float reach = i == kSolveGlowSample ? scene_objects[g.k].glow.x : (i == kSolveLight ? lights.reach : 0.0);
  vec4 found[SOL_FOUND_SLOTS];
  int count = 1;
  if (i == kSolveDensityFromCentre && dq.from_centre.w > 0.0) {  // the march's (glow_density_known)
    [[unroll]] for (int j = 0; j < SOL_FOUND_SLOTS; ++j) found[j] = vec4(0.0);
    found[0] = dq.from_centre;
  } else {
    count = sol_connections(target, reach, found);
  }
  if (i == kSolveLight) {
    light_gather_solved(lights, count, found);
  } else if (i == kSolveDensityFromX) {
    solve = glow_density_reached(dq, count, found[0]) ? kSolveDensityFromCentre : kSolveGlowSample;
  } else if (i == kSolveDensityFromCentre) {
    glow_density = glow_density_of(dq, count, found[0]);
    solve = kSolveGlowSample;
  } else {
    g.count = count;
    g.ways = found;
    solve = kSolveLight;
  }
}

// Whether geodesic j of g is one light can come along: of positive length,
// leaving the surface's front (else it is not marched).
bool glow_way_open(GlowSample g, int j) {
  const vec4 way = sol_slot_get(g.ways, j);
  return way.w > 0.0 && dot(g.n, way.xyz) > 0.0;
}

// The light along geodesic j of g, `to` the march along it: counted where
// that march first meets the ball at the geodesic's length, weighted for the
// sampling (params.path.w: kPathSampling*), times g.factor.
vec3 glow_connection(GlowSample g, int j, MarchHit to) {
  const vec4 way = sol_slot_get(g.ways, j);
  const vec3 d = way.xyz;
  const float L = way.w, cos_x = dot(g.n, d);
  const int met = QUOTIENT && to.k >= 0 ? int(images[to.k].info.z) : to.k;  // the scene object met
  // (Enclosed: the march without the ball went to its limit unhindered.)
  const bool reached = g.enclosed ? to.k < 0 && !(to.t < glow_enclosed_limit(L))
                                  : met == g.k && !(abs(to.t - L) > 1e-3 * max(1.0, L));
  if (!reached) return vec3(0.0);  // something, or the ball's nearer side, is in the way
  // The tangent at y: in Sol the march's own at its hit (met at L, within
  // the check above), which saves the path kernel a closed form; in a
  // quotient the march's frame may be turned by Γ, and an enclosed march
  // stops short of y, so the geodesic's own.
  const SolSpread along = sol_spread(d, L);
  const vec3 arriving = QUOTIENT || g.enclosed ? along.direction : to.u;
  const float cos_y = abs(dot(arriving, g.normal_y));
  const float spreading = along.density;
  if (!(spreading > 0.0)) return vec3(0.0);
  float weight = 1.0;
  if (params.path.w == kPathSamplingCombined) {
    const float glow = g.area * spreading / max(cos_y, 1e-30), reflection = cos_x / SOL_PI;
    weight = glow / (glow + reflection);
  }
  return g.factor * scene_objects[g.k].material.rgb * (weight * cos_x * cos_y / (SOL_PI * spreading * g.area));
}

// A hit's fog and emission on a path (path_radiance): the fog of its
// segment into `color` and its transmittance into `weight`; the emission
// (`emission`, weighted) added at once, or, where next-event estimation
// could have found this hit (`reachable`: after a diffuse vertex, with
// glowing balls to sample; true returned), once its density is solved (dq,
// kSolveDensity*).
bool path_emission(MarchHit h, Surface f, bool reachable, vec3 from, vec3 from_direction, float from_cosine,
                   inout vec3 color, inout vec3 weight, out vec3 emission, out GlowDensity dq) {
  const vec4 material = scene_objects[f.object].material;
  const float transmittance = HAS_FOG ? exp(-params.shading.y * h.t) : 1.0;
  color += weight * ((1.0 - transmittance) * params.fog_color.rgb);
  weight *= transmittance;
  emission = weight * material.rgb;
  float share = 1.0;
  bool density = false;
  if (HAS_EMISSION && GLOW_SAMPLING && reachable && glowing(f.object)) {
    if (params.path.w == kPathSamplingGlowOnly) {
      share = 0.0;  // next-event estimation counted it
    } else {
      density = glow_density_target(f.object, from, from_direction, h.t, h.q, abs(dot(h.u, f.n)), dq);
      if (density) glow_density_known(h, dq);
      if (density && dq.minimiser && dq.from_centre.w > 0.0) {  // known: no solve, its share at once
        const float reflection = from_cosine / SOL_PI;
        share = reflection / (reflection + glow_density_of(dq, 1, dq.from_centre));
        density = false;
      }
    }
  }
  if (HAS_EMISSION && !density) color += emission * share;  // (else once its density is solved)
  return density;
}

// Where a path's march from the vertex h starts (path_radiance): a
// geodesic to a point of the glowing ball that encloses h leaves the ball
// out, up to the connection's tolerance before y (glow_enclosed); a segment
// that leaves the inner wall of h's convex exact ball inward (at the cosine
// `exit_cos` > 0 with its normal) solves its exit first (exit_newton), from
// the chord 2 r cos θ; else from the start. `limit` (the march's) is cut
// to the enclosed connection's.
MarchResume path_march_start(MarchHit h, bool to_glow, bool segment, GlowSample g, int way, float exit_cos,
                             inout float limit) {
  if (MARCH_SKIPS && to_glow && g.enclosed) {
    limit = min(limit, glow_enclosed_limit(sol_slot_get(g.ways, way).w));
    return MarchResume(0.0, 0u, 0, 1u << uint(g.k), -1, 0.0);
  }
  const bool exits = MARCH_SKIPS && segment && exit_cos > 0.0;
  return MarchResume(0.0, 0u, 0, 0u, exits ? h.k : -1, exits ? 2.0 * g_radii[h.k] * exit_cos : 0.0);
}

// Paths from the eye: a pixel's camera ray is its path's first segment
// (march/passes.glsl, from_eye_pass). The host chooses it where
// the march is dear to compile (exact balls: sol::vk's defer_passes): the
// pipeline then holds one march, where the march pass and the shade pass
// would hold one each (the shade pass, over the hits alone, keeps the
// SIMD lanes of a path-traced world fuller where the march is cheap).
const bool PATH_FROM_EYE = FROM_EYE_WORLD && PATH_TRACING && INTEGRATOR == 0;

// Whether the hit's lights are gathered a step at a time in path_radiance's
// loop (light_gather_step: shadow rays to march or solves to make), else at once.
const bool HAS_LIGHT_STEPS = HAS_SHADOWS || HAS_EXACT_LIGHTS;

// What one path from a camera ray's hit brings back (path_radiance in
// libsol/src/render.cpp): at each hit, over the fog of its segment, the
// object's emission; then with probability `mirror` the path goes on along
// the reflected geodesic, else it is diffuse: the lights' light by
// next-event estimation (light_gather_next: every geodesic to an exact
// light with its 1/J, and shadows) times the albedo, and the path goes on along a
// cosine-distributed direction, its weight times the albedo; at most
// World::path_bounces scatterings (params.limits.z), Russian roulette from
// the fourth hit with q = min(1, the weight's largest). No ambient light. Glowing exact balls by
// next-event estimation too (glow_sample, glow_connection), the emission a
// path meets after a diffuse bounce weighed by the balance heuristic.
// One call of march, for the path's next segment, the shadow rays of the
// lights and the geodesics to a glowing ball's point alike (those first,
// from the same hit), and one of sol_connections, for the glowing ball's
// solves and the exact lights' alike (kSolve*; a turn of the loop makes a
// solve or marches a ray): the driver inlines each call, and each holds a
// march or a solve (see radiance). From the eye (PATH_FROM_EYE:
// `from_eye`, h.q the ray's start and h.u its direction) the camera ray is
// the path's first segment, marched by that same call, so the path's
// pipeline holds one march; `first` is then what that segment met and
// `first_f` its surface, where it met one (the AOVs' hit).
vec4 path_radiance(MarchHit h, Surface f, int eye, uint pixel, const bool from_eye, out MarchHit first,
                   out Surface first_f) {
  uvec2 state = path_random_start(uvec2(params.path.xy), pixel, uint(params.path.z));
  const int light_count = min(int(params.shading.z), kMaxLights);
  const int glow_count = GLOW_SAMPLING && params.path.w != kPathSamplingReflectionOnly ? glowing_count() : 0;
  vec3 color = vec3(0.0), weight = vec3(1.0);
  // The last hit, where it was diffuse (for the emission's weight at the next).
  bool after_diffuse = false;
  vec3 from = vec3(0.0), from_direction = vec3(0.0);
  float from_cosine = 0.0;
  const int bounces = int(params.limits.z);  // World::path_bounces: the scatterings a path takes
  int depth = from_eye ? -1 : 0;  // (the camera ray's segment is no scattering)
  bool alive = true;        // the path goes on from h (h to shade, or its next segment to march)
  bool fresh = !from_eye;   // h is a hit not yet shaded
  GlowSample g;             // the hit's next-event estimation to a glowing ball: its geodesics from `way` on left to march
  g.count = 0;
  g.enclosed = false;
  int way = 0;
  vec3 next = h.u;          // (from the eye: the camera ray's direction)
  float exit_cos = 0.0;     // > 0: the next segment leaves h's convex exact ball inward at this cosine (path_march_start)
  LightGather lights;       // the hit's next-event estimation to the lights, its shadow rays and solves still to make
  bool gathering = false;
  // The hit's solves (kSolve*) from `solve` to `solves_end` - 1, for the
  // glowing ball's density at it (dq: its emission's share, `emission` times
  // reflection / (reflection + glow_density)) and its sample's geodesics (g).
  int solve = 0, solves_end = 0;
  GlowDensity dq;
  bool density = false;
  float reflection = 0.0, glow_density = 0.0;
  vec3 emission = vec3(0.0);
  vec3 lights_gain = vec3(0.0);
  first = h;
  first_f = f;
  do {
    if (fresh) {
      fresh = false;
      reflection = from_cosine / SOL_PI;  // the last diffuse vertex's density of this ray
      density = path_emission(h, f, glow_count > 0 && after_diffuse, from, from_direction, from_cosine, color, weight,
                              emission, dq);
      const vec3 n = dot(f.n, h.u) > 0.0 ? -f.n : f.n;
      const bool goes_on = depth < bounces;  // this vertex may scatter the path further
      bool sampled = false;  // a glowing ball's point drawn (g), its connections to solve
      g.count = 0;
      way = 0;
      // The material's lobes (sol/materials.h), as path_radiance in libsol.
      const vec3 surface_albedo = albedo(f.object, f.uv);
      const SolLobes lobes = lobes_of(f.object, surface_albedo);
      if (HAS_MIRRORS && lobes.specular_probability > 0.0 && path_uniform(state) < lobes.specular_probability) {
        next = specular_direction(h.u, n, lobes.roughness, lobes.ior, f.inside, state);
        // (This vertex gathers no light: its start may move past the surface.)
        if (HAS_INSIDE && lobes.ior > 0.0 && f.inside && dot(next, n) < 0.0) skip_surface(h.q, next, n);
        weight *= lobes.specular / lobes.specular_probability;
        after_diffuse = false;
      } else {
        const vec3 a = surface_albedo * (lobes.diffuse / (1.0 - lobes.specular_probability));
        if (light_count > 0) {
          lights = light_gather_begin(n, h.q);
          lights_gain = weight * a;
          if (HAS_LIGHT_STEPS) {
            gathering = true;  // its shadow rays and solves made below, first
          } else {  // no shadow ray: its light at once (added below instead, the hall
                    // of mirrors' paths in the quotient came out brighter than the
                    // CPU's on lavapipe, the sum the same: docs/history.md)
            vec3 unused_direction;
            float unused_len;
            light_gather_next(lights, eye, unused_direction, unused_len);
            color += lights_gain * lights.light;
          }
        }
        if (GLOW_SAMPLING && glow_count > 0 && goes_on) {
          g = glow_sample(h, n, weight * a, state);
          sampled = true;
        }
        weight *= a;
        next = cosine_direction(n, state);
        after_diffuse = true;
        from = h.q;
        from_direction = next;
        from_cosine = dot(n, next);
      }
      exit_cos = on_convex_ball_inside(h) ? max(dot(next, n), 0.0) : 0.0;
      alive = goes_on;
      if (goes_on && depth >= 3) {
        const float q = min(1.0, max(weight.r, max(weight.g, weight.b)));
        alive = q > 0.0 && path_uniform(state) < q;
        weight /= max(q, 1e-30);
      }
      if (GLOW_SAMPLING && (density || sampled)) {  // the vertex's solves, in the next turns
        solve = density ? (dq.minimiser ? kSolveDensityFromCentre : kSolveDensityFromX) : kSolveGlowSample;
        solves_end = sampled ? kSolveLight : kSolveGlowSample;
        glow_density = 0.0;
      }
    }
    // The turn's ray: a connection solve of the vertex, else the next step
    // of the hit's lights (a solve or a shadow ray), else a geodesic to a
    // glowing ball's point, else the path's next segment.
    vec3 direction;
    float len;
    const bool vertex_solve = GLOW_SAMPLING && solve < solves_end;
    const int step = HAS_LIGHT_STEPS && gathering && !vertex_solve ? light_gather_step(lights, eye, direction, len)
                                                                    : kGatherDone;
    // (A constant condition first: a world without glowing exact balls or
    // exact lights holds no solve.)
    if ((GLOW_SAMPLING || HAS_EXACT_LIGHTS) && (vertex_solve || step == kGatherSolve)) {
      path_solve(vertex_solve ? solve : kSolveLight, dq, g, lights, solve, glow_density);
      if (HAS_EMISSION && vertex_solve && density && solve >= solves_end) {
        color += emission * (reflection / (reflection + glow_density));
      }
      continue;
    }
    const bool shadow = step == kGatherShadow;
    if (HAS_LIGHT_STEPS && gathering && !vertex_solve && step == kGatherDone) {
      color += lights_gain * lights.light;
      gathering = false;
    }
    if (GLOW_SAMPLING && !shadow) {
      while (way < g.count && !glow_way_open(g, way)) ++way;
    }
    const bool to_glow = GLOW_SAMPLING && !shadow && way < g.count;
    if (shadow || to_glow || alive) {
      // (From the eye the camera ray's segment is marched as a camera ray:
      // the purpose is then no constant, and this one march holds both
      // purposes' branches; otherwise it folds to kMarchShadow.)
      float limit = shadow ? min(len, params.limits.x) : params.limits.x;
      const MarchResume resume_at = path_march_start(h, to_glow, !shadow && !to_glow, g, way, exit_cos, limit);
      const MarchHit m = march(h.q, shadow ? direction : (to_glow ? sol_slot_get(g.ways, way).xyz : next), limit,
                               resume_at, PATH_FROM_EYE && depth < 0 ? kMarchCamera : kMarchShadow);
      if (shadow) {
        light_gather_blocked(lights, m.k >= 0);
      } else if (to_glow) {
        color += glow_connection(g, way, m);
        ++way;
      } else {
        h = m;
        alive = h.k >= 0;
        ++depth;
        if (alive) {
          f = surface_at(h);
          fresh = true;
        }
        if (from_eye && depth == 0) {
          first = m;
          first_f = f;
        }
      }
    }
  } while (gathering || (GLOW_SAMPLING && (way < g.count || solve < solves_end)) || alive);
  return vec4(color, 1.0);
}

#endif  // SOL_MARCH_PATHS_GLSL
