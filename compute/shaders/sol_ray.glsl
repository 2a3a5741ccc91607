// A closed-form geodesic from the origin in float, prepared once per ray
// (SolRay: its regime, elliptic modulus, phase and Carlson anchors), and
// what it gives without marching: heights (Jacobi theta series), the
// height range, the cut time. Part of sol_geodesic.glsl.
#ifndef SOL_RAY_GLSL
#define SOL_RAY_GLSL

#include "sol_elliptic.glsl"

// ---- The geodesic ----------------------------------------------------------------

const int REGIME_VERTICAL = 0;
const int REGIME_PLANE = 1;
const int REGIME_STRAIGHT = 2;
const int REGIME_GENERAL = 3;

struct SolPoint {
  vec3 jac;  // sn, cn, dn
  float ew;   // e^{w}
  float f2;   // s - s₋
  float f3;   // s₊ - s
  float sm1;  // s - 1
  int quarter;
};

struct SolRay {
  vec3 direction;
  int regime;
  float sign_x, sign_y;
  bool swapped;
  float a, b, c;
  float s0;  // plane regime
  float mu, sqrt_mu, lambda, k, kc, w0, m, m1, K, u0;
  float sqrt_sm, sqrt_sp, one_minus_sm, sp_minus_one, sp_minus_sm;
  float quarter_lo, quarter_hi;
  vec2 far_forward;  // the integrals from the start to the end of its quarter (sol_forward's coordinate; both after sol_ray_restarted)
  SolAgm agm;
  // Heights by Jacobi theta series (sol_height): nome q <= e^{-π} of k'
  // (hyperbolic form, m > 1/2) or of k (m <= 1/2), K' = K(m1).
  bool theta_hyperbolic;
  float nome, nome_quarter, Kp, sqrt_k, sqrt_kc;
  float log_cosh_s0;  // plane regime
  SolPoint start;
  vec3 start_factors;  // sol_factors(start), kept with it
  // The anchors' factors (sol_anchor): s₋, the middle, s₊.
  vec3 anchor_bottom, anchor_middle, anchor_top;
  int start_quarter;
  // Positions by Jacobi's zeta function (sol_ray_zeta, sol_forward_zeta):
  // the integrals' mean rate per unit of phase G/λ, their scale 2/(λ m1),
  // Z and sn at the start's phase, e^{±2w} there, 1/k'.
  float zeta_rate, zeta_scale, zeta_start, sn_start;
  float s_start, is_start;
  float inv_kc, zeta_inv_lambda;
};

// The path's values from sn, cn, dn at one parameter (see sol_point).
SolPoint sol_point_from(SolRay g, vec3 j) {
  SolPoint p;
  p.jac = j;
  float k = g.k, kc = g.kc, sn2 = j.x * j.x;
  if (j.y >= 0.0) {
    p.ew = (j.z + k * j.y) / kc;
    float top_gap = k * sn2 * (k / (1.0 + j.z) + 1.0 / (1.0 + j.y)) / kc;  // e^{W} - e^{w}
    p.f3 = top_gap * (g.sqrt_sp + p.ew);
    p.sm1 = 2.0 * p.ew * k * j.y / kc;
    p.f2 = p.sm1 + g.one_minus_sm;
  } else {
    float dmk = j.z - k * j.y;
    p.ew = kc / dmk;
    float one_minus_k = kc * kc / (1.0 + k);
    float bottom_gap = k * sn2 * (one_minus_k + kc * p.ew) / ((1.0 - j.y) * (1.0 + j.z) * kc);  // e^{w} - e^{-W}
    p.f2 = bottom_gap * (p.ew + g.sqrt_sm);
    p.sm1 = 2.0 * p.ew * k * j.y / kc;
    p.f3 = g.sp_minus_one - p.sm1;
  }
  p.quarter = j.x < 0.0 ? (j.y < 0.0 ? 0 : 1) : (j.y >= 0.0 ? 2 : 3);
  return p;
}

SolPoint sol_point(SolRay g, float u) { return sol_point_from(g, jacobi(u, g.m, g.m1, g.K, g.kc, g.agm)); }

