// Closed-form Sol geodesics from the origin in float: the GLSL mirror of
// libsol's ClosedFormGeodesic<float> (libsol/src/closed_form.cpp, the
// derivation in libsol/include/sol/closed_form.hpp) and of the elliptic
// functions it needs (libsol/src/elliptic.cpp, carlson.hpp). Keep the two in
// step: tests/kernel_test.cpp holds them together.
//
// The positions by Jacobi's zeta function (sol_forward_zeta, the quotient
// march's first pass) are the kernel's own: no C++ mirror; tested against
// libsol's double closed form.
//
// Differences from the C++ float version, all below float rounding at the
// arc lengths a frame uses: K comes from a float AGM (no double-double
// K_lo), the AGM chain of sn, cn, dn runs in float, and the AGM sequence is
// computed once per ray.

const float SOL_PI = 3.14159265358979;
const float SOL_EPS = 1.1920929e-7;

// log cosh v without overflow.
float sol_log_cosh(float v) {
  float a = abs(v);
  return a + log(1.0 + exp(-2.0 * a)) - 0.693147181;
}

// ---- Carlson's R_F and R_D (Carlson 1995), square roots only ------------------
// (R_D below: carlson_rd.)

float carlson_rf(float x, float y, float z) {
  float a = (x + y + z) / 3.0;
  // (3 eps)^(-1/6) for float.
  float q = 11.8693820 * max(max(abs(a - x), abs(a - y)), abs(a - z));
  float scale = 1.0;
  for (int i = 0; i < 80 && q * scale >= abs(a); ++i) {  // 4^80 covers any float spread
    float sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    float l = sx * sy + sy * sz + sz * sx;
    x = (x + l) * 0.25;
    y = (y + l) * 0.25;
    z = (z + l) * 0.25;
    a = (a + l) * 0.25;
    scale *= 0.25;
  }
  float X = 1.0 - x / a, Y = 1.0 - y / a, Z = -(X + Y);
  float e2 = X * Y - Z * Z, e3 = X * Y * Z;
  return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / sqrt(a);
}

// Carlson's R_D(x, y, z) (Carlson 1995): duplications until the spread is
// below float rounding, then the series to fifth order.
float carlson_rd(float x, float y, float z) {
  float a = (x + y + 3.0 * z) / 5.0;
  float q = 17.9593928 * max(max(abs(a - x), abs(a - y)), abs(a - z));
  float scale = 1.0, sum = 0.0;
  for (int i = 0; i < 80 && q * scale >= abs(a); ++i) {
    float sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    float l = sx * sy + sy * sz + sz * sx;
    sum += scale / (sz * (z + l));
    x = (x + l) * 0.25;
    y = (y + l) * 0.25;
    z = (z + l) * 0.25;
    a = (a + l) * 0.25;
    scale *= 0.25;
  }
  float inv_a = 1.0 / a;
  float X = 1.0 - x * inv_a, Y = 1.0 - y * inv_a, Z = -(X + Y) / 3.0;
  float xy = X * Y, z2 = Z * Z;
  float e2 = xy - 6.0 * z2, e3 = (3.0 * xy - 8.0 * z2) * Z, e4 = 3.0 * (xy - z2) * z2, e5 = xy * z2 * Z;
  float s = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0 +
            3.0 * e5 / 26.0;
  return scale * s / (a * sqrt(a)) + 3.0 * sum;
}

// ---- Jacobi functions ------------------------------------------------------------

// The arithmetic–geometric mean of 1 and k' with its sequence: depends only
// on the parameter, so a ray computes it once (Bulirsch's sncndn splits the
// same way). A fixed number of levels, SOL_AGM_LEVELS, keeps every loop
// constant (lavapipe then keeps the arrays in registers): 7 levels converge
// in float for k' >= 2e-12 (the smallest k' of the general regime, μ >= 1e-24);
// levels past convergence are exact identities (a = b).
const int SOL_AGM_LEVELS = 7;

