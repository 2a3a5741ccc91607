// The march: one function, march(), advances every ray of the kernel from
// its start to the first object it meets (docs/renderer.md "The march"),
// whatever the ray is for: a camera ray, or a shadow ray from a hit point
// towards a light. Its purpose is a constant at each call, so that each
// inlined copy keeps only its own branches. In Sol the ray is the
// closed-form geodesic evaluated at the accumulated arc length (or RK4 for
// camera rays, for comparison) through the objects relative to the eye;
// in the quotient it lives in D, teleported back when a step leaves it,
// and steps by the distance field's candidates. The GLSL twin of
// march_cover and march_quotient in libsol/src/render.cpp.
#ifndef SOL_MARCH_MARCH_GLSL
#define SOL_MARCH_MARCH_GLSL

// What a march is for.
const int kMarchCamera = 0;  // from an eye (or an ODS column's eye) to the first object
const int kMarchShadow = 1;  // from a hit point: towards a light, or a mirror's reflected ray; passes the surface it starts on

// Where a march picks a ray up: at arc length t, march step `step`,
// passing the objects of the mask `passing` (cutout planes between their
// discs, the surface a shadow ray leaves). A new ray starts at zero; the
// resume pass goes on from the march pass's record (defer_exact). Paths
// inside a convex exact ball (MARCH_SKIPS, exit_newton): a segment that
// leaves the inner wall of such a ball k (`exit_k`, else -1) has its exit
// solved first, from `exit_guess`, and marches the others up to it
// without that ball (`skip`, a mask of objects).
struct MarchResume {
  float t;
  uint passing;
  int step;
  uint skip;
  int exit_k;
  float exit_guess;
};

const MarchResume kMarchFromStart = MarchResume(0.0, 0u, 0, 0u, -1, 0.0);

// Whether a march may leave objects out or solve an exit
// (MarchResume::skip, exit_k): paths inside exact balls, in Sol among
// listed objects.
const bool MARCH_SKIPS = PATH_TRACING && HAS_EXACT_BALLS && HAS_INSIDE && !QUOTIENT && !CROWD;

// What a march found.
struct MarchHit {
  int k;       // the object hit: the scene object in Sol, the image in the quotient; -1 for none
  int item;    // a crowd's item hit (march/crowd.glsl); -1 otherwise
  float t;     // the arc length marched (to the hit)
  vec3 q;      // the point reached, in the march's coordinates
  vec3 from;   // the start of the ray's last segment (planes face its side)
  vec3 u;      // with mirrors, paths or an eye inside a solid: the ray's unit tangent at q, frame components
  int steps;   // positions evaluated
  // The exact ball whose geodesic from its centre `exact_end` ends at q (-1:
  // none), with that geodesic's initial vector `exact_v` (|exact_v| its
  // length; 0 where the solve did not land).
  int exact_k;
  SolEnd exact_end;
  vec3 exact_v;
  bool exact_inside;  // that geodesic is shorter than the ball's radius: the sphere seen from inside
  // The march pass left the ray to the resume pass, from `resume`.
  bool deferred;
  MarchResume resume;
};

MarchHit march_hit_none(MarchResume resume) {
  MarchHit h;
  h.k = -1;
  h.item = -1;
  h.t = resume.t;
  h.q = vec3(0.0);
  h.from = vec3(0.0);
  h.u = vec3(0.0, 0.0, 1.0);
  h.steps = 0;
  h.exact_k = -1;
  h.exact_end = SolEnd(vec3(0.0), vec3(0.0, 0.0, 1.0));
  h.exact_v = vec3(0.0);
  h.exact_inside = false;
  h.deferred = false;
  h.resume = resume;
  return h;
}

// What a march found: object (image) k, or -1, at arc length t and point q,
// its last segment from `from`, after `steps` positions, with its last
// exact solve.
MarchHit march_found(int k, float t, vec3 q, vec3 from, int steps, ExactSolve exact) {
  MarchHit h = march_hit_none(kMarchFromStart);
  h.k = k;
  h.t = t;
  h.q = q;
  h.from = from;
  h.steps = steps;
  h.exact_k = exact.k;
  h.exact_end = exact.end;
  h.exact_v = exact.known ? exact.v : vec3(0.0);
  return h;
}

