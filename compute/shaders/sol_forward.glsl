// Positions and tangents along a prepared ray (SolRay, sol_ray.glsl) at an
// arc length: by Carlson's integrals (sol_forward) or by Jacobi's zeta
// function (sol_forward_zeta); restarting a ray where it arrived (the
// quotient's teleports); and the group law's left translation of a
// position. Part of sol_geodesic.glsl.
#ifndef SOL_FORWARD_GLSL
#define SOL_FORWARD_GLSL

#include "sol_ray.glsl"

// What sol_forward found on its way to a position: enough to restart the
// ray there without another Jacobi or Carlson evaluation (sol_ray_restarted).
struct SolForward {
  vec3 position;   // relative to the start
  vec3 direction;  // the unit tangent there (frame components)
  SolPoint point;  // the path's values there (general regime)
  vec2 near;       // the integrals from the start of the point's quarter (or the ray's start, `same`) to it
  bool same;       // the point lies in the start's quarter
  float zeta;      // sol_forward_zeta: Z at the point's phase
  float inv_ew;    // sol_forward_zeta: e^{-w} there (point.ew's reciprocal)
  float phase;     // sol_forward_zeta: the phase u evaluated
};

// sol_forward's (and sol_forward_zeta's) position and tangent at arc
// length t for the regimes other than the general one (the plane regime's
// where `plane_regime`, a constant).
void sol_forward_regimes(SolRay g, float t, const bool plane_regime, inout SolForward f) {
  if (plane_regime) {
    vec3 plane_direction;
    const vec3 plane = sol_plane_position(g, t, plane_direction);
    f.position = g.regime == REGIME_PLANE ? plane : f.position;
    f.direction = g.regime == REGIME_PLANE ? plane_direction : f.direction;
  }
  f.position = g.regime == REGIME_VERTICAL ? vec3(0.0, 0.0, g.c * t) : f.position;
  f.position = g.regime == REGIME_STRAIGHT ? vec3(g.direction.x * t, g.direction.y * t, 0.0) : f.position;
  f.direction = g.regime == REGIME_VERTICAL || g.regime == REGIME_STRAIGHT ? g.direction : f.direction;
}

// The rest of sol_forward at arc length t, whose point p and integral (of
// sol_carlson_y's coordinate, from the start) are found: the height, the
// tangent, the other coordinate from the first integral, the other regimes.
void sol_forward_at(SolRay g, float t, SolPoint p, float integral, const bool plane_regime, inout SolForward f) {
  const bool carlson_y = sol_carlson_y(g);
  const float z = log(p.ew) - g.w0;
  // The tangent's frame components: |u1| = |a| e^{z} = √μ e^{w}, |u2| = |b| e^{-z}.
  const float u1 = g.sqrt_mu * p.ew, u2 = g.sqrt_mu / p.ew;
  f.direction = vec3(g.sign_x * u1, g.sign_y * u2, -g.k * g.lambda * p.jac.x);
  // The first integral: a x - b y = c - z' (signed a, b, c: the start's direction);
  // c² - z'² = u1² - a² + u2² - b² (|u| = 1 at both ends).
  const float a = g.direction.x, b = g.direction.y, c = g.direction.z, dz = f.direction.z;
  const float energy = ((u1 - g.a) * (u1 + g.a) + (u2 - g.b) * (u2 + g.b)) / (c + dz);
  const float c_minus_dz = c * dz > 0.0 && abs(c + dz) >= 0.5 ? energy : c - dz;
  const float y = g.sign_y * g.a * integral, x = g.sign_x * g.b * integral;
  f.position = carlson_y ? vec3((c_minus_dz + b * y) / a, y, z) : vec3(x, (a * x - c_minus_dz) / b, z);
  sol_forward_regimes(g, t, plane_regime, f);
}