// sol_forward_zeta's descent: 5 levels, for rays of μ >= 0.01 (k' >= 0.198,
// the quotient march's kZetaLeastMu), where the AGM's c_5 is below 1e-11:
// the fifth level's term of Z, 2^5 c_5 times the 2/(λ m1) <= 50 of the
// integrals, is below 1e-8 (with 4 levels the fourth's, 6e-5 times 50,
// is not: measured 2e-3 at μ = 0.01).
const int SOL_ZETA_LEVELS = 5;
// sol_forward_zeta's segments shorter than this (arc length) take the
// corrected trapezoid rule: its error h⁵ max|s⁗|/720 is then below the
// zeta function's rounding (tests/kernel_test.cpp walks rays in segments).
const float SOL_ZETA_SHORT = 0.1;

struct SolAgm {
  float mean[SOL_AGM_LEVELS];
  float inv_mean[SOL_AGM_LEVELS];  // 1 / mean: the descent multiplies (a division per level saved per call)
  float root[SOL_AGM_LEVELS];
  float c;  // the mean: π/(2K)
  // Jacobi's zeta function by the same descent (jacobi_agm's `zeta`): level
  // i's 2^i c_i and modulus k_i = c_i/a_i (c_i = (a_{i-1} - b_{i-1})/2).
  float zeta_coef[SOL_AGM_LEVELS];
  float zeta_k[SOL_AGM_LEVELS];
  float zeta_sum;  // Σ_{i>=1} 2^i c_i² (1 - E/K = (m + zeta_sum)/2)
};

SolAgm sol_agm(float m1) {
  SolAgm g;
  float a = 1.0, b = sqrt(m1);
  for (int i = 0; i < SOL_AGM_LEVELS; ++i) {
    g.mean[i] = a;
    g.inv_mean[i] = 1.0 / a;
    g.root[i] = b;
    float next = 0.5 * (a + b);
    b = sqrt(a * b);
    a = next;
  }
  g.c = a;
  // c_1 = (1 - k')/2, then c_{i+1} = c_i²/(4 a_{i+1}) (no cancellation).
  float ci = 0.5 * (1.0 - g.root[0]), scale = 2.0;
  g.zeta_coef[0] = 0.0;
  g.zeta_k[0] = 0.0;
  g.zeta_sum = 0.0;
  for (int i = 1; i < SOL_AGM_LEVELS; ++i) {
    g.zeta_coef[i] = scale * ci;
    g.zeta_k[i] = ci * g.inv_mean[i];
    g.zeta_sum += scale * ci * ci;
    scale *= 2.0;
    const float next_mean = i + 1 < SOL_AGM_LEVELS ? g.mean[i + 1] : g.c;
    ci = ci * ci / (4.0 * next_mean);
  }
  return g;
}

// tan x for |x| <= π/4: x + x³ P(x²), P of degree 5 fitted to the least
// relative error (scripts/fit_tan_quarter.py: within 1.5 float ulps of tan
// there, evaluated in float). One polynomial instead of sin and cos, which
// lavapipe expands into a range reduction and a series each.
float sol_tan_quarter(float x) {
  const float z = x * x;
  const float p = ((((9.3853911777e-3 * z + 3.1199745749e-3) * z + 2.4430073875e-2) * z + 5.3411308991e-2) * z +
                   1.3338798882e-1) * z + 3.3333156886e-1;
  return x + x * z * p;
}