// ---- RK4 (camera rays with INTEGRATOR = 1, for comparison): the geodesic
// ODE in frame components, x' = e^{z}u1, y' = e^{-z}u2, z' = u3,
// u1' = u1 u3, u2' = -u2 u3, u3' = u2² - u1², advanced from the last
// step's state, so that its error accumulates (what the bench measures).
void geodesic_rhs(vec3 p, vec3 u, out vec3 dp, out vec3 du) {
  float ez = exp(p.z);
  dp = vec3(ez * u.x, u.y / ez, u.z);
  du = vec3(u.x * u.z, -u.y * u.z, u.y * u.y - u.x * u.x);
}

void rk4_advance(inout vec3 p, inout vec3 u, float length, float step) {
  int n = max(1, int(ceil(length / step)));
  float h = length / float(n);
  for (int i = 0; i < n; ++i) {
    vec3 p1, u1, p2, u2, p3, u3, p4, u4;
    geodesic_rhs(p, u, p1, u1);
    geodesic_rhs(p + 0.5 * h * p1, u + 0.5 * h * u1, p2, u2);
    geodesic_rhs(p + 0.5 * h * p2, u + 0.5 * h * u2, p3, u3);
    geodesic_rhs(p + h * p3, u + h * u3, p4, u4);
    p += h / 6.0 * (p1 + 2.0 * p2 + 2.0 * p3 + p4);
    u += h / 6.0 * (u1 + 2.0 * u2 + 2.0 * u3 + u4);
  }
}

// ---- The march in Sol

#include "steps.glsl"

// The surfaces a ray from a surface starts on (within 2 hit_epsilon of
// `origin`): passed (`passing`), and the solids among them it leaves
// through the face it starts on (`leaving`); for a plane z = c, `leaving`
// says the ray starts upward (its pass ends where u_z turns: march_objects).
void march_starts_on(vec3 origin, vec3 direction, float hit_epsilon, inout uint passing, inout uint leaving) {
  for (int k = 0; k < g_count; ++k) {
    if (object_distance(g_types[k], origin, g_relative[k], g_headings[k], g_radii[k]) < 2.0 * hit_epsilon) {
      passing |= 1u << uint(k);
      const bool leaves = HAS_INSIDE && leaves_through_start(g_types[k], origin, direction, g_relative[k], g_headings[k], g_radii[k]);
      const bool upward = HAS_PLANES_Z && g_types[k] == kObjectPlaneZ && direction.z > 0.0;
      leaving |= leaves || upward ? 1u << uint(k) : 0u;
    }
  }
}

// Exact culling for planes z = c (as the CPU reference): whether the
// z-range of the whole ray, from a start at height z0, comes within
// hit_epsilon of a plane; a ray that does not never hits.
bool planes_z_reachable(SolRay ray, float z0, float hit_epsilon) {
  vec2 range = sol_height_range(ray) + z0 + vec2(-hit_epsilon, hit_epsilon);
  bool reachable = false;
  for (int k = 0; k < g_count; ++k) reachable = reachable || (g_constants[k] >= range.x && g_constants[k] <= range.y);
  return reachable;
}

