// Path tracing (PATH_TRACING; path_radiance in libsol/src/render.cpp, the
// same estimator with the same random numbers): one path per pixel and
// dispatch, from the camera ray's hit, in the shade pass (the march pass
// lists the hits), so that the camera rays' pipelines never hold a path's
// march nor its connection solves. docs/lighting.md, "Path tracing".
#ifndef SOL_MARCH_PATHS_GLSL
#define SOL_MARCH_PATHS_GLSL

// A direction about the unit normal n with density cos θ / π
// (sol_cosine_direction, shared with the CPU's cosine_direction), from the path's next two numbers.
vec3 cosine_direction(vec3 n, inout uvec2 state) {
  const float xi1 = path_uniform(state), xi2 = path_uniform(state);
  return sol_cosine_direction(n, xi1, xi2);
}

#include "glow.glsl"  // next-event estimation to glowing objects: targets, samples, densities

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
    const bool reached = glow_density_reached(dq, count, found[0]);
    if (reached && closed_form(dq.shape)) glow_density = glow_density_of(dq, count, found[0]);  // no second solve
    solve = reached && !closed_form(dq.shape) ? kSolveDensityFromCentre : kSolveGlowSample;
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
  const bool reached = met == g.k && !(abs(to.t - L) > 1e-3 * max(1.0, L));
  if (!reached) return vec3(0.0);  // something, or the ball's nearer side, is in the way
  // The tangent at y: in Sol the march's own at its hit (met at L, within
  // the check above), which saves the path kernel a closed form; in a
  // quotient the march's frame may be turned by Γ, so the geodesic's own.
  const SolSpread along = sol_spread(d, L);
  const vec3 arriving = QUOTIENT ? along.direction : to.u;
  const float cos_y = abs(dot(arriving, g.normal_y));
  const float spreading = along.density;
  if (!(spreading > 0.0) || !(g.area > 0.0)) return vec3(0.0);  // (a point of density 0 is never drawn)
  float weight = 1.0;
  if (params.path.w == kPathSamplingCombined) {
    const float glow = g.area * spreading / max(cos_y, 1e-30), reflection = cos_x / SOL_PI;
    weight = glow / (glow + reflection);
  }
  return g.factor * scene_objects[g.k].material.rgb * (weight * cos_x * cos_y / (SOL_PI * spreading * g.area));
}

// The share of a glowing target's emission that reflection sampling
// counts, where next-event estimation draws its direction with density
// `glow` and the diffuse vertex with `reflection`: the balance heuristic's,
// or with next-event estimation alone all or nothing (what it could not
// have drawn, such as a quotient's image it does not list, is counted here).
float emission_share(float reflection, float glow) {
  if (params.path.w == kPathSamplingGlowOnly) return glow > 0.0 ? 0.0 : 1.0;
  return reflection / (reflection + glow);
}

// A hit's fog and emission on a path (path_radiance): the fog of its
// segment into `color` and its transmittance into `weight`; the emission
// (`emission`, weighted) added at once, or, where next-event estimation
// could have found this hit (`reachable`: after a diffuse vertex, with
// glowing objects to sample; true returned), once its density is solved (dq,
// kSolveDensity*). `from_inside`: the solid whose inner wall that vertex
// lies on (no target from there), or -1.
bool path_emission(MarchHit h, Surface f, bool reachable, vec3 from, int from_inside, vec3 from_direction,
                   float from_cosine, inout vec3 color, inout vec3 weight, out vec3 emission, out GlowDensity dq) {
  const vec4 material = scene_objects[f.object].material;
  const float transmittance = fog_transmittance(h.t);
  color += weight * ((1.0 - transmittance) * params.fog_color.rgb);
  weight *= transmittance;
  emission = weight * material.rgb;
  float share = 1.0;
  bool density = false;
  if (HAS_EMISSION && GLOW_SAMPLING && reachable && glowing(f.object)) {
    const int kind = int(scene_objects[f.object].plane.x);
    const float cos_y = GLOW_SURFACES && kind != kObjectExactBall ? surface_hit_cosine(h) : abs(dot(h.u, f.n));
    density = glow_density_target(f.object, from, from_inside, from_direction, h.t, h.q, cos_y, dq);
    if (density) glow_density_known(h, dq);
    if (density && dq.minimiser && (dq.from_centre.w > 0.0 || closed_form(dq.shape))) {  // known: no solve, its share at once
      share = emission_share(from_cosine / SOL_PI, glow_density_of(dq, 1, dq.from_centre));
      density = false;
    }
  }
  if (HAS_EMISSION && !density) color += emission * share;  // (else once its density is solved)
  return density;
}

