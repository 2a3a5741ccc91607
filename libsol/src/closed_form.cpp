#include "sol/closed_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include <glm/geometric.hpp>

#include "carlson.hpp"
#include "check.hpp"

// Notation and derivation: see closed_form.hpp. In the reduced frame
// (a, b >= 0) with s = e^{2w}: s₋ = ((1-k)/k')^2 and s₊ = ((1+k)/k')^2 are the
// turning points (s₋ s₊ = 1), w'^2 = μ (s - s₋)(s₊ - s)/s, so
//   ∫ s dt = (1/(2√μ)) ∫ √s ds / √((s - s₋)(s₊ - s)),
// and ∫ (1/s) dt is the same integral in σ = 1/s (which maps s₋ ↔ s₊).
// Every factor at a point is computed without cancellation from sn, cn, dn:
//   cn >= 0:  e^{w} = (dn + k cn)/k',   e^{W} - e^{w} = k sn² (k/(1+dn) + 1/(1+cn)) / k'
//   cn <  0:  e^{w} = k'/(dn - k cn),   e^{w} - e^{-W} = k sn² ((1-k) + (dn + k cn)) / ((1-cn)(1+dn) k')
//   s - 1 = 2 e^{w} sinh w = 2 e^{w} k cn / k',
// with 1 - s₋ = 2k/(1+k), s₊ - 1 = 2k(1+k)/k'^2, s₊ - s₋ = 4k/k'^2 exact.

