#include "sol/elliptic.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "carlson.hpp"
#include "sol/error.hpp"

namespace sol::elliptic {
namespace {

template <class T>
void validate(T m, T m1, const char* function) {
  if (!std::isfinite(m) || !std::isfinite(m1) || m < T(0) || m1 < T(0) || m > T(1) || m1 > T(1) ||
      std::abs(m + m1 - T(1)) > T(8) * std::numeric_limits<T>::epsilon()) {
    throw InvalidArgument(std::string(function) + ": need m, m1 in [0, 1] with m + m1 = 1, got m = " +
                          std::to_string(static_cast<double>(m)) + ", m1 = " + std::to_string(static_cast<double>(m1)));
  }
}

template <class T>
void validate_argument(T x, const char* function) {
  if (!std::isfinite(x)) throw InvalidArgument(std::string(function) + ": argument is not finite");
}

template <class T>
constexpr T pi() {
  return T(3.141592653589793238462643383279502884L);
}

// F(φ|m) for φ ∈ [-π/2, π/2] from s = sin φ, c = cos φ >= 0 and
// Δ² = c² + m1 s² (DLMF 19.25.5, Δ² computed without cancellation).
template <class T>
T legendre_f(T s, T c, T delta2) {
  return s * detail::carlson_rf(c * c, delta2, T(1));
}

// Double-double arithmetic (Dekker; value = hi + lo, |lo| <= ulp(hi)/2) for
// K to ~1e-31: the period reduction u - nK must stay exact for n up to 2^20.
struct DD {
  double hi, lo;
};

DD dd_norm(double s, double e) {
  const double hi = s + e;
  return {hi, e - (hi - s)};
}

DD dd_add(DD a, DD b) {
  const double s = a.hi + b.hi;
  const double v = s - a.hi;
  const double e = (a.hi - (s - v)) + (b.hi - v);
  return dd_norm(s, e + a.lo + b.lo);
}

DD dd_mul(DD a, DD b) {
  const double p = a.hi * b.hi;
  const double e = std::fma(a.hi, b.hi, -p);
  return dd_norm(p, e + a.hi * b.lo + a.lo * b.hi);
}

DD dd_sqrt(DD a) {
  const double x = std::sqrt(a.hi);
  // One Newton step: x + (a - x²)/(2x), the residual exact through fma.
  const double residual = (a.hi - x * x - std::fma(x, x, -x * x)) + a.lo;
  return dd_norm(x, residual / (2 * x));
}

DD dd_div(DD a, DD b) {
  const double q1 = a.hi / b.hi;
  const DD r = dd_add(a, dd_mul(b, {-q1, 0.0}));
  const double q2 = r.hi / b.hi;
  const DD r2 = dd_add(r, dd_mul(b, {-q2, 0.0}));
  return dd_add(dd_norm(q1, q2), {r2.hi / b.hi, 0.0});
}

// K(m) = π / (2 AGM(1, k')) in double-double, k' = √m1 with m1 = 1 - m
// formed exactly from whichever of m, m1 is the smaller (and so exact).
template <class T>
DD complete_k_dd(T m, T m1) {
  const DD complement = m < m1 ? dd_add({1.0, 0.0}, {-static_cast<double>(m), 0.0}) : DD{static_cast<double>(m1), 0.0};
  DD a{1.0, 0.0}, b = dd_sqrt(complement);
  for (int i = 0; i < 64; ++i) {
    const DD diff = dd_add(a, {-b.hi, -b.lo});
    if (std::abs(diff.hi) <= 1e-31 * a.hi) break;
    const DD next_a = dd_mul(dd_add(a, b), {0.5, 0.0});
    b = dd_sqrt(dd_mul(a, b));
    a = next_a;
  }
  const DD pi{3.141592653589793116, 1.2246467991473532e-16};
  return dd_div(pi, dd_mul(a, {2.0, 0.0}));
}

// φ = nπ + r with r ∈ [-π/2, π/2]: returns n and sin r, cos r >= 0 taken
// from sin φ, cos φ themselves (libm reduces φ exactly), so φ near an odd
// multiple of π/2 lands on the correct side of the singularity of F.
template <class T>
T reduce_angle(T phi, T& s, T& c) {
  T n = std::round(phi / pi<T>());
  const T sign = std::fmod(n, T(2)) == T(0) ? T(1) : T(-1);
  s = sign * std::sin(phi);
  c = sign * std::cos(phi);
  if (c < T(0)) {  // φ/π rounded across the boundary: take the neighbouring n
    n += phi > n * pi<T>() ? T(1) : T(-1);
    s = -s;
    c = -c;
  }
  return n;
}

// sn, cn, dn of r with |r| <= K/2: the arithmetic–geometric mean of 1 and k'
// followed by Bulirsch's multiplicative back-substitution (R. Bulirsch,
// "Numerical calculation of elliptic integrals and elliptic functions",
// Numer. Math. 7 (1965) 78–90, procedure sncndn). It starts from cot of the
// scaled argument (|r| AGM ≤ π/4 here, so that cosine is not small) and
// carries cn/sn and dn through products and sums of positive terms, so cn
// and dn keep relative accuracy where the angle-based Landen recursion
// (cn = cos φ with φ near π/2 when m → 1) loses it.
template <class T>
Jacobi<T> jacobi_agm(T r, T m, T m1) {
  // Taylor series where r^4 is below rounding (also avoids cot overflow).
  const T small = T(0.5) * std::sqrt(std::sqrt(std::numeric_limits<T>::epsilon()));
  if (std::abs(r) < small) {
    const T r2 = r * r;
    return {r * (T(1) - (T(1) + m) * r2 / T(6)), T(1) - r2 / T(2), T(1) - m * r2 / T(2)};
  }
  constexpr int kMax = 16;
  const T tol = std::sqrt(std::numeric_limits<T>::epsilon());  // quadratic convergence: one more step reaches eps
  T mean[kMax], root[kMax];
  T a = T(1), c = T(1), dn = T(1), b_sq = m1;
  int last = 0;
  for (int i = 0; i < kMax; ++i) {
    last = i;
    mean[i] = a;
    root[i] = std::sqrt(b_sq);  // b_i
    c = (a + root[i]) / T(2);
    if (std::abs(a - root[i]) <= tol * a) break;
    b_sq = root[i] * a;  // b_{i+1}^2 = a_i b_i
    a = c;
  }
  const T scaled = r * c;
  const T sn = std::sin(scaled), cn = std::cos(scaled);
  T ratio = cn / sn;  // carries cn/sn (times products of dn) up the sequence
  c *= ratio;
  for (int i = last; i >= 0; --i) {
    ratio *= c;
    c *= dn;
    dn = (root[i] + ratio) / (mean[i] + ratio);
    ratio = c / mean[i];
  }
  const T s = std::copysign(T(1) / std::sqrt(c * c + T(1)), sn);
  const T cn_r = c * s;
  // dn from cn (dn² = m1 + m cn², both terms positive): relatively as good as
  // cn, where the recursion's own dn gathers ~20 ulp near r = K/2 as m → 1.
  (void)dn;
  return {s, cn_r, std::sqrt(m1 + m * cn_r * cn_r)};
}

// The working precision of the reduction and the AGM chain: double for
// both. For float this costs nothing on a CPU (scalar double is as fast) and
// keeps the result within a few ulp where float arithmetic would lose
// r·tanh r ulp (the conditioning of cn, dn in r) as m → 1.
using Work = double;

// u = nK + r with r ∈ [-K/2, K/2], exact to the rounding of r for any n: K
// is carried as K + K_lo and nK is subtracted exactly (fma; in float the
// products are exact in double).
template <class T>
Work reduce_quarter(T u, const Parameter<T>& p, T& n) {
  n = std::round(u / p.K);
  const Work nw = n;
  return std::fma(-nw, static_cast<Work>(p.K), static_cast<Work>(u)) - nw * static_cast<Work>(p.K_lo);
}

// The Jacobi functions of u as h half periods plus a residual v ∈ [-K, K]
// (where cn v >= 0), every value relatively accurate.
template <class T>
struct Reduced {
  T h;           // u = 2hK + v
  Jacobi<T> v;   // sn v, cn v >= 0, dn v
  T residual;    // v (to the rounding of K's multiples)
};

template <class T>
Reduced<T> reduce(T u, const Parameter<T>& p) {
  T n;
  const Work r = reduce_quarter(u, p, n);
  const Work m = p.m, m1 = p.m1, kc = std::sqrt(m1), K = static_cast<Work>(p.K) + static_cast<Work>(p.K_lo);
  const Jacobi<Work> j = jacobi_agm(r, m, m1);
  const T quarter = std::fmod(n, T(2));  // -1, 0 or 1
  if (quarter == T(0)) return {n / T(2), {T(j.sn), T(j.cn), T(j.dn)}, T(r)};
  // Odd n: the quarter shift sn(K + r) = cd r, cn(K + r) = -k' sd r, dn(K + r) = k' nd r.
  const T cd = T(j.cn / j.dn), sd = T(kc * j.sn / j.dn), nd = T(kc / j.dn);
  if (r <= Work(0)) return {(n - T(1)) / T(2), {cd, -sd, nd}, T(K + r)};  // v = K + r ∈ [K/2, K]
  return {(n + T(1)) / T(2), {-cd, sd, nd}, T(r - K)};                      // v = r - K ∈ [-K, -K/2)
}

bool odd(double h) { return std::fmod(h, 2.0) != 0.0; }

// E(φ|m) with sin φ = s, cos φ = c >= 0, Δ = d, as a sum of positive terms
// (DLMF 19.25.10): E = k'² F + (k² k'²/3) s³ R_D(c², 1, Δ²) + k² s c / Δ.
template <class T>
T legendre_e_positive(T s, T c, T d, T m, T m1) {
  const T c2 = c * c, d2 = d * d;
  if (d2 == T(0)) return s;  // m = 1 at φ = ±π/2: E = sin φ
  return m1 * s * detail::carlson_rf(c2, d2, T(1)) + m * m1 / T(3) * s * s * s * detail::carlson_rd(c2, T(1), d2) +
         m * s * c / d;
}

}  // namespace

template <class T>
T complete_k(T m, T m1) {
  validate(m, m1, "sol::elliptic::complete_k");
  if (m1 == T(0)) return std::numeric_limits<T>::infinity();
  return static_cast<T>(complete_k_dd(m, m1).hi);
}

template <class T>
T complete_e(T m, T m1) {
  validate(m, m1, "sol::elliptic::complete_e");
  if (m1 == T(0)) return T(1);
  return m1 / T(3) * (detail::carlson_rd(T(0), m1, T(1)) + detail::carlson_rd(T(0), T(1), m1));
}

template <class T>
Parameter<T> make_parameter(T m, T m1) {
  validate(m, m1, "sol::elliptic::make_parameter");
  if (m1 == T(0)) throw InvalidArgument("sol::elliptic::make_parameter: m = 1 (K infinite)");
  Parameter<T> p;
  p.m = m;
  p.m1 = m1;
  p.k = std::sqrt(m);
  p.kc = std::sqrt(m1);
  const DD K = complete_k_dd(m, m1);
  p.K = static_cast<T>(K.hi);
  p.K_lo = (K.hi - static_cast<double>(p.K)) + K.lo;
  p.E = complete_e(m, m1);
  return p;
}

template <class T>
T incomplete_f(T phi, T m, T m1) {
  validate(m, m1, "sol::elliptic::incomplete_f");
  validate_argument(phi, "sol::elliptic::incomplete_f");
  T s, c;
  const T n = reduce_angle(phi, s, c);
  const T f = legendre_f(s, c, c * c + m1 * s * s);
  return n == T(0) ? f : f + T(2) * n * complete_k(m, m1);
}

template <class T>
T incomplete_e(T phi, T m, T m1) {
  validate(m, m1, "sol::elliptic::incomplete_e");
  validate_argument(phi, "sol::elliptic::incomplete_e");
  T s, c;
  const T n = reduce_angle(phi, s, c);
  const T e = legendre_e_positive(s, c, std::sqrt(c * c + m1 * s * s), m, m1);
  return n == T(0) ? e : e + T(2) * n * complete_e(m, m1);
}

template <class T>
Jacobi<T> jacobi(T u, const Parameter<T>& p) {
  validate_argument(u, "sol::elliptic::jacobi");
  Reduced<T> r = reduce(u, p);
  if (odd(static_cast<double>(r.h))) {  // odd number of half periods: sn, cn change sign
    r.v.sn = -r.v.sn;
    r.v.cn = -r.v.cn;
  }
  return r.v;
}

template <class T>
Jacobi<T> jacobi(T u, T m, T m1) {
  return jacobi(u, make_parameter(m, m1));
}

template <class T>
T amplitude(T u, const Parameter<T>& p) {
  validate_argument(u, "sol::elliptic::amplitude");
  const Reduced<T> r = reduce(u, p);
  return r.h * pi<T>() + std::atan2(r.v.sn, r.v.cn);
}

template <class T>
T amplitude(T u, T m, T m1) {
  return amplitude(u, make_parameter(m, m1));
}

template <class T>
T epsilon(T u, const Parameter<T>& p) {
  validate_argument(u, "sol::elliptic::epsilon");
  const Reduced<T> r = reduce(u, p);
  return T(2) * r.h * p.E + legendre_e_positive(r.v.sn, r.v.cn, r.v.dn, p.m, p.m1);
}

template <class T>
T epsilon(T u, T m, T m1) {
  return epsilon(u, make_parameter(m, m1));
}

template <class T>
T zeta(T u, const Parameter<T>& p) {
  // Z is 2K-periodic: evaluate on the residual so no large terms cancel.
  validate_argument(u, "sol::elliptic::zeta");
  const Reduced<T> r = reduce(u, p);
  return legendre_e_positive(r.v.sn, r.v.cn, r.v.dn, p.m, p.m1) - p.E / p.K * r.residual;
}

template <class T>
T zeta(T u, T m, T m1) {
  return zeta(u, make_parameter(m, m1));
}

#define SOL_ELLIPTIC_INSTANTIATE(T)                                 \
  template Parameter<T> make_parameter<T>(T, T);                   \
  template T complete_k<T>(T, T);                                   \
  template T complete_e<T>(T, T);                                   \
  template T incomplete_f<T>(T, T, T);                              \
  template T incomplete_e<T>(T, T, T);                              \
  template Jacobi<T> jacobi<T>(T, const Parameter<T>&);             \
  template Jacobi<T> jacobi<T>(T, T, T);                            \
  template T amplitude<T>(T, const Parameter<T>&);                  \
  template T amplitude<T>(T, T, T);                                 \
  template T epsilon<T>(T, const Parameter<T>&);                    \
  template T epsilon<T>(T, T, T);                                   \
  template T zeta<T>(T, const Parameter<T>&);                       \
  template T zeta<T>(T, T, T);

SOL_ELLIPTIC_INSTANTIATE(float)
SOL_ELLIPTIC_INSTANTIATE(double)

}  // namespace sol::elliptic