int sol_absolute_quarter(SolRay g, float u, int quarter) {
  int q = int(floor((u + 2.0 * g.K) / g.K));
  int r = ((q % 4) + 4) % 4;
  int diff = (quarter - r + 4) % 4;
  if (diff == 1) ++q;
  if (diff == 3) --q;
  return q;
}

// Carlson's [1,-1,-1] integral between two limits given by their factors
// (√t, √(t - s₋), √(s₊ - t)); gap = |t_x - t_y|. Scaled by the largest V_i
// so nothing overflows (see carlson_piece in libsol/src/closed_form.cpp);
// 0 for a piece with no gap or V_1 <= 0 (dead pieces get harmless operands).
float carlson_piece(vec3 x0, vec3 y0, float gap) {
  const float v1 = x0.x * y0.y * y0.z + y0.x * x0.y * x0.z;
  const float v2 = x0.y * y0.x * y0.z + y0.y * x0.x * x0.z;
  const float v3 = x0.z * y0.x * y0.y + y0.z * x0.x * x0.y;
  const bool live = gap > 0.0 && v1 > 0.0;
  const float inv = 1.0 / (live ? max(max(v1, v2), v3) : 1.0);
  const float w1 = live ? v1 * inv : 1.0, w2 = live ? v2 * inv : 1.0, w3 = live ? v3 * inv : 1.0;
  const float r = live ? gap * inv : 0.0;
  const float piece = 2.0 * x0.x * y0.x * r / w1 - (2.0 / 3.0) * r * r * r * carlson_rd(w2 * w2, w3 * w3, w1 * w1);
  return live ? piece : 0.0;
}

vec3 sol_reciprocal(vec3 f, float sqrt_sm, float sqrt_sp) {
  const float inv = 1.0 / f.x;
  return vec3(inv, sqrt_sm * f.z * inv, sqrt_sp * f.y * inv);
}

// The time integral of s (x's, y = false) or of 1/s (y's) between limits
// with factors fx, fy (first factor e^{w}) and s-gap `gap`; the 1/s gap is
// gap/(s_x s_y).
float sol_piece_of(SolRay g, vec3 fx, vec3 fy, float gap, bool y) {
  const vec3 x0 = y ? sol_reciprocal(fx, g.sqrt_sm, g.sqrt_sp) : fx;
  const vec3 y0 = y ? sol_reciprocal(fy, g.sqrt_sm, g.sqrt_sp) : fy;
  const float gap_of = y ? gap / (fx.x * fx.x * fy.x * fy.x) : gap;
  return carlson_piece(x0, y0, gap_of) / (2.0 * g.sqrt_mu);
}

// Both integrals (x's, y's) between those limits.
vec2 sol_piece(SolRay g, vec3 fx, vec3 fy, float gap) {
  return vec2(sol_piece_of(g, fx, fy, gap, false), sol_piece_of(g, fx, fy, gap, true));
}

// Which coordinate's integral sol_forward takes by Carlson: y's where
// |a| >= |b| (x then follows from the first integral z' + a x - b y = c,
// divided by the larger of |a|, |b|), else x's.
bool sol_carlson_y(SolRay g) { return g.a >= g.b; }

// sol_piece's component for that coordinate alone: one Carlson R_D.
float sol_piece_one(SolRay g, vec3 fx, vec3 fy, float gap) { return sol_piece_of(g, fx, fy, gap, sol_carlson_y(g)); }

vec3 sol_factors(SolPoint p) { return vec3(p.ew, sqrt(p.f2), sqrt(p.f3)); }

// An anchor's factors (0: s₋, 1: middle, 2: s₊) and the s-gap from p to it.
vec3 sol_anchor(SolRay g, SolPoint p, int anchor, out float gap) {
  gap = anchor == 0 ? p.f2 : (anchor == 1 ? abs(p.sm1) : p.f3);
  return anchor == 0 ? g.anchor_bottom : (anchor == 1 ? g.anchor_middle : g.anchor_top);
}

