// A march step in Sol over a listed world's objects (g_*, load_objects):
// the objects' distances from the ray's point (march_objects), the step's
// end (a hit, a pass between a cutout plane's discs, or the advance), and
// the step finished by an exact ball's exact distance (march_exact_step).
// march_sol (march.glsl) takes the positions and calls these.
#ifndef SOL_MARCH_STEPS_GLSL
#define SOL_MARCH_STEPS_GLSL

#include "sol/exit_search.h"  // the exit search's rounds, shared with libsol

// The end of a march step whose nearest object (for a hit) is nearest_k at
// nearest_hit and whose step is `nearest`: a hit (`hit` set), a pass
// between a cutout plane's discs, or the advance (at least 2 hit_epsilon
// while `passes` and the ray passes an object). Returns whether the march
// goes on.
bool march_step_end(float nearest, float nearest_hit, int nearest_k, vec3 q, float hit_epsilon, float limit,
                    const bool passes, inout uint passing, inout float t, inout int hit) {
  if (nearest_hit < hit_epsilon) {
    if (HAS_CUTOUT && scene_objects[nearest_k].plane.w != 0.0) {
      // (Full positions whenever the scene has cutouts.)
      const vec2 uv = object_pattern_uv(g_types[nearest_k], q, pattern_phase(q, g_eye_camera, g_eye_frac),
                                        g_relative[nearest_k], g_headings[nearest_k], g_radii[nearest_k]);
      if (pattern_factor(int(scene_objects[nearest_k].plane.z), uv.x, uv.y) != 1.0) {
        passing |= 1u << uint(nearest_k);  // between the discs: go through
        t += max(nearest, 2.0 * hit_epsilon);
        return !(t > limit);
      }
    }
    hit = nearest_k + 1;
    return false;
  }
  t += (passes && passing != 0u) ? max(nearest, 2.0 * hit_epsilon) : nearest;
  return !(t > limit);
}

// One step's findings over the objects (march_objects): the least distance
// (`nearest`, of object `nearest_any`) and the least to the others
// (`others`); the nearest candidate hit (`nearest_hit`, `nearest_k`: not an
// object being passed) and, with exact balls, the runner-up (`second_hit`,
// `second_k`), for when the nearest is an exact ball. Exact balls count
// by what their solves have shown where that is more than their bound
// (`seen`, exact_seen_bound).
struct MarchStep {
  float nearest, nearest_hit, others, second_hit;
  int nearest_k, nearest_any, second_k;
};

MarchStep march_step_none() { return MarchStep(1e30, 1e30, 1e30, 1e30, 0, 0, 0); }

