// Closed-form Sol geodesics from the origin, exact to rounding in every regime.
//
// A unit direction (a, b, c) (frame components) is reduced by the symmetries
// (±x, ±y, z) to A = |a|, B = |b| >= 0. With μ = AB and w = z - ½ln(B/A), the
// height oscillates in the potential 2μ cosh 2w (w'^2 + 2μ cosh 2w = 1) and
//   x' = B e^{2w},  y' = A e^{-2w},  u = (√μ e^{w}, √μ e^{-w}, w')
// in the reduced frame. Jacobi functions of u = λt + u0 with
// λ = √(1+2μ), m = ((A-B)^2 + c^2)/λ^2, m1 = 4μ/λ^2 (both exact, docs/mathematics.md) give
//   e^{w} = (dn + k cn)/k' = k'/(dn - k cn),  w' = -kλ sn,
// the top of the oscillation at u = 0. The positions are the time integrals
// of s = e^{2w} and 1/s. These are never formed as differences of elliptic
// integrals (which cancel catastrophically when μ → 0); instead each piece of
// path between an anchor (a turning point s± or the middle s = 1) and the
// point, or between two points of one quarter period, is evaluated with
// Carlson's formula for integrals between arbitrary limits (B. C. Carlson,
// "A table of elliptic integrals of the second kind", Math. Comp. 49 (1987)
// 595–606, the case [1,-1,-1]):
//   ∫_y^x √t dt / √((t - s₋)(s₊ - t)) = 2 X1 Y1 / U1 - (2/3) s₋ s₊ R_D(U2², U3², U1²),
// all of whose terms are positive sums, so the result loses at most one bit.
// The pieces are positive and summed, so x and y carry relative accuracy.
// Whole periods are added in one step (γ(t + T) = (X_T, Y_T, 0) * γ(t)), so
// the cost does not grow with t.
//
// Degenerate regimes are exact closed forms: vertical lines (a = b = 0),
// geodesics of the hyperbolic planes x = const or y = const (ab = 0, and
// μ < 1e-120, whose deviation from the plane is below rounding), and the
// straight lines |a| = |b|, c = 0.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "sol/elliptic.hpp"

namespace sol {

template <class T>
class ClosedFormGeodesic {
 public:
  using Vec3 = glm::vec<3, T, glm::defaultp>;
  struct State {
    Vec3 position;   ///< relative to the start (the geodesic starts at the origin)
    Vec3 direction;  ///< unit tangent, frame components
  };

  /// Precomputes everything that depends only on the direction (normalised;
  /// non-finite or zero throws InvalidArgument).
  explicit ClosedFormGeodesic(const Vec3& direction);

  /// The geodesic at arc length t (either sign). Cost independent of |t|.
  /// Throws OutOfRange when t is so long that the phase of the z-oscillation
  /// is lost to rounding (over 2^50 periods in double, 2^21 in float).
  State at(T t) const;

  /// Only the unit tangent at arc length t (cheaper than at(t)).
  Vec3 direction_at(T t) const;

  /// Only the height z at arc length t (cheaper than at(t): no integrals).
  T height_at(T t) const;

  /// The range of heights the whole geodesic (t in R) visits: z oscillates
  /// between the turning points when ab != 0; ±inf where z is unbounded.
  T min_height() const;
  T max_height() const;

  /// Arc length of one z-oscillation (+inf when z does not oscillate).
  T period() const;
  /// (X_T, Y_T, 0) with γ(t + T) = (X_T, Y_T, 0) * γ(t); zero when no period.
  Vec3 period_shift() const;

  const Vec3& direction() const { return m_direction; }

  // Values of the path at one parameter u (public for tests and kernels' mirrors).
  struct Point {
    T sn, cn, dn;
    T ew;   ///< e^{w} = √s
    T f2;   ///< s - s₋
    T f3;   ///< s₊ - s
    T sm1;  ///< s - 1
    int quarter;  ///< 0: bottom→middle, 1: middle→top, 2: top→middle, 3: middle→bottom
  };

 private:
  enum class Regime : std::uint8_t { Vertical, Plane, Straight, General };

  T phase(T t) const;  // u = λt + u0; throws OutOfRange when the phase exceeds precision
  Point point_at(T u) const;
  std::int64_t absolute_quarter(T u, int quarter) const;
  // Time integrals of s (A) and 1/s (B) from a point to an anchor (0: s₋, 1: middle, 2: s₊).
  void anchor_piece(const Point& p, int anchor, T& integral_a, T& integral_b) const;
  void two_point_piece(const Point& p, const Point& q, T& integral_a, T& integral_b) const;
  void quarters(std::int64_t first, std::int64_t last, T& integral_a, T& integral_b) const;
  State plane(T t) const;

  Vec3 m_direction;
  Regime m_regime = Regime::General;
  T m_sign_x = 1, m_sign_y = 1;  // reduction by (±x, ±y, z)
  bool m_swapped = false;        // plane regime: x = const mapped to y = const by (y, x, -z)
  T m_a = 0, m_b = 0, m_c = 0;   // reduced direction (a, b >= 0)
  // Plane regime.
  T m_s0 = 0;
  // General regime.
  T m_mu = 0, m_sqrt_mu = 0, m_lambda = 0, m_k = 0, m_kc = 0, m_w0 = 0;
  elliptic::Parameter<T> m_parameter{};
  T m_K = 0, m_u0 = 0;
  T m_sqrt_sm = 0, m_sqrt_sp = 0, m_one_minus_sm = 0, m_sp_minus_one = 0, m_sp_minus_sm = 0;
  T m_quarter_lo = 0, m_quarter_hi = 0;  // time integral of s over a lower / upper quarter
  Point m_start{};
  std::int64_t m_start_quarter = 0;
  T m_head_a = 0, m_head_b = 0, m_tail_a = 0, m_tail_b = 0;  // start to its quarter's start / end
};

extern template class ClosedFormGeodesic<float>;
extern template class ClosedFormGeodesic<double>;

}  // namespace sol