// |s_p - s_q| of two points of one quarter from the representation with the
// smaller operands (each relatively accurate).
float sol_two_point_gap(SolPoint p, SolPoint q) {
  bool lower = p.quarter == 0 || p.quarter == 3;
  float via_anchor = lower ? abs(p.f2 - q.f2) : abs(p.f3 - q.f3);
  float size_anchor = lower ? max(p.f2, q.f2) : max(p.f3, q.f3);
  float via_middle = abs(p.sm1 - q.sm1);
  float size_middle = max(abs(p.sm1), abs(q.sm1));
  return size_anchor < size_middle ? via_anchor : via_middle;
}

vec2 sol_quarters(SolRay g, int first, int last) {
  if (last < first) return vec2(0.0);
  int count = last - first + 1;
  int periods = count / 4;
  float whole = float(periods) * 2.0 * (g.quarter_lo + g.quarter_hi);
  vec2 r = vec2(whole);
  for (int j = first + 4 * periods; j <= last; ++j) {
    int q = ((j % 4) + 4) % 4;
    bool lower = q == 0 || q == 3;
    r += lower ? vec2(g.quarter_lo, g.quarter_hi) : vec2(g.quarter_hi, g.quarter_lo);
  }
  return r;
}

int sol_start_anchor(int q) { return q == 0 ? 0 : (q == 2 ? 2 : 1); }
int sol_end_anchor(int q) { return q == 1 ? 2 : (q == 3 ? 0 : 1); }

// The integral from the ray's start to the end of its quarter, for the
// coordinate sol_forward takes by Carlson (the other component 0): the part
// of every forward position past that quarter that does not depend on the
// point.
void sol_ray_far_forward(inout SolRay g) {
  float gap;
  const vec3 f_far = sol_anchor(g, g.start, sol_end_anchor(g.start.quarter), gap);
  const float piece = sol_piece_one(g, g.start_factors, f_far, gap);
  g.far_forward = sol_carlson_y(g) ? vec2(0.0, piece) : vec2(piece, 0.0);
}