// Position (relative to the start) at arc length t >= 0 (a march's), and
// what was found on the way (SolForward), after sol_ray_integrals: as
// sol_position, with the piece from the start to the end of its quarter
// precomputed (SolRay::far_forward), and for one coordinate: one Carlson R_D
// per call where sol_position takes two pairs (`near` holds that coordinate
// alone). The coordinate with the larger of |a|, |b| in a x - b y = c - z'
// (the first integral along a geodesic from the origin with unit direction
// (a, b, c); docs/mathematics.md) comes from the other: x = (c - z' + b y)/a
// where |a| >= |b|, else y = (a x - c + z')/b. Where c and z' share their
// sign and |c + z'| >= 1/2, c - z' (both near ±1 on a steep ray, whose |a|,
// |b| are small) is taken without cancellation from |u| = 1 as
// (c² - z'²)/(c + z'), c² - z'² = u1² - a² + u2² - b² (the tangent's frame
// components u1 = a e^{z}, u2 = b e^{-z}), whose rounding scales with a², b²
// and which leaves x its relative accuracy; elsewhere c - z' is not small,
// or max(|a|, |b|) is not.
//
// `plane_regime` (a constant at each call): whether g may be of the plane
// regime. Without it (a ray from sol_direction_off_plane_regime) the plane
// regime's position, three exp and a log that lavapipe evaluates for every
// ray (a select, below), is left out.
SolForward sol_forward(SolRay g, float t, const bool plane_regime) {
  SolForward f;
  const float u = g.lambda * t + g.u0;
  const SolPoint p = sol_point(g, u);
  f.point = p;
  const int q = sol_absolute_quarter(g, u, p.quarter);
  f.same = q <= g.start_quarter;
  float gap_near;
  vec3 f_near = sol_anchor(g, p, sol_start_anchor(p.quarter), gap_near);
  f_near = f.same ? g.start_factors : f_near;
  gap_near = f.same ? sol_two_point_gap(g.start, p) : gap_near;
  const bool carlson_y = sol_carlson_y(g);
  const float near = sol_piece_one(g, f_near, sol_factors(p), gap_near);
  f.near = carlson_y ? vec2(0.0, near) : vec2(near, 0.0);
  const vec2 whole = sol_quarters(g, g.start_quarter + 1, q - 1);
  const float integral = f.same ? near : (carlson_y ? g.far_forward.y + whole.y : g.far_forward.x + whole.x) + near;
  sol_forward_at(g, t, p, integral, plane_regime, f);
  return f;
}

SolForward sol_forward(SolRay g, float t) { return sol_forward(g, t, true); }

// What positions by Jacobi's zeta function need (sol_forward_zeta), in
// place of sol_ray_integrals. Along a geodesic e^{w} = (dn u + k cn u)/k',
// so the integrals of s = e^{2w} and 1/s over u are
//   (2E(u) ± 2k sn u - m1 u)/m1 = G u + (2Z(u) ± 2k sn u)/m1,
// E(u) = (E/K) u + Z(u), with the mean rate G = (2E/K - m1)/m1 and, by
// E/K = 1 - ½ Σ_{i>=0} 2^i c_i² (c_0 = k, the AGM's c_i; Abramowitz and
// Stegun 17.6.3), 2E/K - m1 = 1 - Σ_{i>=1} 2^i c_i²: at least 0.66 for the
// rays sol_forward_zeta serves (μ >= 0.01, m <= 0.961), no cancellation.
void sol_ray_zeta(inout SolRay g) {
  if (g.regime != REGIME_GENERAL) return;
  const float rate = 1.0 - g.agm.zeta_sum;
  g.zeta_rate = rate / (g.lambda * g.m1);
  g.zeta_scale = 2.0 / (g.lambda * g.m1);
  g.inv_kc = 1.0 / g.kc;
  g.zeta_inv_lambda = 1.0 / g.lambda;
  // Z and sn at the start's phase from the same descent as at every later
  // phase (sol_forward_zeta), so that the integrals are 0 there.
  const vec4 start = jacobi_zeta(g.u0, g.m, g.m1, g.K, g.kc, g.agm, SOL_ZETA_LEVELS);
  g.zeta_start = start.w;
  g.sn_start = start.x;
  g.s_start = g.start.ew * g.start.ew;
  g.is_start = 1.0 / g.s_start;
}