// The objects' distances from q at arc length t (hz: q.z's half
// exponentials), updating the mask of objects being passed. Planes x = c,
// y = c whose crossing is solved (`xy`) answer the arc length left to it;
// the objects of the mask `skip` are not there (MarchResume::skip).
MarchStep march_objects(vec3 q, vec3 u, vec2 hz, float t, float hit_epsilon, const bool heights_only, const bool passes,
                        PlaneRoot xy, ExactSeen seen, inout uint passing, uint leaving, uint skip) {
  MarchStep s = march_step_none();
  int k = 0;
  if (g_count > 0) do {  // (tested at its end: see march.comp)
    float d = heights_only ? abs(q.z - g_constants[k])
                           : object_distance(g_types[k], q, g_relative[k], g_headings[k], g_radii[k], hz, g_half_exp_z[k]);
    if (HAS_EXACT_BALLS && g_types[k] == kObjectExactBall) d = exact_seen_bound(seen, k, t, d);
    if (MARCH_SKIPS && (skip & (1u << uint(k))) != 0u) d = 1e30;
    if (HAS_PLANES_XY && xy.solved && (g_types[k] == kObjectPlaneX || g_types[k] == kObjectPlaneY)) {
      d = k == xy.k ? max(xy.t - t, 0.0) : 1e30;  // solved: the arc length left to its crossing
    }
    if (HAS_CUTOUT && g_cutouts[k] != 0) {
      d = max(d, cutout_gap_bound(g_cutouts[k], pattern_phase(q, g_eye_camera, g_eye_frac).xy, g_eye_camera.w * exp(q.z)));
    }
    // Objects being passed (cutout planes between their discs, the surface
    // a shadow ray leaves) are not hits until the ray is 2 hit_epsilon away
    // again (as the CPU reference).
    const uint bit = 1u << uint(k);
    // The surface it leaves: passed until 2 hit_epsilon away, or (seen from
    // inside) until the ray heads for a face of it (sol::InsideClearances;
    // exact balls: march_exact_step), unless it leaves through the face it
    // started on (`leaving`: it heads for that face from the start).
    if (passes && (passing & bit) != 0u) {
      bool heads = false;
      if (HAS_INSIDE && inside_by_bound(g_types[k]) && (leaving & bit) == 0u) {
        const float raw = object_bound(g_types[k], q, g_relative[k], g_headings[k], g_radii[k], hz, g_half_exp_z[k]);
        heads = raw < -kHeadsDepth * hit_epsilon && object_inside_clearances(g_types[k], q, u, g_relative[k], g_headings[k], g_radii[k], hz,
                                                      g_half_exp_z[k], -raw).w < 0.0;
      }
      // Not seen from inside, a solid drawn by its bound is passed until
      // the ray is 2 hit_epsilon out of it or into it (passed_into,
      // sinks_into; exact balls: march_exact_step).
      const bool into = passed_into(g_types[k], d, hit_epsilon) ||
                        (may_sink_into(g_types[k], d) &&
                         sinks_into(object_inside_clearances(g_types[k], q, u, g_relative[k], g_headings[k], g_radii[k], hz,
                                                             g_half_exp_z[k], -d)));
      // A plane z = c is passed until the ray turns back towards it (u_z
      // turns from the start's: `leaving` says upward): one that leaves it
      // almost level bends back into it (z'' = u2² - u1²) before it is 2
      // hit_epsilon away (as the CPU's pass_ends).
      const bool turned = HAS_PLANES_Z && g_types[k] == kObjectPlaneZ && ((leaving & bit) != 0u ? u.z < 0.0 : u.z > 0.0);
      if (d > 2.0 * hit_epsilon || heads || into || turned) passing &= ~bit;
    }
    if (d < s.nearest) {
      s.others = s.nearest;
      s.nearest_any = k;
    } else {
      s.others = min(s.others, d);
    }
    s.nearest = min(s.nearest, d);
    if ((!passes || (passing & bit) == 0u) && d < s.nearest_hit) {
      if (HAS_EXACT_BALLS) {
        s.second_hit = s.nearest_hit;
        s.second_k = s.nearest_k;
      }
      s.nearest_hit = d;
      s.nearest_k = k;
    } else if (HAS_EXACT_BALLS && (!passes || (passing & bit) == 0u) && d < s.second_hit) {
      s.second_hit = d;
      s.second_k = k;
    }
  } while (++k < g_count);
  return s;
}

// The step where the nearest object (s.nearest_any) is a ball or a tube:
// its clearance along the ray (object_clearance) up to the others' least
// distance (as the CPU's march_cover: one clearance a step). An exact
// ball's distance may be more than its bound's clearance: what a solve has
// shown (exact_seen_bound).
float march_clearance_step(MarchStep s, vec3 q, vec3 u, vec2 hz) {
  const int k = s.nearest_any;
  const float clear = object_clearance(g_types[k], q, u, g_relative[k], g_headings[k], g_radii[k], hz, g_half_exp_z[k]).y;
  return min(s.others, HAS_EXACT_BALLS ? max(s.nearest, clear) : clear);
}

// The step where the nearest object is a plane z = c: how far the ray
// stays more than hit_epsilon from it (plane_z_step), up to the others'
// least distance; at least the plane's distance (a cutout's gap bound may
// be more).
float march_plane_z_step(MarchStep s, vec3 q, vec3 u, float hit_epsilon) {
  return min(s.others, max(s.nearest, plane_z_step(q, u, g_relative[s.nearest_any].x, hit_epsilon)));
}

// The step where the nearest object is a plane x = c or y = c whose
// crossing is not solved: how far the ray stays more than hit_epsilon from
// it (plane_xy_step), up to the others' least distance.
float march_plane_xy_step(MarchStep s, vec3 q, vec3 u, float hit_epsilon) {
  const int k = s.nearest_any;
  return min(s.others, max(s.nearest, plane_xy_step(q, u, g_types[k], g_constants[k], hit_epsilon)));
}

// Whether march_sol takes the ray's tangent at each step (full positions by
// sol_forward): every ray but the camera rays of a world without solids or
// cutouts (RK4 carries its own), which take climb_speed's |u_z| instead.
bool march_takes_tangent(bool camera) { return HAS_SOLIDS || HAS_CUTOUT || !camera; }

// A camera ray's |u_z| at height z from its direction at its start's
// height z0 alone: u1 e^{-z} and u2 e^{z} are constant along a geodesic
// (u1' = u1 u3, u2' = -u2 u3), and u3² = 1 - u1² - u2². For the camera
// rays of a world without solids or cutouts, whose march takes positions
// (or heights) alone: the plane z = c step of march_step_length.
float climb_speed(vec3 direction, float z0, float z) {
  const float e = exp(z - z0);
  const float u1 = direction.x * e, u2 = direction.y / e;
  return sqrt(max(1.0 - u1 * u1 - u2 * u2, 0.0));
}