// The march through the objects (g_*, load_objects) of a ray from `origin`
// (relative to the eye; a camera ray's is 0 but for an ODS column's eye)
// with unit direction `direction` (frame components there), up to arc
// length `limit`, picked up at `resume`. With exact balls it runs in
// rounds: the inner loop marches by the objects' distances (exact balls by
// their bound) until the ray comes within kExactShell of an exact ball;
// that step is finished after the inner loop by the exact distance
// (exact_ball_sdf), and the next round goes on. lavapipe executes the body
// of every if, and of every loop at least once, for all its lanes, masked,
// whichever way they go: inside the loop the exact solve (a Newton loop
// around the closed form) would cost every step of every ray; here once a
// round. A camera ray's march pass of a deferred world stops at the first
// exact ball's shell (`deferred`), leaving the rest to the resume pass.
MarchHit march_sol(vec3 origin, vec3 direction, float limit, MarchResume resume, const int purpose) {
  const bool camera = purpose == kMarchCamera;
  const float hit_epsilon = params.limits.y;
  const int max_steps = int(params.limits.w);
  // Camera rays take the world's short cuts; shadow rays the closed form's
  // full positions, from their start on a surface.
  const bool rk4 = camera && INTEGRATOR == 1;
  const bool heights_only = camera && HEIGHTS_ONLY;
  const bool planes_xy_only = camera && PLANES_XY_ONLY;
  const bool zeta = camera && SOL_ZETA, zeta_only = camera && SOL_ZETA_ONLY;
  const bool translated = !camera || HAS_ODS || HAS_LENS;  // positions from a start other than the eye
  // Whether objects can be passed: cutout planes, and the surface a shadow ray leaves.
  const bool passes = !camera || HAS_CUTOUT;
  MarchHit h = march_hit_none(resume);
  h.from = origin;

  SolRay ray;
  bool zeta_round = false;  // this round's positions by the zeta function (SOL_ZETA)
  if (!rk4) {
    ray = sol_ray(direction);
    zeta_round = zeta && ray.mu >= kZetaLeastMu;
    if (zeta_only && !zeta_round) {  // this ray in the resume pass, by Carlson's integrals
      h.deferred = true;
      return h;
    }
    if (!heights_only || HAS_CUTOUT) sol_ray_integrals(ray);
    if (zeta) sol_ray_zeta(ray);
  }
  vec3 rk_p = vec3(0.0), rk_u = direction;
  float rk_t = 0.0;

  int hit = 0, steps = 0;
  uint passing = resume.passing;
  uint leaving = 0u;  // the solids it leaves through the face it starts on (as the CPU's leaving_sign)
  if (!camera) march_starts_on(origin, direction, hit_epsilon, passing, leaving);
  ExactSolve exact = exact_solve_none();
  ExactSeen seen = exact_seen_none();
  float t = resume.t;
  vec3 q = vec3(0.0);
  // The exit search (exit_newton): while `exit.searching`, t is Newton's trial.
  ExitSearch exit = exit_search_start(MARCH_SKIPS ? resume.exit_k : -1, resume.exit_guess, limit);
  uint skip = MARCH_SKIPS ? resume.skip : 0u;
  if (MARCH_SKIPS && exit.searching) t = exit.t;
  const bool reachable = !(heights_only && INTEGRATOR == 0) || planes_z_reachable(ray, origin.z, hit_epsilon);
  // Planes x = c, y = c: a camera ray's first crossing solved
  // (plane_xy_roots); the march then takes the other objects up to it, or
  // is not needed.
  PlaneRoot xy;
  xy.solved = false;
  xy.k = -1;
  int root_steps = 0;
  if (camera && HAS_PLANES_XY && INTEGRATOR == 0) {
    xy = plane_xy_roots(ray, origin, g_count, g_types, g_constants, limit, hit_epsilon, max_steps, root_steps);
    if (planes_xy_only) {
      steps = root_steps;
      if (xy.k >= 0) {
        hit = xy.k + 1;
        t = xy.t;
        q = xy.q;
      }
    }
  }
  bool alive = reachable && !planes_xy_only;
  int step = resume.step;
  MarchStep s = march_step_none();
  bool shell = false;  // the step's nearest is an exact ball within kExactShell: finished exactly
  bool leaving_shell = false;  // the step's nearest is an exact ball the ray leaves (passed), near its sphere
  float leave_sign = 0.0;      // the sign of its exact distance's rate at the first such step (march_exact_step)
  vec3 u = vec3(0.0);  // the ray's tangent at q (frame components), for the clearances
  // (Without exact balls one round, a loop the compiler unrolls; with
  // PLANES_XY_ONLY none: the roots did all, and a loop whose condition is
  // not a constant would run its body once. The march pass of a deferred
  // world stops at the first exact ball's shell: one round, its exact block
  // left to the resume pass. Loops tested at their end: see march.comp.)
  const bool defer_shell = camera && DEFER_EXACT && PASS == kPassMarch;
  const bool rounds = HAS_EXACT_BALLS && !defer_shell;
  int round = 0;
  if (!planes_xy_only) do {
    if (step < max_steps && alive) do {
      if (!rk4) {
        // Cutout planes need the full position for their gap bounds (march_takes_tangent).
        if (march_takes_tangent(camera)) {
          const SolForward forward = zeta_only ? sol_forward_zeta(ray, t)
                                     : (zeta && zeta_round ? sol_forward_zeta(ray, t) : sol_forward(ray, t));
          q = forward.position;
          u = forward.direction;
        } else {
          q = heights_only ? vec3(0.0, 0.0, sol_height(ray, t)) : sol_position_forward(ray, t);
        }
      } else {
        rk4_advance(rk_p, rk_u, t - rk_t, g_rk4_step);
        rk_t = t;
        q = rk_p;
        u = rk_u;
      }
      if (translated) q = sol_translate(origin, q);
      if (HAS_PLANES_Z && !rk4 && !march_takes_tangent(camera)) u.z = climb_speed(direction, origin.z, q.z);
      if (MARCH_SKIPS && exit.searching) break;  // the exit search's trial point: solved below
      const vec2 hz = heights_only ? vec2(1.0) : half_exp(q.z);  // shared by the objects
      s = march_objects(q, u, hz, t, hit_epsilon, heights_only, passes, xy, seen, passing, leaving, skip);
      s.nearest = march_step_length(s, q, u, hz, hit_epsilon, camera, rk4);
      shell = HAS_EXACT_BALLS && g_types[s.nearest_k] == kObjectExactBall && s.nearest_hit < kExactShell;
      // The exact ball the ray leaves, still passed, near enough to hold the step back: its exact distance below.
      leaving_shell = HAS_EXACT_BALLS && !camera && g_types[s.nearest_any] == kObjectExactBall &&
                      (passing & (1u << uint(s.nearest_any))) != 0u && s.nearest < kExactShell;
      if (shell || leaving_shell) break;  // finished below
      steps = root_steps + step + 1;
      alive = march_step_end(s.nearest, s.nearest_hit, s.nearest_k, q, hit_epsilon, limit, passes, passing, t, hit);
    } while (++step < max_steps && alive);
    if (defer_shell) {
      if (shell && alive) {  // the rest of this ray in the resume pass
        h.deferred = true;
        h.resume = MarchResume(t, passing, step, 0u, -1, 0.0);
        return h;
      }
    } else if (zeta && zeta_round && shell && alive) {
      zeta_round = false;  // this step again, by Carlson's integrals (as the resume pass)
      shell = false;
    } else if (HAS_EXACT_BALLS && (shell || leaving_shell || (MARCH_SKIPS && exit.searching)) && alive) {
      steps = root_steps + step + 1;
      const bool searched = MARCH_SKIPS && exit.searching;
      alive = march_exact_step(q, u, hit_epsilon, limit, passes, leaving_shell, s, exact, seen, passing,
                               leave_sign, t, hit, exit);
      if (searched && !exit.searching) exit_search_ended(exit, resume.t, t, limit, skip);
      shell = leaving_shell = false;
      ++step;
    }
    alive = alive && step < max_steps;
  } while (rounds && ++round < max_steps && alive);

  if (MARCH_SKIPS && exit.found) exit_met(exit, limit, hit, t, q, exact);
  // Neither an object nor the limit: the steps ran out first.
  if (!planes_xy_only && reachable && hit == 0 && !(t > limit)) ++g_out_of_steps;
  // A camera ray that marched by heights alone takes its full position at the hit.
  if (hit != 0 && INTEGRATOR == 0 && heights_only && !HAS_CUTOUT) {
    sol_ray_integrals(ray);
    q = sol_position_forward(ray, t);
    if (HAS_ODS || HAS_LENS) q = sol_translate(origin, q);
  }
  MarchHit found = march_found(hit - 1, t, q, origin, steps, exact);
  // A mirror reflects the ray's tangent at the hit (the positions above may
  // have left it out); seen from inside a solid the normal faces it (surface_at).
  if ((HAS_MIRRORS || PATH_TRACING || HAS_INSIDE) && hit != 0) found.u = rk4 ? rk_u : sol_forward(ray, t).direction;
  found.exact_inside = HAS_INSIDE && exact.k == hit - 1 && exact.known && length(exact.v) < g_radii[exact.k];
  return found;
}