// sol_forward by Jacobi's zeta function (after sol_ray_zeta), for t >= 0:
// the integrals from the start's phase u0 to u = u0 + λt are
// (G (u - u0) + 2(ΔZ ± k Δsn)/m1)/λ, with one descent (jacobi_zeta) at u:
// no Carlson integral and no quarters. The rounding of Z and sn, a few
// ulps, is amplified by 2/(λ m1) = λ/(2μ): about 2e-7/μ relative to the
// position's scale a segment (measured: 8e-6 at μ = 0.012, t <= 12), so
// rays of small μ take sol_forward (the quotient march: kZetaLeastMu).
SolForward sol_forward_zeta(SolRay g, float t) {
  SolForward f;
  const float u = g.lambda * t + g.u0;
  f.phase = u;
  const vec4 jz = jacobi_zeta(u, g.m, g.m1, g.K, g.kc, g.agm, SOL_ZETA_LEVELS);
  // e^{±w} = (dn ± k cn)/k' = k'/(dn ∓ k cn): of the two forms of each, the
  // one without cancellation (dn + k|cn|), so one division for both.
  const float D = jz.z + g.k * abs(jz.y), inv_D = 1.0 / D;
  const bool upper = jz.y >= 0.0;
  f.point.jac = jz.xyz;
  f.point.ew = upper ? D * g.inv_kc : g.kc * inv_D;
  f.inv_ew = upper ? g.kc * inv_D : D * g.inv_kc;
  f.zeta = jz.w;
  f.same = true;
  f.near = vec2(0.0);
  // The integrals of s (x's) and of 1/s (y's) from the start. The phase's
  // rounding only moves the point along the geodesic: the mean rate takes
  // the phase evaluated, u - u0, not λt.
  const float du = u - g.u0, h = du * g.zeta_inv_lambda;
  const float base = g.zeta_rate * du + g.zeta_scale * (jz.w - g.zeta_start);
  const float k_sn = g.zeta_scale * g.k * (jz.x - g.sn_start);
  vec2 integrals = vec2(base + k_sn, base - k_sn);
  // Short segments: that rounding does not shrink with the segment (and
  // adds up over a ray's restarts), so below SOL_ZETA_SHORT the corrected
  // trapezoid rule h (f0 + f1)/2 + h² (f0' - f1')/12 from the ends' s and
  // 1/s and their slopes ±2 s z' (z' = c at the start, -kλ sn here).
  const float s1 = f.point.ew * f.point.ew, is1 = f.inv_ew * f.inv_ew, dz1 = -g.k * g.lambda * jz.x;
  const vec2 ends = vec2(g.s_start + s1, g.is_start + is1), slopes = vec2(g.s_start * g.c - s1 * dz1, is1 * dz1 - g.is_start * g.c);
  integrals = h < SOL_ZETA_SHORT ? 0.5 * h * ends + (h * h / 6.0) * slopes : integrals;
  f.position = vec3(g.sign_x * g.b * integrals.x, g.sign_y * g.a * integrals.y, log(f.point.ew) - g.w0);
  // The tangent's frame components: |u1| = |a| e^{z} = √μ e^{w}, |u2| = |b| e^{-z}.
  f.direction = vec3(g.sign_x * g.sqrt_mu * f.point.ew, g.sign_y * g.sqrt_mu * f.inv_ew, -g.k * g.lambda * jz.x);
  sol_forward_regimes(g, t, false, f);
  return f;
}