// The step of march_sol from q (tangent u, known unless a camera ray in a
// world without solids or cutouts: then u.z holds |u_z|, climb_speed). The nearest solid's clearance for camera rays, for
// every segment and connection of a path (one that leaves a wall almost
// level crawled by the bound, 2 hit_epsilon a step while it passed the
// wall, and ran out of steps: the CPU steps every ray so), and for every
// ray in a frame whose eye is inside a solid (object_inside_clearances);
// a direct-light shadow ray steps by the bound (inside the light's loop
// over its geodesics one clearance a step made shadowed scenes 10-25 %
// slower on lavapipe though the steps fell tenfold). A plane z = c: its
// clearance to hit_epsilon for every ray whose tangent is known
// (march_plane_z_step: one square root; a ray leaving a floor almost level
// crawled by |z - c|), and for the other camera rays the same with the
// ray taken as heading for it (plane_z_step_heading: a ray that turns
// just short of a plane crawled by |z - c| about its turning point and
// could run out of steps). A plane x = c or y = c whose crossing is not solved
// (every ray but a camera ray of the closed form): likewise its clearance
// (march_plane_xy_step; one arriving at a grazing angle crawled by its distance).
float march_step_length(MarchStep s, vec3 q, vec3 u, vec2 hz, float hit_epsilon, bool camera, bool rk4) {
  const int type = g_types[s.nearest_any];
  if ((camera || HAS_INSIDE || PATH_TRACING) && object_is_solid(type)) return march_clearance_step(s, q, u, hz);
  if (HAS_PLANES_Z && type == kObjectPlaneZ) {
    if (march_takes_tangent(camera) || rk4) return march_plane_z_step(s, q, u, hit_epsilon);
    // A camera ray whose tangent the march does not take: |u_z| alone (u.z, climb_speed).
    return min(s.others, max(s.nearest, plane_z_step_heading(s.nearest, u.z, hit_epsilon)));
  }
  if (HAS_PLANES_XY && (!camera || rk4) && (type == kObjectPlaneX || type == kObjectPlaneY)) {
    return march_plane_xy_step(s, q, u, hit_epsilon);
  }
  return s.nearest;
}

// ---- The exit of a convex exact ball (MarchResume::exit_k): a path
// segment that leaves the inner wall of an exact ball of radius below
// kConvexBallRadius (< π/2). There the distance f from its centre is convex
// along the ray (the Hessian comparison with sectional curvatures at most
// 1: Hess d >= cot(d) (g - ∇d ∇d) >= 0 below π/2, before the cut locus, at
// least √2π away), so the exit, where f first reaches r - hit_epsilon/2
// after the wall, is Newton's root from any trial where f' > 0: from
// before it (past the nearest approach) Newton jumps beyond it, and from
// beyond it falls onto it (monotonically while f stays below π/2); the
// rounds' arithmetic is sol/exit_search.h, shared. A trial is one position
// and one exact solve, a round of the march: about 3 rounds where the
// ball's safe clearances (exact_ball_inside_clearance) take about 8 (a
// chord has no tighter safe step: its curvature bound is within a quarter
// of the truth). Found, the march goes back to the wall and marches the
// other objects without the ball up to the exit, where, met by none, the
// ray meets the ball; not found within kExitRounds (a solve that does not
// land, a trial that is outside while heading in), it marches as any ray.
// The CPU searches the same way (exact_ball_exit in libsol/src/render.cpp).

struct ExitSearch {
  int k;           // the ball (-1: none)
  bool searching;  // t is the trial
  bool found;
  float t;         // the trial, then the exit
  int rounds;
  ExactSolve solve;  // the solve at the exit, and the point
  vec3 q;
};

// The search for ball k's exit (-1: none) from the trial `guess`, within the march's limit.
ExitSearch exit_search_start(int k, float guess, float limit) {
  return ExitSearch(k, k >= 0, false, min(guess, limit), 0, exact_solve_none(), vec3(0.0));
}

// The search has ended: the march goes back to its start (`start`), and
// where the exit was found marches the others without the ball up to it.
void exit_search_ended(ExitSearch e, float start, inout float t, inout float limit, inout uint skip) {
  t = start;
  if (e.found) {
    limit = min(limit, e.t);
    skip |= 1u << uint(e.k);
  }
}

// The exit found and nothing met before it (the march past its limit): the
// hit is the ball's, at its exit, with the solve there.
void exit_met(ExitSearch e, float limit, inout int hit, inout float t, inout vec3 q, inout ExactSolve exact) {
  if (hit != 0 || !(t > limit)) return;
  hit = e.k + 1;
  t = e.t;
  q = e.q;
  exact = e.solve;
}