// ---- The march in the quotient (march_quotient in libsol/src/render.cpp)

// The quotient camera march's positions (sol_forward_zeta where the ray's
// μ is at least kZetaLeastMu, `by_zeta`, else sol_forward), its set-up
// and its restarts. With the resume pass (DEFER_SMALL_MU) each pass holds
// one of the two alone (constants); in one dispatch both are there and
// each ray takes its own.
const bool QUOTIENT_ZETA_ONLY = DEFER_SMALL_MU && PASS == kPassMarch;
const bool QUOTIENT_CARLSON_ONLY = DEFER_SMALL_MU && PASS == kPassResume;

void quotient_ray_prepared(inout SolRay g) {
  if (!QUOTIENT_CARLSON_ONLY) sol_ray_zeta(g);
  if (!QUOTIENT_ZETA_ONLY) sol_ray_integrals(g);
}

SolForward quotient_forward(SolRay g, float t, bool by_zeta) {
  if (QUOTIENT_ZETA_ONLY) return sol_forward_zeta(g, t);
  if (QUOTIENT_CARLSON_ONLY) return sol_forward(g, t, false);
  return by_zeta ? sol_forward_zeta(g, t) : sol_forward(g, t, false);
}

SolRay quotient_ray_restarted(SolRay g, float t0, SolForward f, bool by_zeta) {
  if (QUOTIENT_ZETA_ONLY) return sol_ray_restarted_zeta(g, f);
  if (QUOTIENT_CARLSON_ONLY) return sol_ray_restarted(g, t0, f, false);
  return by_zeta ? sol_ray_restarted_zeta(g, f) : sol_ray_restarted(g, t0, f, false);
}

