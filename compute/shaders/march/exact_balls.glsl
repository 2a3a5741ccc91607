// Exact balls (kObjectExactBall) near their sphere: their exact distance by
// the shortest geodesic from the centre (sol_connection.glsl), the true
// sphere's normal, and the clearance that lets a step pass beside them.
// Far from the sphere they are marched by their bound (objects.glsl).
#ifndef SOL_MARCH_EXACT_BALLS_GLSL
#define SOL_MARCH_EXACT_BALLS_GLSL

// A march's last exact solve: the exact ball (object or image) `k` whose
// shortest geodesic from its centre has the initial vector `v` and ends at
// `end`, whether that is a solution to start the next solve from
// (`known`), and the solve's Jacobian (sol_newton).
struct ExactSolve {
  int k;
  vec3 v;
  SolEnd end;
  bool known;
  mat3 J;
};

ExactSolve exact_solve_none() { return ExactSolve(-1, vec3(0.0), SolEnd(vec3(0.0), vec3(0.0, 0.0, 1.0)), false, mat3(1.0)); }

// What a march's exact solves have shown, for the last two exact balls
// solved (objects, images or items `k`; -1: none): the distance to the
// sphere `value` found at arc length `at` (|sdf| where the eye may be
// inside a solid, else sdf). A distance is 1-Lipschitz along a unit-speed
// geodesic, so value - |t - at| stays a lower bound of it at arc length t,
// and the march takes it where it is more than the ball's bound
// (exact_seen_bound). Where exact balls overlap, the march then solves
// each in turn (its nearest by that measure), not the one whose bound is
// least forever with the other taken by its bound; and an exact ball's
// bound never makes a hit (march_exact_step): a hit is on a true sphere,
// the nearer one.
struct ExactSeen {
  ivec2 k;
  vec2 value, at;
};

ExactSeen exact_seen_none() { return ExactSeen(ivec2(-1), vec2(0.0), vec2(0.0)); }

// Ball k's distance at arc length t: the march's `d` (its bound), or more
// where a solve has shown more.
float exact_seen_bound(ExactSeen s, int k, float t, float d) {
  const vec2 lower = mix(vec2(-1e30), s.value - abs(vec2(t) - s.at), equal(s.k, ivec2(k)));
  return max(d, max(lower.x, lower.y));
}

// Notes ball k's distance `value` at arc length t (a solve that landed),
// in the first slot, the other ball's in the second.
void exact_seen_note(inout ExactSeen s, int k, float value, float t) {
  if (s.k.x != k) {
    s.k.y = s.k.x;
    s.value.y = s.value.x;
    s.at.y = s.at.x;
  }
  s.k.x = k;
  s.value.x = value;
  s.at.x = t;
}

// Notes ball k's solve at arc length t where it landed (`known`): its
// distance to the sphere sdf, taken as |sdf| where the eye may be inside a solid.
void exact_seen_solved(inout ExactSeen s, bool known, int k, float sdf, float t) {
  if (known) exact_seen_note(s, k, HAS_INSIDE ? abs(sdf) : sdf, t);
}

// Exact balls near their sphere: the exact distance from the centre c to q
// less the radius, from the shortest geodesic from c to q (sol_shortest,
// started from the last solve of the same ball when there is one, and left
// holding this one); where Newton does not land, the bound (safe, but the
// hit then lies on the bound's surface) and the next solve starts afresh.
float exact_ball_sdf(vec3 q, vec3 c, float radius, int k, inout ExactSolve x) {
  if (x.k != k) x.known = false;
  x.k = k;
  const vec3 w = vec3((q.x - c.x) * exp(-c.z), (q.y - c.y) * exp(c.z), q.z - c.z);
  const float residual = sol_shortest(w, x.v, x.end, x.known, x.J);
  if (residual < 2e-4) return length(x.v) - radius;
  x.known = false;
  return distance_lower_bound(q, c) - radius;
}

// The true sphere's outward normal at the end of the geodesic from its
// centre (the last solve's end): that geodesic's tangent there (frame
// components), as sol::sdf_ball_exact_gradient.
vec3 exact_sphere_normal(SolEnd end) { return normalize(end.tangent); }

// The clearance of an exact ball from q (the kernel's own: the CPU steps by
// the exact distance; derivation in docs/exact.md), where its exact
// distance is f = d - r (d the distance from the centre) and f' = slope
// along the ray, for steps of at most kExactClearanceCap. Sol's
// sectional curvatures are at most 1 (its curvature operator is diagonal
// in the frame, +1, -1, -1), so by the Hessian comparison theorem
// Hess d >= cot(d) (g - ∇d ∇d) where d < π, before any conjugate or cut
// point (those lie at least √2 π away): along the ray f'' >= min(0, cot d),
// and over the step d stays below D = d + cap. So f'' >= -M with M = 0
// where D <= π/2 (f convex: a Newton step never passes its root), -cot D
// up to π - 0.1, and no clearance beyond. Aimed at f = hit_epsilon/2, so
// that float rounding of the slope does not carry the step into the ball.
float exact_ball_clearance(float f, float d, float slope, float eps) {
  const float D = d + kExactClearanceCap;
  const float bend = D <= 1.5707963 ? 1e-6 : -cos(D) / sin(D);
  const float s = min(clearance_root(f - 0.5 * eps, slope, bend), kExactClearanceCap);
  return D < 3.0415927 ? max(f, s) : f;
}

// The clearance of an exact ball seen from inside: g = r - d > 0 the
// exact distance to the sphere, `slope` = d' along the ray (so g' =
// -slope), for steps of at most d/2 and kExactClearanceCap. Sol's
// sectional curvatures are at least -1, so by the Hessian comparison
// theorem Hess d <= coth(d) (g - ∇d ∇d) before any cut point (the
// kernel's balls, r <= 2, lie well within the cut time, at least √2 π):
// along the ray d'' <= coth(d), and over a step of at most d/2, d stays
// above d/2, so g'' >= -M with M = coth(d/2). The step is the first root
// of g - eps/2 - slope s - ½ M s² (aimed at g = eps/2, as
// exact_ball_clearance), at least g itself. A ray that leaves the wall
// inward at angle θ to the normal steps about the chord, 2 cos θ r / M,
// instead of crawling out by sphere tracing.
float exact_ball_inside_clearance(float g, float d, float slope, float eps) {
  const float half_d = 0.5 * d;
  const float bend = cosh(half_d) / max(sinh(half_d), 1e-30);
  const float s = min(clearance_root(g - 0.5 * eps, -slope, bend), min(half_d, kExactClearanceCap));
  return max(g, s);
}

// Whether a ray that leaves an exact ball's sphere (passing it) stops
// passing it at this step, the ball a hit candidate again: once it is 2
// hit_epsilon away (`away`, |sdf|, where the solve landed: `known`), or
// where it turns back towards the sphere, the rate of its distance from
// the centre (`slope`) of the other sign than at the first step
// (`leave_sign`, 0 before it and again once the pass ends): a grazing chord
// of the inner wall may never be 2 hit_epsilon deep (exact_ball_turned_back
// in libsol/src/render.cpp).
bool exact_pass_ends(bool known, float away, float slope, float hit_epsilon, inout float leave_sign) {
  const bool turned = known && leave_sign != 0.0 && slope * leave_sign < 0.0;
  if (known && leave_sign == 0.0 && slope != 0.0) leave_sign = sign(slope);
  const bool ends = away > 2.0 * hit_epsilon || turned;
  if (ends) leave_sign = 0.0;
  return ends;
}

#endif  // SOL_MARCH_EXACT_BALLS_GLSL
