// The elliptic functions of the kernels' closed-form geodesics, in float:
// Carlson's symmetric integrals R_F and R_D, and Jacobi's sn, cn, dn and
// zeta function by the AGM (Landen's descent). The GLSL mirror of
// libsol/src/elliptic.cpp and carlson.hpp (see sol_geodesic.glsl).
#ifndef SOL_ELLIPTIC_GLSL
#define SOL_ELLIPTIC_GLSL

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

#endif  // SOL_ELLIPTIC_GLSL