// Rays in D, teleported back when a step ends outside. Each step is the
// least clearance along the ray (object_clearances) of the cell's candidate
// images (sol::QuotientField: every image that can be nearer than
// kFieldNear there, or else the nearest), capped at the cell's reach
// (field_reach: every other image is farther; one read instead of every
// image's bound), and the candidate that comes within hit_epsilon is the
// image hit. Steps stay within the world's longest step
// (sol::quotient_max_step), the reach of the listed images, which the
// reaches are capped at. Camera rays over-relax (march_quotient's): where
// the reach, not a candidate, limits a step, a longer proposal is kept
// where the clearance back from its end covers what the reach did not.
// Shadow rays take Carlson's positions and pass the images they start on.
MarchHit march_quotient(vec3 origin, vec3 direction, float limit, const int purpose) {
  const bool camera = purpose == kMarchCamera;
  const float hit_epsilon = params.limits.y;
  const int max_steps = int(params.limits.w);
  const int image_count = min(params.counts.x, kMaxGpuImages);
  MarchHit h = march_hit_none(kMarchFromStart);
  vec2 origin_scale = vec2(exp(origin.z), exp(-origin.z));  // sol_translate's, kept with origin
  // The ray's direction off the plane regime (sol_direction_off_plane_regime,
  // a change far below float rounding), so that no step evaluates that
  // regime's position for every ray.
  SolRay qray = sol_ray(sol_direction_off_plane_regime(direction));
  // A camera ray's positions by the zeta function, or by Carlson's
  // integrals where μ is small (quotient_forward); those rays left to the
  // resume pass.
  const bool by_zeta = camera && qray.mu >= kZetaLeastMu;
  if (camera && DEFER_SMALL_MU && PASS == kPassMarch && !by_zeta) {
    h.deferred = true;  // this ray in the resume pass, by Carlson's integrals
    return h;
  }
  if (camera) {
    quotient_ray_prepared(qray);
  } else {
    sol_ray_integrals(qray);
  }
  float t = 0.0, local_t = 0.0;
  int hit_image = -1, steps = 0;
  vec3 q = origin;
  ExactSolve exact = exact_solve_none();
  // What the exact solves have shown (exact_seen_bound), by image: a
  // teleport moves the point among the images, so it starts afresh there.
  ExactSeen seen = exact_seen_none();
  // A shadow ray's images it leaves: up to four, by index (and for exact
  // balls the sign of the rate of their distance at the first solve, as
  // march_exact_step's `leave_sign`).
  ivec4 passing = ivec4(-1);
  vec4 leave_signs = vec4(0.0);
  if (!camera) {
    const uint word = field_candidates(field_cell(q));
    const bool all = word == kFieldAllImages;
    int held = 0;
    for (int s = 0; s < (all ? image_count : kFieldCandidates); ++s) {
      const int i = all ? s : int((word >> uint(8 * s)) & 255u);
      if (i == kFieldEmpty || held == 4) continue;
      const Image m = images[i];
      if (image_distance(image_type(m), q, m) < 2.0 * hit_epsilon) {
        // (A solid it leaves through the face it starts on: leave sign 1, as the CPU's leaving_sign.)
        if (HAS_INSIDE && image_leaves_through_start(image_type(m), q, direction, m)) leave_signs[held] = 1.0;
        passing[held++] = i;
      }
    }
  }
  // Over-relaxation: `proposal` is the step from q, the last point the
  // march moved to, and `covered` the part of it q's own bounds clear.
  float proposal = 0.0, covered = 0.0;
  vec3 u = vec3(0.0, 0.0, 1.0);  // with mirrors: the tangent at q (frame components)
  bool ended = false;  // at a hit or the limit (else the steps ran out first)
  for (int step = 0; step < max_steps; ++step) {
    SolForward forward = camera ? quotient_forward(qray, local_t + proposal, by_zeta)
                                : sol_forward(qray, local_t + proposal, false);
    vec3 e = sol_translate(origin, origin_scale, forward.position);
    const bool outside = !in_domain(e);
    float turn = 1.0;  // -1: the teleport turned the fibre (teleport), and the direction's frame components
    if (outside) e = teleport(e, true, turn);
    forward.direction.xy *= turn;
    if (outside) seen = exact_seen_none();
    const int cell = field_cell(e);
    steps = step + 1;
    const uint word = field_candidates(cell);
    const bool all = word == kFieldAllImages;
    const vec2 hz = half_exp(e.z);  // shared by the candidates' clearances
    QuotientCandidates c = quotient_candidates(word, all, all ? image_count : field_candidate_count(word), e,
                                               forward.direction, hz, camera, hit_epsilon, seen, t + proposal, passing,
                                               leave_signs);
    quotient_exact_step(e, forward.direction, hit_epsilon, t + proposal, c, exact, seen, passing, leave_signs);
    const float reach = field_reach(cell);
    if (camera && proposal > covered && covered + min(c.back, reach) < proposal) {
      proposal = covered;  // not covered: the plain step instead
      if (outside) seen = exact_seen_none();  // (noted beyond a teleport the plain step may not take)
      continue;
    }
    // The march moves to e. The same geodesic goes on from a teleported
    // point, restarted from what the positions found there.
    t += proposal;
    if (outside) {
      origin = e;
      origin_scale = hz * hz;  // e^{±z} of e
      qray = camera ? quotient_ray_restarted(qray, local_t + proposal, forward, by_zeta)
                    : sol_ray_restarted(qray, local_t + proposal, forward, false);
      // A turned restart goes on along the half-turned geodesic: the signs
      // of its x and y (applied last to every position and direction).
      qray.sign_x *= turn;
      qray.sign_y *= turn;
      qray.direction.xy *= turn;
      local_t = 0.0;
    } else {
      local_t += proposal;
    }
    q = e;
    if (HAS_MIRRORS || PATH_TRACING || HAS_INSIDE) u = forward.direction;
    if (c.nearest < hit_epsilon) {
      hit_image = c.nearest_i;
      ended = true;
      break;
    }
    const float clear = min(c.clear_nearest, c.clear_rest);
    float step_length = min(clear, reach);
    if (!camera && any(greaterThanEqual(passing, ivec4(0)))) step_length = max(step_length, 2.0 * hit_epsilon);
    if (t + step_length > limit) {
      ended = true;
      break;
    }
    covered = step_length;
    proposal = camera && reach < clear ? min(max(step_length, min(kQuotientOverRelax * step_length, kQuotientMaxStep)), limit - t)
                                       : step_length;
  }
  if (!ended) ++g_out_of_steps;
  MarchHit found = march_found(hit_image, t, q, origin, steps, exact);
  found.u = u;
  found.exact_inside = HAS_INSIDE && hit_image >= 0 && exact.k == hit_image && exact.known &&
                       length(exact.v) < images[hit_image].bound.w;
  return found;
}

#include "crowd.glsl"

// The march of any ray: from `origin` (march coordinates: relative to the
// eye in Sol, world coordinates in D in the quotient) along the unit
// `direction` up to arc length `limit`, picked up at `resume` (Sol; the
// quotient's deferred rays start afresh).
MarchHit march(vec3 origin, vec3 direction, float limit, MarchResume resume, const int purpose) {
  if (QUOTIENT) return march_quotient(origin, direction, limit, purpose);
  if (CROWD) return march_crowd(origin, direction, limit, purpose);
  return march_sol(origin, direction, limit, resume, purpose);
}

#endif  // SOL_MARCH_MARCH_GLSL