SolRay sol_ray(vec3 direction) {
  SolRay g;
  g.direction = normalize(direction);
  g.sign_x = g.direction.x < 0.0 ? -1.0 : 1.0;
  g.sign_y = g.direction.y < 0.0 ? -1.0 : 1.0;
  g.a = abs(g.direction.x);
  g.b = abs(g.direction.y);
  g.c = g.direction.z;
  g.swapped = false;
  g.s0 = 0.0;
  g.log_cosh_s0 = 0.0;
  // Defaults that keep sol_height's branch-free arithmetic finite in every regime.
  g.K = 1.0;
  g.Kp = 1.0;
  g.nome = 0.0;
  g.nome_quarter = 0.0;
  g.theta_hyperbolic = true;
  g.sqrt_k = 0.0;
  g.sqrt_kc = 1.0;
  g.lambda = 1.0;
  g.u0 = 0.0;
  g.w0 = 0.0;
  g.sqrt_sm = 1.0;
  g.sqrt_sp = 1.0;
  g.anchor_bottom = g.anchor_middle = g.anchor_top = g.start_factors = vec3(1.0, 0.0, 0.0);
  g.zeta_rate = g.zeta_scale = g.zeta_start = g.sn_start = 0.0;
  g.s_start = g.is_start = 1.0;
  g.inv_kc = 1.0;
  g.zeta_inv_lambda = 1.0;
  g.mu = g.a * g.b;
  if (g.a == 0.0 && g.b == 0.0) {
    g.regime = REGIME_VERTICAL;
    return g;
  }
  if (g.mu < 1e-24) {
    g.regime = REGIME_PLANE;
    if (g.b > g.a) {  // x = const: mapped to y = const by (x, y, z) -> (y, x, -z)
      g.swapped = true;
      float t = g.a;
      g.a = g.b;
      g.b = t;
      g.c = -g.c;
    }
    g.s0 = asinh(-g.c / g.a);
    g.log_cosh_s0 = sol_log_cosh(g.s0);
    return g;
  }
  float m2 = (g.a - g.b) * (g.a - g.b) + g.c * g.c;
  if (m2 == 0.0) {
    g.regime = REGIME_STRAIGHT;
    return g;
  }
  g.regime = REGIME_GENERAL;
  g.sqrt_mu = sqrt(g.mu);
  g.lambda = sqrt(1.0 + 2.0 * g.mu);
  g.m = m2 / (g.lambda * g.lambda);
  g.m1 = 4.0 * g.mu / (g.lambda * g.lambda);
  g.k = sqrt(g.m);
  g.kc = 2.0 * g.sqrt_mu / g.lambda;
  g.agm = sol_agm(g.m1);
  g.K = SOL_PI / (2.0 * g.agm.c);  // K = π / (2 AGM(1, k'))
  g.w0 = 0.5 * (log(g.a) - log(g.b));
  // u0 from sn u0, cn u0, dn u0 directly (never through the angle).
  float root = sqrt(m2);
  float sn0 = -g.c / root, cn0 = (g.a - g.b) / root, dn0 = (g.a + g.b) / g.lambda;
  float f = sn0 * carlson_rf(cn0 * cn0, dn0 * dn0, 1.0);
  g.u0 = cn0 >= 0.0 ? f : (sn0 < 0.0 ? -2.0 : 2.0) * g.K - f;
  g.sqrt_sm = g.kc / (1.0 + g.k);
  g.sqrt_sp = (1.0 + g.k) / g.kc;
  g.one_minus_sm = 2.0 * g.k / (1.0 + g.k);
  g.sp_minus_one = 2.0 * g.k * (1.0 + g.k) / g.m1;
  g.sp_minus_sm = 4.0 * g.k / g.m1;
  // K' = π / (2 AGM(1, k)) for the nome.
  // The nome of the smaller modulus (k' when m > 1/2, else k) by its
  // λ-series, q = λ + 2λ⁵ + 15λ⁹ + 150λ¹³ with λ = (1 - √κ')/(2(1 + √κ'))
  // <= 0.0434 (DLMF 22.2.2 and the classical expansion; the terms left out
  // are below 3e-16), 1 - √κ' formed from m1 or m without cancellation;
  // then K' = K(m1) from q = exp(-πK/K').
  g.theta_hyperbolic = g.m > 0.5;
  float root_other = g.theta_hyperbolic ? sqrt(g.k) : sqrt(g.kc);
  float other = g.theta_hyperbolic ? g.k : g.kc;
  float lambda_q = (g.theta_hyperbolic ? g.m1 : g.m) / (2.0 * (1.0 + other) * (1.0 + root_other) * (1.0 + root_other));
  float l4 = lambda_q * lambda_q * lambda_q * lambda_q;
  g.nome = lambda_q * (1.0 + l4 * (2.0 + l4 * (15.0 + 150.0 * l4)));
  g.nome_quarter = sqrt(sqrt(g.nome));
  g.Kp = g.theta_hyperbolic ? -SOL_PI * g.K / log(g.nome) : 1.0;
  g.sqrt_k = sqrt(g.k);
  g.sqrt_kc = sqrt(g.kc);
  // The start from its exact sn, cn, dn: no Jacobi evaluation in the setup.
  g.anchor_bottom = vec3(g.sqrt_sm, 0.0, sqrt(g.sp_minus_sm));
  g.anchor_middle = vec3(1.0, sqrt(g.one_minus_sm), sqrt(g.sp_minus_one));
  g.anchor_top = vec3(g.sqrt_sp, sqrt(g.sp_minus_sm), 0.0);
  g.start = sol_point_from(g, vec3(sn0, cn0, dn0));
  g.start_factors = sol_factors(g.start);
  g.start_quarter = sol_absolute_quarter(g, g.u0, g.start.quarter);
  g.quarter_lo = g.quarter_hi = 0.0;
  return g;
}