// A direction for a ray that sol_forward and sol_ray_restarted may take
// without the plane regime: a direction of that regime (μ = |ab| < 1e-24,
// not vertical) has its smaller horizontal component raised to 2e-24 over
// the larger one, so that μ is 2e-24 and the ray is of the general regime,
// whose float evaluation holds down to μ = 1e-24 (see sol_agm); where the
// larger is below 1e-12 both are set to 0 (the vertical regime). Either
// moves the unit direction by at most 2e-12, 30 000 times less than the
// float rounding of the direction itself (6e-8), whose effect on the
// geodesic grows along it the same way (at most as e^{t}). Other
// directions are returned as they are.
vec3 sol_direction_off_plane_regime(vec3 direction) {
  const vec3 d = normalize(direction);
  const float a = abs(d.x), b = abs(d.y), larger = max(a, b);
  if (a * b >= 1e-24) return d;
  if (larger < 1e-12) return vec3(0.0, 0.0, d.z < 0.0 ? -1.0 : 1.0);
  const float raised = 2e-24 / larger;
  return a < b ? vec3(d.x < 0.0 ? -raised : raised, d.y, d.z) : vec3(d.x, d.y < 0.0 ? -raised : raised, d.z);
}

vec3 sol_position_forward(SolRay g, float t) {
  if (g.regime == REGIME_VERTICAL) return vec3(0.0, 0.0, g.c * t);
  if (g.regime == REGIME_STRAIGHT) return vec3(g.direction.x * t, g.direction.y * t, 0.0);
  if (g.regime == REGIME_PLANE) return sol_plane_position(g, t);
  return sol_forward(g, t).position;
}

// Position (relative to the start) at arc length t; needs sol_ray_integrals(g) first.
vec3 sol_position(SolRay g, float t) {
  if (g.regime == REGIME_VERTICAL) return vec3(0.0, 0.0, g.c * t);
  if (g.regime == REGIME_STRAIGHT) return vec3(g.direction.x * t, g.direction.y * t, 0.0);
  if (g.regime == REGIME_PLANE) return sol_plane_position(g, t);
  float u = g.lambda * t + g.u0;
  SolPoint p = sol_point(g, u);
  int q = sol_absolute_quarter(g, u, p.quarter);
  bool same = q == g.start_quarter, forward = q > g.start_quarter;
  // Written with selected inputs, so that each Carlson pair is evaluated once
  // (lavapipe would pay for every branch): the path is
  //   same quarter:  start -> p
  //   forward:       start -> end of its quarter, whole quarters, start of p's quarter -> p
  //   backward:      the same, mirrored, with the sign flipped.
  float gap_near;
  vec3 f_near = sol_anchor(g, p, forward ? sol_start_anchor(p.quarter) : sol_end_anchor(p.quarter), gap_near);
  f_near = same ? g.start_factors : f_near;
  gap_near = same ? sol_two_point_gap(g.start, p) : gap_near;
  vec2 near = sol_piece(g, f_near, sol_factors(p), gap_near);
  float gap_far;
  vec3 f_far = sol_anchor(g, g.start, forward ? sol_end_anchor(g.start.quarter) : sol_start_anchor(g.start.quarter), gap_far);
  vec2 far = sol_piece(g, g.start_factors, f_far, same ? 0.0 : gap_far);
  vec2 middle = forward ? sol_quarters(g, g.start_quarter + 1, q - 1) : sol_quarters(g, q + 1, g.start_quarter - 1);
  vec2 integral = same ? (t < 0.0 ? -near : near) : (forward ? far + middle + near : -(far + middle + near));
  return vec3(g.sign_x * g.b * integral.x, g.sign_y * g.a * integral.y, log(p.ew) - g.w0);
}

// The phase of arc length t0 for a restart there, reduced by whole periods
// of sn, cn, dn (4K) to keep its float rounding small.
float sol_restart_phase(SolRay g, float t0) {
  const float u = g.lambda * t0 + g.u0;
  return u - 4.0 * g.K * round(u / (4.0 * g.K));
}