// sn, cn, dn of |r| <= K/2: Bulirsch's multiplicative back-substitution
// down the AGM sequence over its first `levels` levels; dn from cn
// (dn² = m1 + m cn²), but for sol_forward_zeta's descent (SOL_ZETA_LEVELS
// levels) the last level's dn, which is dn(r) (a square root fewer; that
// path is tested on its own). With `zeta`, Jacobi's zeta function Z(r)
// from the same levels (docs/mathematics.md).
vec3 jacobi_agm(float r, float m, float m1, SolAgm agm, const int levels, out float zeta) {
  if (abs(r) < 0.0093) {  // r⁴ below rounding: Taylor series
    float r2 = r * r;
    zeta = r * (0.5 * (m + agm.zeta_sum) - m * r2 / 3.0);
    return vec3(r * (1.0 - (1.0 + m) * r2 / 6.0), 1.0 - r2 / 2.0, 1.0 - m * r2 / 2.0);
  }
  float c = agm.c, dn = 1.0;
  // |r| <= K/2 and c = π/(2K): |scaled| <= π/4, where the back-substitution
  // needs cot(scaled) and the sign of its sine alone.
  const float scaled = r * c;
  float ratio = 1.0 / sol_tan_quarter(scaled);
  c *= ratio;
  zeta = 0.0;
  for (int i = levels - 1; i >= 0; --i) {
    ratio *= c;
    c *= dn;
    dn = (agm.root[i] + ratio) / (agm.mean[i] + ratio);
    ratio = c * agm.inv_mean[i];
    // Level i: ratio = cn/sn and dn of (a_i r | k_i); Z(r) = Σ 2^i c_i sn cn dn/(1 + k_i sn²).
    if (i > 0) zeta += agm.zeta_coef[i] * ratio * dn / (1.0 + ratio * ratio + agm.zeta_k[i]);
  }
  float s = sign(scaled) / sqrt(c * c + 1.0);
  float cn_r = c * s;
  // (sol_forward_zeta's descent: dn from its last level, which is dn(r).)
  return vec3(s, cn_r, levels == SOL_ZETA_LEVELS ? dn : sqrt(m1 + m * cn_r * cn_r));
}

vec3 jacobi_agm(float r, float m, float m1, SolAgm agm) {
  float unused;
  return jacobi_agm(r, m, m1, agm, SOL_AGM_LEVELS, unused);
}

// sn, cn, dn of any u (xyz) and Jacobi's zeta function Z(u) = E(u) - (E/K) u
// (w): u = nK + r, |r| <= K/2, then the quarter shifts; Z has period 2K and
// Z(K + r) = Z(r) - m sn r cd r (the addition theorem of E).
vec4 jacobi_zeta(float u, float m, float m1, float K, float kc, SolAgm agm, const int levels) {
  float n = round(u / K);
  float r = u - n * K;
  float zeta;
  vec3 j = jacobi_agm(r, m, m1, agm, levels, zeta);
  int quarter = int(n - 4.0 * floor(n / 4.0));  // n mod 4 in [0, 3]
  if (quarter == 0) return vec4(j, zeta);
  if (quarter == 2) return vec4(-j.x, -j.y, j.z, zeta);
  // sn(K + r) = cd r, cn(K + r) = -k' sd r, dn(K + r) = k' nd r.
  vec3 shifted = vec3(j.y / j.z, -kc * j.x / j.z, kc / j.z);
  zeta -= m * j.x * shifted.x;
  return quarter == 1 ? vec4(shifted, zeta) : vec4(-shifted.x, -shifted.y, shifted.z, zeta);
}

// sn, cn, dn of any u.
vec3 jacobi(float u, float m, float m1, float K, float kc, SolAgm agm) { return jacobi_zeta(u, m, m1, K, kc, agm, SOL_AGM_LEVELS).xyz; }

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

// The unit tangent (frame components) of the closed-form ray at arc length t.
vec3 sol_direction(SolRay g, float t) {
  if (g.regime == REGIME_VERTICAL || g.regime == REGIME_STRAIGHT) return g.direction;
  if (g.regime == REGIME_PLANE) {
    const float v = t + g.s0;
    vec3 d = vec3(1.0 / cosh(v), 0.0, -tanh(v));
    if (g.swapped) d = vec3(d.y, d.x, -d.z);
    return vec3(g.sign_x * d.x, g.sign_y * d.y, d.z);
  }
  const SolPoint p = sol_point(g, g.lambda * t + g.u0);
  return vec3(g.sign_x * g.sqrt_mu * p.ew, g.sign_y * g.sqrt_mu / p.ew, -g.k * g.lambda * p.jac.x);
}