// The time integrals of a ray over whole lower and upper quarters (needed by
// sol_position and sol_forward, not by sol_height, so a march that only
// needs heights computes them once, at the hit), and the piece from the
// start to the end of its quarter for the coordinate sol_forward takes by
// Carlson (sol_ray_far_forward; sol_ray_restarted sets both).
void sol_ray_integrals(inout SolRay g) {
  if (g.regime != REGIME_GENERAL) return;
  // A lower quarter's integral of s by Carlson; the upper one's from the
  // first integral over the lower quarter, whose integral of 1/s it is:
  // I_x - I_y = -Δz'/μ, Δz' = kλ (a sum of positive terms).
  g.quarter_lo = carlson_piece(g.anchor_bottom, g.anchor_middle, g.one_minus_sm) / (2.0 * g.sqrt_mu);
  g.quarter_hi = g.quarter_lo + g.k * g.lambda / g.mu;
  sol_ray_far_forward(g);
}


// Position at arc length t in the plane regime (the hyperbolic plane y = 0):
// x = sinh t / cosh v, z = log cosh s0 - log cosh v, v = t + s0. Written
// without branches and without overflow short of x's own, from T = |t|,
// A = |v|: x = sign(t) e^{T - A} (1 - e^{-2T}) / (1 + e^{-2A}),
// log cosh v = A - ln 2 + log(1 + e^{-2A}): three exp and one log. The
// march evaluates it at every step for every ray (a select, not a branch:
// lavapipe pays for the body of an if whichever way its lanes go, and a
// branching form with its overflow guard cost the quotient 8-10 %).
// The tangent there, from the same exp: (1/cosh v, 0, -tanh v) with
// 1/cosh v = 2 e^{-A}/(1 + e^{-2A}), tanh v = sign(v)(1 - e^{-2A})/(1 + e^{-2A}).
vec3 sol_plane_position(SolRay g, float t, out vec3 direction) {
  const float T = abs(t), A = abs(t + g.s0);
  const float e_v = exp(-2.0 * A);
  const float x = sign(t) * exp(T - A) * (1.0 - exp(-2.0 * T)) / (1.0 + e_v);
  vec3 p = vec3(x, 0.0, g.log_cosh_s0 - (A - 0.693147181 + log(1.0 + e_v)));
  vec3 d = vec3(2.0 * sqrt(e_v), 0.0, -sign(t + g.s0) * (1.0 - e_v)) / (1.0 + e_v);
  p = g.swapped ? vec3(p.y, p.x, -p.z) : p;
  d = g.swapped ? vec3(d.y, d.x, -d.z) : d;
  direction = vec3(g.sign_x * d.x, g.sign_y * d.y, d.z);
  return vec3(g.sign_x * p.x, g.sign_y * p.y, p.z);
}

vec3 sol_plane_position(SolRay g, float t) {
  vec3 unused;
  return sol_plane_position(g, t, unused);
}

// e^{w} = (dn u + k cn u)/k' by Jacobi theta series, the cheap path for
// heights (one exp or cos per call; docs/mathematics.md). e^{w} is even in u and
// e^{w(u + 2K)} = e^{-w(u)}, so u is reduced to r ∈ [0, K]. With the nome
// q <= e^{-π} the series below are truncated below 4e-9 relative (checked
// against mpmath for m from 1e-6 to 1 - 1e-20).
//  m <= 1/2, v = πr/(2K):  e^{w} = (θ3(v) + √k θ2(v)) / (√k' θ4(v)).
//  m >  1/2, by Jacobi's imaginary transformation (DLMF 22.6.1) with the
//  nome q of k' and P = q e^{2y} = exp(π(r - K)/K') ∈ [q, 1]:
//    θ3 = 1 + P + q²/P + q²P² + q⁶/P²,  θ4 = 1 - P - q²/P + q²P² + q⁶/P²,
//    T2 = 1 + qP + q/P + q⁴P² + q⁴/P²,  e^{w} = (θ3 + √k θ4) q^{1/4} / (√k' √P T2),
//  with √P = exp(π(r - K)/(2K')) the one exp per step.
float sol_theta_ew_from(SolRay g, float r, float Q) {
  float q = g.nome;
  float q2 = q * q, q4 = q2 * q2;
  // m > 1/2: the imaginary transformation, Q = √P = exp(π(r - K)/(2K')).
  float P = Q * Q;
  float iP = 1.0 / P, iP2 = iP * iP, P2 = P * P;
  float th3h = 1.0 + P + q2 * iP + q2 * P2 + q4 * q2 * iP2;
  float th4h = 1.0 - P - q2 * iP + q2 * P2 + q4 * q2 * iP2;
  float t2h = 1.0 + q * P + q * iP + q4 * P2 + q4 * iP2;
  float hyperbolic = (th3h + g.sqrt_k * th4h) * g.nome_quarter / (g.sqrt_kc * Q * t2h);
  // m <= 1/2: v = πr/(2K).
  float c1 = cos(SOL_PI * r / (2.0 * g.K)), c2 = 2.0 * c1 * c1 - 1.0;
  float c3 = c1 * (2.0 * c2 - 1.0), c4 = 2.0 * c2 * c2 - 1.0, c5 = 2.0 * c1 * c4 - c3;
  float th2 = 2.0 * g.nome_quarter * (c1 + q2 * c3 + q4 * q2 * c5);
  float th3 = 1.0 + 2.0 * q * c2 + 2.0 * q4 * c4;
  float th4 = 1.0 - 2.0 * q * c2 + 2.0 * q4 * c4;
  float elliptic = (th3 + g.sqrt_k * th2) / (g.sqrt_kc * th4);
  return g.theta_hyperbolic ? hyperbolic : elliptic;
}