namespace sol {
namespace {

template <class T>
struct Factors {
  T x1, x2, x3;  // √t, √(t - s₋), √(s₊ - t) at one limit
};

// Carlson's [1,-1,-1] integral ∫ √t dt / √((t - s₋)(s₊ - t)) between limits
// with factors x and y, |x - y| = gap; d12 d13 = -s₋ s₊ = -1:
//   J = 2 X1 Y1 / U1 - (2/3) R_D(U2², U3², U1²),  U_i = V_i / gap.
// U can overflow when μ is small (V ~ √s₊ (s₊ - s₋)) and the gap tiny, so
// with V_i = W_i V_max and r = gap / V_max, using R_D's homogeneity:
//   J = 2 X1 Y1 r / W1 - (2/3) r³ R_D(W2², W3², W1²),
// every argument in [0, 1]. For a small gap the first term is the integrand
// times the gap and the second O(gap³): nothing cancels, nothing is dropped.
template <class T>
T carlson_piece(const Factors<T>& x, const Factors<T>& y, T gap) {
  if (!(gap > T(0))) return T(0);
  const T v1 = x.x1 * y.x2 * y.x3 + y.x1 * x.x2 * x.x3;
  const T v2 = x.x2 * y.x1 * y.x3 + y.x2 * x.x1 * x.x3;
  const T v3 = x.x3 * y.x1 * y.x2 + y.x3 * x.x1 * x.x2;
  const T v_max = std::max({v1, v2, v3});
  if (!(v1 > T(0))) return T(0);  // both limits at turning points: not a piece within one quarter
  const T w1 = v1 / v_max, w2 = v2 / v_max, w3 = v3 / v_max, r = gap / v_max;
  return T(2) * x.x1 * y.x1 * r / w1 - T(2) / T(3) * r * r * r * detail::carlson_rd(w2 * w2, w3 * w3, w1 * w1);
}

// Factors of σ = 1/t from those of t: σ - s₋ = s₋ (s₊ - t)/t, s₊ - σ = s₊ (t - s₋)/t.
template <class T>
Factors<T> reciprocal(const Factors<T>& f, T sqrt_sm, T sqrt_sp) {
  return {T(1) / f.x1, sqrt_sm * f.x3 / f.x1, sqrt_sp * f.x2 / f.x1};
}

template <class T>
T log_cosh(T v) {
  const T a = std::abs(v);
  return a + std::log1p(std::exp(T(-2) * a)) - T(0.69314718055994530942);
}

constexpr int kStartAnchor[4] = {0, 1, 2, 1};
constexpr int kEndAnchor[4] = {1, 2, 1, 0};

}  // namespace

template <class T>
ClosedFormGeodesic<T>::ClosedFormGeodesic(const Vec3& direction) {
  constexpr const char* function = "sol::ClosedFormGeodesic";
  detail::require_finite(glm::dvec3(direction), function, "direction");
  if (glm::length(glm::dvec3(direction)) == 0.0) throw InvalidArgument("sol::ClosedFormGeodesic: zero direction");
  m_direction = Vec3(glm::normalize(glm::dvec3(direction)));
  m_sign_x = m_direction.x < T(0) ? T(-1) : T(1);
  m_sign_y = m_direction.y < T(0) ? T(-1) : T(1);
  m_a = std::abs(m_direction.x);
  m_b = std::abs(m_direction.y);
  m_c = m_direction.z;
  if (m_a == T(0) && m_b == T(0)) {
    m_regime = Regime::Vertical;
    return;
  }
  m_mu = m_a * m_b;
  // Below this μ the geodesic leaves its hyperbolic plane by about μ e^{2|z|}:
  // < 1e-30 for |z| < 100 in double, < 1e-7 for |z| < 20 in float, below the
  // rounding of each; above it the factors (up to √s₊ ~ μ^{-1/2}) and their
  // triple products (Carlson pieces) stay within range of each type.
  const T mu_plane = std::is_same_v<T, float> ? T(1e-24) : T(1e-120);
  if (m_mu < mu_plane) {
    m_regime = Regime::Plane;
    if (m_b > m_a) {  // the plane x = const: map to y = const by (x,y,z) -> (y,x,-z)
      m_swapped = true;
      std::swap(m_a, m_b);
      m_c = -m_c;
    }
    m_s0 = std::asinh(-m_c / m_a);
    return;
  }
  // 1 - 2ab = (a - b)^2 + c^2 for a unit vector: m without cancellation.
  const T m2 = (m_a - m_b) * (m_a - m_b) + m_c * m_c;
  if (m2 == T(0)) {
    m_regime = Regime::Straight;
    return;
  }
  m_regime = Regime::General;
  m_sqrt_mu = std::sqrt(m_mu);
  m_lambda = std::sqrt(T(1) + T(2) * m_mu);
  // A direction normalised to rounding can give m2 > λ² by an ulp when μ is
  // tiny (m ≈ 1): m <= 1 keeps the parameter valid (m + m1 = 1 to rounding).
  const T m = std::min(T(1), m2 / (m_lambda * m_lambda));
  const T m1 = T(4) * m_mu / (m_lambda * m_lambda);
  m_k = std::sqrt(m);
  m_kc = T(2) * m_sqrt_mu / m_lambda;
  m_parameter = elliptic::make_parameter(m, m1);
  m_K = m_parameter.K;
  m_w0 = T(0.5) * (std::log(m_a) - std::log(m_b));
  // u0 = F(am u0) from sn u0 = -c/(kλ), cn u0 = (a - b)/(kλ), dn u0 = (a + b)/λ
  // (kλ = √m2) directly, never through the angle: when c → ±1 the amplitude
  // sits next to ±π/2, where F is so steep (1/Δ ~ 1/k') that rounding the
  // angle would cost digits.
  {
    const T root = std::sqrt(m2);
    const T sn0 = -m_c / root, cn0 = (m_a - m_b) / root, dn0 = (m_a + m_b) / m_lambda;
    const T f = sn0 * detail::carlson_rf(cn0 * cn0, dn0 * dn0, T(1));  // F of the angle with cos = |cn0|
    m_u0 = cn0 >= T(0) ? f : (sn0 < T(0) ? T(-2) : T(2)) * m_K - f;  // beyond ±π/2: F(±π - φ) = ±2K - F(φ)
  }
  m_sqrt_sm = m_kc / (T(1) + m_k);
  m_sqrt_sp = (T(1) + m_k) / m_kc;
  m_one_minus_sm = T(2) * m_k / (T(1) + m_k);
  m_sp_minus_one = T(2) * m_k * (T(1) + m_k) / m1;
  m_sp_minus_sm = T(4) * m_k / m1;
  const Factors<T> bottom{m_sqrt_sm, T(0), std::sqrt(m_sp_minus_sm)};
  const Factors<T> middle{T(1), std::sqrt(m_one_minus_sm), std::sqrt(m_sp_minus_one)};
  const Factors<T> top{m_sqrt_sp, std::sqrt(m_sp_minus_sm), T(0)};
  m_quarter_lo = carlson_piece(bottom, middle, m_one_minus_sm) / (T(2) * m_sqrt_mu);
  m_quarter_hi = carlson_piece(middle, top, m_sp_minus_one) / (T(2) * m_sqrt_mu);
  m_start = point_at(m_u0);
  m_start_quarter = absolute_quarter(m_u0, m_start.quarter);
  anchor_piece(m_start, kStartAnchor[m_start.quarter], m_head_a, m_head_b);
  anchor_piece(m_start, kEndAnchor[m_start.quarter], m_tail_a, m_tail_b);
}

template <class T>
T ClosedFormGeodesic<T>::phase(T t) const {
  const T u = m_lambda * t + m_u0;
  // Beyond 2^52 quarter periods (2^23 in float) the phase is lost to rounding
  // (and the quarter count to integer range): refuse rather than guess.
  const T max_quarters = std::is_same_v<T, float> ? T(8388608) : T(4503599627370496.0);
  if (!(std::abs(u) < max_quarters * m_K)) {
    throw OutOfRange("sol::ClosedFormGeodesic: arc length " + std::to_string(static_cast<double>(t)) +
                     " too long for the precision of the phase");
  }
  return u;
}

template <class T>
typename ClosedFormGeodesic<T>::Point ClosedFormGeodesic<T>::point_at(T u) const {
  const elliptic::Jacobi<T> j = elliptic::jacobi(u, m_parameter);
  Point p;
  p.sn = j.sn;
  p.cn = j.cn;
  p.dn = j.dn;
  const T k = m_k, kc = m_kc, sn2 = j.sn * j.sn;
  if (j.cn >= T(0)) {
    p.ew = (j.dn + k * j.cn) / kc;
    const T top_gap = k * sn2 * (k / (T(1) + j.dn) + T(1) / (T(1) + j.cn)) / kc;  // e^{W} - e^{w}
    p.f3 = top_gap * (m_sqrt_sp + p.ew);
    p.sm1 = T(2) * p.ew * k * j.cn / kc;
    p.f2 = p.sm1 + m_one_minus_sm;
  } else {
    const T dmk = j.dn - k * j.cn;  // > dn >= k'
    p.ew = kc / dmk;
    const T one_minus_k = kc * kc / (T(1) + k);
    const T bottom_gap = k * sn2 * (one_minus_k + kc * p.ew) / ((T(1) - j.cn) * (T(1) + j.dn) * kc);  // e^{w} - e^{-W}
    p.f2 = bottom_gap * (p.ew + m_sqrt_sm);
    p.sm1 = T(2) * p.ew * k * j.cn / kc;
    p.f3 = m_sp_minus_one - p.sm1;
  }
  p.quarter = j.sn < T(0) ? (j.cn < T(0) ? 0 : 1) : (j.cn >= T(0) ? 2 : 3);
  return p;
}

template <class T>
std::int64_t ClosedFormGeodesic<T>::absolute_quarter(T u, int quarter) const {
  auto q = static_cast<std::int64_t>(std::floor((u + T(2) * m_K) / m_K));
  const int r = static_cast<int>(((q % 4) + 4) % 4);
  const int diff = (quarter - r + 4) % 4;
  // u near a quarter boundary may round to the neighbour of the quarter that
  // the signs of sn and cn (which the pieces use) say: follow the signs.
  if (diff == 1) ++q;
  if (diff == 3) --q;
  return q;
}

template <class T>
void ClosedFormGeodesic<T>::anchor_piece(const Point& p, int anchor, T& integral_a, T& integral_b) const {
  const Factors<T> fp{p.ew, std::sqrt(p.f2), std::sqrt(p.f3)};
  Factors<T> fa;
  T gap, s_anchor;
  switch (anchor) {
    case 0:
      fa = {m_sqrt_sm, T(0), std::sqrt(m_sp_minus_sm)};
      gap = p.f2;
      s_anchor = m_sqrt_sm * m_sqrt_sm;
      break;
    case 1:
      fa = {T(1), std::sqrt(m_one_minus_sm), std::sqrt(m_sp_minus_one)};
      gap = std::abs(p.sm1);
      s_anchor = T(1);
      break;
    default:
      fa = {m_sqrt_sp, std::sqrt(m_sp_minus_sm), T(0)};
      gap = p.f3;
      s_anchor = m_sqrt_sp * m_sqrt_sp;
      break;
  }
  const T scale = T(1) / (T(2) * m_sqrt_mu);
  integral_a = carlson_piece(fp, fa, gap) * scale;
  const T gap_sigma = gap / (p.ew * p.ew * s_anchor);
  integral_b = carlson_piece(reciprocal(fp, m_sqrt_sm, m_sqrt_sp), reciprocal(fa, m_sqrt_sm, m_sqrt_sp), gap_sigma) * scale;
}

template <class T>
void ClosedFormGeodesic<T>::two_point_piece(const Point& p, const Point& q, T& integral_a, T& integral_b) const {
  // |s_p - s_q| from the representation with the smaller operands (each is
  // relatively accurate, so the difference is accurate to ~eps of them).
  const bool lower = p.quarter == 0 || p.quarter == 3;
  const T via_anchor = lower ? std::abs(p.f2 - q.f2) : std::abs(p.f3 - q.f3);
  const T size_anchor = lower ? std::max(p.f2, q.f2) : std::max(p.f3, q.f3);
  const T via_middle = std::abs(p.sm1 - q.sm1);
  const T size_middle = std::max(std::abs(p.sm1), std::abs(q.sm1));
  const T gap = size_anchor < size_middle ? via_anchor : via_middle;
  const Factors<T> fp{p.ew, std::sqrt(p.f2), std::sqrt(p.f3)};
  const Factors<T> fq{q.ew, std::sqrt(q.f2), std::sqrt(q.f3)};
  const T scale = T(1) / (T(2) * m_sqrt_mu);
  integral_a = carlson_piece(fp, fq, gap) * scale;
  const T gap_sigma = gap / (p.ew * p.ew * q.ew * q.ew);
  integral_b = carlson_piece(reciprocal(fp, m_sqrt_sm, m_sqrt_sp), reciprocal(fq, m_sqrt_sm, m_sqrt_sp), gap_sigma) * scale;
}

template <class T>
void ClosedFormGeodesic<T>::quarters(std::int64_t first, std::int64_t last, T& integral_a, T& integral_b) const {
  integral_a = integral_b = T(0);
  if (last < first) return;
  const std::int64_t count = last - first + 1;
  const std::int64_t periods = count / 4;
  // Over a lower quarter s integrates to quarter_lo and 1/s to quarter_hi (the
  // symmetry w -> -w), and the other way round over an upper quarter.
  integral_a = integral_b = static_cast<T>(periods) * T(2) * (m_quarter_lo + m_quarter_hi);
  for (std::int64_t j = first + 4 * periods; j <= last; ++j) {
    const int q = static_cast<int>(((j % 4) + 4) % 4);
    const bool lower = q == 0 || q == 3;
    integral_a += lower ? m_quarter_lo : m_quarter_hi;
    integral_b += lower ? m_quarter_hi : m_quarter_lo;
  }
}

template <class T>
typename ClosedFormGeodesic<T>::State ClosedFormGeodesic<T>::plane(T t) const {
  // The hyperbolic plane y = 0 (metric e^{-2z}dx^2 + dz^2; (x, e^{z}) is the
  // upper half-plane): x = sinh t / cosh(t + s0), e^{z} = cosh s0 / cosh(t + s0),
  // with sinh s0 = -c/a, cosh s0 = 1/a.
  const T v = t + m_s0;
  T x;
  if (std::max(std::abs(t), std::abs(v)) < T(40)) {
    x = std::sinh(t) / std::cosh(v);
  } else {
    const T at = std::abs(t);
    const T log_sinh = at + std::log1p(-std::exp(T(-2) * at)) - T(0.69314718055994530942);
    x = std::copysign(std::exp(log_sinh - log_cosh(v)), t);
  }
  const T z = log_cosh(m_s0) - log_cosh(v);
  Vec3 position(x, T(0), z);
  Vec3 direction(T(1) / std::cosh(v), T(0), -std::tanh(v));
  if (m_swapped) {
    position = Vec3(position.y, position.x, -position.z);
    direction = Vec3(direction.y, direction.x, -direction.z);
  }
  position.x *= m_sign_x;
  direction.x *= m_sign_x;
  position.y *= m_sign_y;
  direction.y *= m_sign_y;
  return {position, direction};
}

template <class T>
typename ClosedFormGeodesic<T>::State ClosedFormGeodesic<T>::at(T t) const {
  switch (m_regime) {
    case Regime::Vertical:
      return {Vec3(T(0), T(0), m_c * t), m_direction};
    case Regime::Straight:
      return {Vec3(m_direction.x * t, m_direction.y * t, T(0)), m_direction};
    case Regime::Plane:
      return plane(t);
    case Regime::General:
      break;
  }
  const T u = phase(t);
  const Point p = point_at(u);
  const std::int64_t q = absolute_quarter(u, p.quarter);
  T ia = 0, ib = 0;
  if (q == m_start_quarter) {
    two_point_piece(m_start, p, ia, ib);
    if (t < T(0)) {
      ia = -ia;
      ib = -ib;
    }
  } else if (q > m_start_quarter) {
    T qa, qb, ha, hb;
    quarters(m_start_quarter + 1, q - 1, qa, qb);
    anchor_piece(p, kStartAnchor[p.quarter], ha, hb);
    ia = m_tail_a + qa + ha;
    ib = m_tail_b + qb + hb;
  } else {
    T qa, qb, ta, tb;
    quarters(q + 1, m_start_quarter - 1, qa, qb);
    anchor_piece(p, kEndAnchor[p.quarter], ta, tb);
    ia = -(m_head_a + qa + ta);
    ib = -(m_head_b + qb + tb);
  }
  // x' = b e^{2w}, y' = a e^{-2w} in the reduced frame; e^{z} = e^{w - w0}.
  const Vec3 position(m_sign_x * m_b * ia, m_sign_y * m_a * ib, std::log(p.ew) - m_w0);
  const Vec3 direction(m_sign_x * m_sqrt_mu * p.ew, m_sign_y * m_sqrt_mu / p.ew, -m_k * m_lambda * p.sn);
  return {position, direction};
}

template <class T>
typename ClosedFormGeodesic<T>::Vec3 ClosedFormGeodesic<T>::direction_at(T t) const {
  if (m_regime != Regime::General) return at(t).direction;
  const Point p = point_at(phase(t));
  return Vec3(m_sign_x * m_sqrt_mu * p.ew, m_sign_y * m_sqrt_mu / p.ew, -m_k * m_lambda * p.sn);
}

template <class T>
T ClosedFormGeodesic<T>::height_at(T t) const {
  switch (m_regime) {
    case Regime::Vertical:
      return m_c * t;
    case Regime::Straight:
      return T(0);
    case Regime::Plane:
      return plane(t).position.z;
    case Regime::General:
      break;
  }
  return std::log(point_at(phase(t)).ew) - m_w0;
}

template <class T>
T ClosedFormGeodesic<T>::min_height() const {
  constexpr T inf = std::numeric_limits<T>::infinity();
  switch (m_regime) {
    case Regime::Vertical:
      return m_c == T(0) ? T(0) : -inf;
    case Regime::Straight:
      return T(0);
    case Regime::Plane:  // the top is at v = 0: z = log cosh s0 (negated when swapped)
      return m_swapped ? -log_cosh(m_s0) : -inf;
    case Regime::General:
      break;
  }
  return std::log(m_sqrt_sm) - m_w0;
}

template <class T>
T ClosedFormGeodesic<T>::max_height() const {
  constexpr T inf = std::numeric_limits<T>::infinity();
  switch (m_regime) {
    case Regime::Vertical:
      return m_c == T(0) ? T(0) : inf;
    case Regime::Straight:
      return T(0);
    case Regime::Plane:
      return m_swapped ? inf : log_cosh(m_s0);
    case Regime::General:
      break;
  }
  return std::log(m_sqrt_sp) - m_w0;
}

template <class T>
T ClosedFormGeodesic<T>::period() const {
  if (m_regime != Regime::General) return std::numeric_limits<T>::infinity();
  return T(4) * m_K / m_lambda;
}

template <class T>
typename ClosedFormGeodesic<T>::Vec3 ClosedFormGeodesic<T>::period_shift() const {
  if (m_regime != Regime::General) return Vec3(T(0));
  const T full = T(2) * (m_quarter_lo + m_quarter_hi);
  return Vec3(m_sign_x * m_b * full, m_sign_y * m_a * full, T(0));
}

template class ClosedFormGeodesic<float>;
template class ClosedFormGeodesic<double>;

}  // namespace sol