// The solid whose inner wall the hit lies on (met from inside: seen so,
// or heading out through its surface where the float march took it as met
// from outside), else -1: no target of next-event estimation from there
// (the CPU's inner_wall_of).
int inner_wall_of(MarchHit h, Surface f) {
  const bool solid = object_is_solid(int(scene_objects[f.object].plane.x));
  return HAS_INSIDE && solid && (f.inside || dot(h.u, f.n) > 0.0) ? f.object : -1;
}

// Where a path's march from the vertex h starts (path_radiance): a segment
// that leaves the inner wall of h's convex exact ball inward (at the cosine
// `exit_cos` > 0 with its normal) solves its exit first (exit_newton), from
// the chord 2 r cos θ; else from the start.
MarchResume path_march_start(MarchHit h, bool segment, float exit_cos) {
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
// lights and the geodesics to a glowing object's point alike (those first,
// from the same hit), and one of sol_connections, for the glowing object's
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
  int from_inside = -1;  // the solid whose inner wall that hit lies on (no target from there)
  const int bounces = int(params.limits.z);  // World::path_bounces: the scatterings a path takes
  int depth = from_eye ? -1 : 0;  // (the camera ray's segment is no scattering)
  bool alive = true;        // the path goes on from h (h to shade, or its next segment to march)
  bool fresh = !from_eye;   // h is a hit not yet shaded
  GlowSample g;             // the hit's next-event estimation to a glowing object: its geodesics from `way` on left to march
  g.count = 0;  // (g.skip: read only after glow_sample sets it)
  int way = 0;
  vec3 next = h.u;          // (from the eye: the camera ray's direction)
  float exit_cos = 0.0;     // > 0: the next segment leaves h's convex exact ball inward at this cosine (path_march_start)
  LightGather lights;       // the hit's next-event estimation to the lights, its shadow rays and solves still to make
  bool gathering = false;
  // The hit's solves (kSolve*) from `solve` to `solves_end` - 1, for the
  // glowing object's density at it (dq: its emission's share, `emission` times
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
      density = path_emission(h, f, glow_count > 0 && after_diffuse, from, from_inside, from_direction, from_cosine,
                              color, weight, emission, dq);
      const vec3 n = dot(f.n, h.u) > 0.0 ? -f.n : f.n;
      const bool goes_on = depth < bounces;  // this vertex may scatter the path further
      bool sampled = false;  // a glowing object's point drawn (g), its connections to solve
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
          g = glow_sample(h, n, weight * a, inner_wall_of(h, f), state);
          sampled = !g.skip;
        }
        weight *= a;
        next = cosine_direction(n, state);
        after_diffuse = true;
        from = h.q;
        from_inside = inner_wall_of(h, f);
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
    // glowing object's point, else the path's next segment.
    vec3 direction;
    float len;
    const bool vertex_solve = GLOW_SAMPLING && solve < solves_end;
    const int step = HAS_LIGHT_STEPS && gathering && !vertex_solve ? light_gather_step(lights, eye, direction, len)
                                                                    : kGatherDone;
    // (A constant condition first: a world without glowing exact balls, boxes or
    // exact lights holds no solve.)
    if ((GLOW_SAMPLING || HAS_EXACT_LIGHTS) && (vertex_solve || step == kGatherSolve)) {
      path_solve(vertex_solve ? solve : kSolveLight, dq, g, lights, solve, glow_density);
      if (HAS_EMISSION && vertex_solve && density && solve >= solves_end) {
        color += emission * emission_share(reflection, glow_density);
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
      const float limit = shadow ? min(len, params.limits.x) : params.limits.x;
      const MarchResume resume_at = path_march_start(h, !shadow && !to_glow, exit_cos);
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