// The general-regime ray restarted at phase u, whose point p is given: the
// new direction's |a|, |b| are √μ e^{±w} there (no rounding piles up over
// many restarts), w0 = ½ ln(|a|/|b|) = w; far_forward is the caller's.
SolRay sol_ray_started_at(SolRay g, float u, SolPoint p) {
  g.a = g.sqrt_mu * p.ew;
  g.b = g.sqrt_mu / p.ew;
  g.w0 = log(p.ew);
  g.u0 = u;
  g.start = p;
  g.start_factors = sol_factors(p);
  g.start_quarter = sol_absolute_quarter(g, u, p.quarter);
  g.c = -g.k * g.lambda * p.jac.x;
  g.direction = vec3(g.sign_x * g.a, g.sign_y * g.b, g.c);
  return g;
}

// The restart of a ray of the other regimes (for sol_ray_advanced and
// sol_ray_restarted): the plane regime's hyperbolic parameter moves, s0 +
// t0; vertical and straight lines keep their direction. sol_ray_restarted
// calls this, not sol_ray_advanced, whose general path (a Jacobi point and
// a Carlson piece) would sit in the quotient march's loop though no ray
// there takes it.
SolRay sol_ray_advanced_special(SolRay g, float t0) {
  if (g.regime == REGIME_PLANE) {
    g.s0 += t0;
    g.log_cosh_s0 = sol_log_cosh(g.s0);
  }
  return g;
}

// The same geodesic, restarted at arc length t0: a ray from its point there
// (the origin of the new coordinates, the left translation by that point's
// inverse) with its tangent there. Left translations keep frame components,
// so the new ray's direction is the old tangent (a e^{z0}, b e^{-z0}, z'(t0))
// = (√μ e^{w}, √μ e^{-w}, w') (signs aside) on the same orbit: μ = |ab|, hence m, K, the AGM, the nome and the quarter
// integrals, are unchanged, and so is the oscillation w(u) of the reduced
// height; only the phase (u0 + λ t0), the height offset (w0 + z0) and the
// start move. A teleport of the quotient march restarts its ray this way
// instead of building it from scratch (sol_ray, sol_ray_integrals), and
// stays on the exact geodesic instead of one through a rounded tangent.
// The other regimes: sol_ray_advanced_special.
SolRay sol_ray_advanced(SolRay g, float t0) {
  if (g.regime != REGIME_GENERAL) return sol_ray_advanced_special(g, t0);
  const float u = sol_restart_phase(g, t0);
  g = sol_ray_started_at(g, u, sol_point(g, u));
  sol_ray_far_forward(g);
  return g;
}