// Height z at arc length t: no integrals, no sn/cn/dn. Written without
// branches (lavapipe evaluates both sides of every branch): every regime's
// value comes from one shared exp and one log.
float sol_height(SolRay g, float t) {
  float u = g.lambda * t + g.u0;
  float n = round(u / (2.0 * g.K));
  float r = abs(u - 2.0 * g.K * n);
  bool flip = n - 2.0 * floor(0.5 * n) != 0.0;
  bool plane = g.regime == REGIME_PLANE;
  // Plane regime (the hyperbolic plane y = 0): z = log cosh s0 - log cosh v,
  // v = t + s0, log cosh v = |v| - ln 2 + log(1 + e^{-2|v|}) (no overflow).
  float v = abs(t + g.s0);
  // The shared exp: √P of the theta series, or e^{-2|v|}.
  float E = exp(plane ? -2.0 * v : SOL_PI * (r - g.K) / (2.0 * g.Kp));
  float ew = sol_theta_ew_from(g, r, max(E, 1e-18));
  ew = flip ? 1.0 / ew : ew;
  float logged = log(plane ? 1.0 + E : ew);
  float z = plane ? g.log_cosh_s0 - v + 0.693147181 - logged : logged - g.w0;
  z = plane && g.swapped ? -z : z;
  return g.regime == REGIME_VERTICAL ? g.c * t : (g.regime == REGIME_STRAIGHT ? 0.0 : z);
}

// The heights the whole geodesic visits (x: lowest, y: highest), ±1e30 where
// unbounded: z oscillates between the turning points log √s± - w0.
vec2 sol_height_range(SolRay g) {
  vec2 general = vec2(log(g.sqrt_sm), log(g.sqrt_sp)) - g.w0;
  float top = sol_log_cosh(g.s0);
  vec2 plane = g.swapped ? vec2(-top, 1e30) : vec2(-1e30, top);
  vec2 r = g.regime == REGIME_GENERAL ? general : (g.regime == REGIME_PLANE ? plane : vec2(-1e30, 1e30));
  return g.regime == REGIME_STRAIGHT ? vec2(0.0) : r;
}

// The z-period T of the geodesic with unit direction d, 4K(m)/λ (1e30,
// infinite, where ab = 0: the planes x, y = const and the vertical line),
// as sol::cut_time: a geodesic minimises exactly up to it
// (Coiculescu–Schwartz).
float sol_cut_time(vec3 d) {
  const float mu = abs(d.x * d.y), lambda2 = 1.0 + 2.0 * mu;
  const SolAgm agm = sol_agm(4.0 * mu / lambda2);  // of k'² = m1
  return mu > 0.0 ? 4.0 * (SOL_PI / (2.0 * agm.c)) / sqrt(lambda2) : 1e30;
}

#endif  // SOL_RAY_GLSL