// Newton's round at the trial e.t, from the exact solve x of ball e.k at
// the ray's point q there (sdf = f - r, slope = f' where x.known), the
// trials below 2r + hit_epsilon (within which a geodesic that has left
// the ball cannot meet it again: docs/lighting.md, "Enclosures") and the
// march's limit.
void exit_newton(inout ExitSearch e, ExactSolve x, float sdf, float slope, vec3 q, float hit_epsilon, float limit) {
  bool give_up = !x.known || ++e.rounds > kExitRounds;
  if (!give_up && sol_exit_found(sdf, slope, hit_epsilon)) {
    e.found = true;
    e.solve = x;
    e.q = q;
  } else if (!give_up) {
    e.t = sol_exit_next(e.t, sdf, slope, g_radii[e.k], hit_epsilon);
    give_up = !(e.t > 0.0 && e.t <= limit);
  }
  e.searching = !(e.found || give_up);
}

// A step of the Sol march that came within kExactShell of an exact ball
// (s.nearest_k), finished by its exact distance (steps, and hits on the
// true sphere) against the least distance to every other object: the step
// beyond it by the ball's clearance along the ray (its rate from the
// sphere's normal), outside or, seen from inside, inside. Or (`leaving`) a
// step of a ray that leaves an exact ball's sphere (s.nearest_any, passed),
// either way, near the sphere, where its bound is negative on both sides
// (the bound's ball holds the exact one) and would hold the pass for every
// step: solved exactly, the pass ends once |sdf| is 2 hit_epsilon (as
// march_objects' for the others), the ball a hit candidate again; the
// others' candidate stands, and is taken first (else a ball near both
// would hold the pass, the ray crawling by 2 hit_epsilon a step). One
// exact solve for both (each call is inlined, a Newton loop each), noted
// in `seen`. An exact ball not solved at the step is no hit by its bound
// (the runner-up, or the candidate while the ray leaves another): the
// step (at most its bound) brings its own solve. Returns whether the
// march goes on (march_step_end).
bool march_exact_step(vec3 q, vec3 u, float hit_epsilon, float limit, const bool passes, bool leaving, inout MarchStep s,
                      inout ExactSolve x, inout ExactSeen seen, inout uint passing, inout float leave_sign, inout float t,
                      inout int hit, inout ExitSearch exit) {
  const bool exiting = MARCH_SKIPS && exit.searching;
  const int e = exiting ? exit.k : (leaving ? s.nearest_any : s.nearest_k);
  const float sdf = exact_ball_sdf(q, g_relative[e].xyz, g_radii[e], e, x);
  const float slope = dot(x.end.tangent, u);  // the exact distance's rate along the ray (where x.known)
  exact_seen_solved(seen, x.known, e, sdf, t);
  if (exiting) {  // the exit search's round (exit_newton): the next trial
    exit_newton(exit, x, sdf, slope, q, hit_epsilon, limit);
    if (exit.searching) t = exit.t;
    return true;
  }
  if (leaving) {
    const float away = x.known ? abs(sdf) : 0.0;  // (where the solve did not land: the passing's least step)
    if (exact_pass_ends(x.known, away, slope, hit_epsilon, leave_sign)) passing &= ~(1u << uint(e));
    const float beyond = HAS_INSIDE && x.known && sdf < 0.0 ? exact_ball_inside_clearance(away, length(x.v), slope, hit_epsilon)
                                                             : away;
    s.nearest = min(s.others, beyond);
    // (A candidate that is an exact ball, not solved at this step, is no hit.)
    const float candidate = g_types[s.nearest_k] == kObjectExactBall ? max(s.nearest_hit, hit_epsilon) : s.nearest_hit;
    return march_step_end(s.nearest, candidate, s.nearest_k, q, hit_epsilon, limit, true, passing, t, hit);
  }
  const float exact = HAS_INSIDE && x.known ? abs(sdf) : sdf;
  float exact_step = exact;
  if (x.known && sdf > hit_epsilon) {
    exact_step = exact_ball_clearance(exact, length(x.v), slope, hit_epsilon);
  } else if (HAS_INSIDE && x.known && sdf < -hit_epsilon) {
    exact_step = exact_ball_inside_clearance(exact, length(x.v), slope, hit_epsilon);
  }
  s.nearest = min(s.nearest_any == s.nearest_k ? s.others : s.nearest, exact_step);
  if (exact <= s.second_hit || g_types[s.second_k] == kObjectExactBall) {
    s.nearest_hit = exact;
  } else {
    s.nearest_hit = s.second_hit;
    s.nearest_k = s.second_k;
  }
  return march_step_end(s.nearest, s.nearest_hit, s.nearest_k, q, hit_epsilon, limit, passes, passing, t, hit);
}

#endif  // SOL_MARCH_STEPS_GLSL