// sol_ray_advanced(g, t0) for t0 >= 0 from what sol_forward(g, t0) found
// there: its point instead of a new Jacobi evaluation. The restarted ray
// needs the piece from the point p to the end E of its quarter for both
// coordinates (its own choice of coordinate may differ). For sol_forward's
// coordinate it is what is left of the quarter's integrals (the whole
// quarter, or the start's piece to that end, less the piece up to the
// point: one subtraction instead of a Carlson pair); for the other it comes
// from the first integral between p and E, in the old ray's coordinates:
// a ΔX - b ΔY = z'_p - z'_E, divided by the larger of |a|, |b| as in
// sol_forward (z'_E is 0 at a turning point and ∓kλ at the middle of the
// oscillation). That piece is used only where the restarted ray takes the
// other coordinate, that is where the ray has crossed the middle (e^{w} = 1,
// where |a| = |b|) since its start, so E is the turning point beyond it
// (z'_E = 0: no cancellation) unless the segment also turned there and came
// back near the middle; then the rounding of z'_p - z'_E, divided by |a| at
// p (about √μ there), costs 2e-7/√μ, and a segment that spans a turning
// point and the middle spans ln((1 + k)/k') in height: for a step of the
// quotient march, within about 1.9 of D's height range, μ >= 0.015 and the
// cost below 2e-6. The other differences lose at most float rounding of the
// quarter's integrals, which the positions carry anyway;
// tests/kernel_test.cpp walks rays in segments through it against the
// double closed form.
//
// `plane_regime` as for sol_forward: without it a ray that is not of the
// general regime (vertical or straight) is restarted as it is.
SolRay sol_ray_restarted(SolRay g, float t0, SolForward f, const bool plane_regime) {
  if (g.regime != REGIME_GENERAL) return plane_regime ? sol_ray_advanced_special(g, t0) : g;
  const bool carlson_y = sol_carlson_y(g);
  const bool lower = f.point.quarter == 0 || f.point.quarter == 3;
  const vec2 quarter = lower ? vec2(g.quarter_lo, g.quarter_hi) : vec2(g.quarter_hi, g.quarter_lo);
  const vec2 whole = f.same ? g.far_forward : quarter;
  const float piece = max((carlson_y ? whole.y - f.near.y : whole.x - f.near.x), 0.0);
  // z'_p - z'_E: E ends quarter 0 and 2 at the middle (sn = ∓1), 1 and 3 at a turning point.
  const float slope_end = f.point.quarter == 0 ? g.k * g.lambda : (f.point.quarter == 2 ? -g.k * g.lambda : 0.0);
  const float a = g.direction.x, b = g.direction.y;
  const float dslope = -g.k * g.lambda * f.point.jac.x - slope_end;
  // The other coordinate's step to E, then in its integral's units (x = σx |b| I_x, y = σy |a| I_y).
  const float other = carlson_y ? (dslope + b * g.sign_y * g.a * piece) / a / (g.sign_x * g.b)
                                : (a * g.sign_x * g.b * piece - dslope) / b / (g.sign_y * g.a);
  const vec2 far_forward = carlson_y ? vec2(max(other, 0.0), piece) : vec2(piece, max(other, 0.0));
  g = sol_ray_started_at(g, sol_restart_phase(g, t0), f.point);
  g.far_forward = far_forward;
  return g;
}

SolRay sol_ray_restarted(SolRay g, float t0, SolForward f) { return sol_ray_restarted(g, t0, f, true); }

// sol_ray_restarted for sol_forward_zeta: the ray restarted at the point f
// found (as sol_ray_started_at, with what sol_forward_zeta needs alone).
// Its phase is the one evaluated there, not reduced: Z and sn at the new
// start are then the values the old segment ended with, so the rounding
// of each cancels between the two segments.
SolRay sol_ray_restarted_zeta(SolRay g, SolForward f) {
  if (g.regime != REGIME_GENERAL) return g;
  g.a = g.sqrt_mu * f.point.ew;
  g.b = g.sqrt_mu * f.inv_ew;
  g.w0 = log(f.point.ew);
  g.u0 = f.phase;
  g.c = -g.k * g.lambda * f.point.jac.x;
  g.direction = vec3(g.sign_x * g.a, g.sign_y * g.b, g.c);
  g.zeta_start = f.zeta;
  g.sn_start = f.point.jac.x;
  g.s_start = f.point.ew * f.point.ew;
  g.is_start = f.inv_ew * f.inv_ew;
  return g;
}

// The point `local` given relative to `origin`, in the coordinates `origin`
// is given in: origin · local (the group law); `scale` = (e^{z}, e^{-z}) of
// origin's z (a march keeps it with its origin).
vec3 sol_translate(vec3 origin, vec2 scale, vec3 local) {
  return vec3(origin.x + scale.x * local.x, origin.y + scale.y * local.y, origin.z + local.z);
}

vec3 sol_translate(vec3 origin, vec3 local) { return sol_translate(origin, vec2(exp(origin.z), exp(-origin.z)), local); }

// The exponential map: the end of the geodesic from the origin with unit
// initial direction `direction` after arc length t, its position and unit
// tangent (a ray set up and evaluated once; not a march).
SolForward sol_exp(vec3 direction, float t) {
  SolRay g = sol_ray(direction);
  sol_ray_integrals(g);
  return sol_forward(g, t);
}

#endif  // SOL_FORWARD_GLSL
