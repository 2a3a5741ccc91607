// The exact Sol distance and the inverse exponential map: every geodesic
// between two points up to a length.
//
// Reduction. Left translation by p⁻¹ is an isometry that keeps frame
// components, so q' = p⁻¹q is joined from the origin. Along a geodesic from
// the origin with direction (a, b, c), x' = a e^{2z} and y' = b e^{-2z}
// (first integrals, docs/mathematics.md): x and y are monotone with the signs of a
// and b. Hence a connection to q' has sign(a) = sign(x'), sign(b) = sign(y'),
// a = 0 iff x' = 0, b = 0 iff y' = 0, and the symmetries (±x, ±y, z) (which act
// on frame components as (±a, ±b, c)) reduce q' to x', y' >= 0:
//   - x' = y' = 0: only the vertical line (a = b = 0) arrives; length |z'|.
//   - y' = 0 < x': b = 0, the geodesic of the hyperbolic plane y = 0 (upper
//     half-plane (x, e^{z})): one connection, cosh d = cosh z' + ½ x'² e^{-z'};
//     x' = 0 < y' is the same after (x, y, z) -> (y, x, -z) (frame (b, a, -c)).
//   - x', y' > 0: a, b > 0. Solved by Newton's method on (direction, t) with
//     the closed-form flow (minimum-norm steps, forward-difference Jacobian,
//     backtracking), seeded for |q'| < 6 by the Euclidean guess (direction
//     q', length |q'|), otherwise by a homotopy from the plane solution of
//     (x', 0, z') (or (0, y', z')), tilted off its plane, to q' linearly in
//     (log x, log y, z), where the flow is close to linear even far away; the
//     end point is polished in frame components. A solution is accepted when
//     its end point is within the tolerance of q' in the frame, or when the
//     first-order error of its length, |a Δx| + |b Δy| + |Δz| (the gradient
//     of the distance at q' is the unit tangent there), is below 1e-12 x
//     max(1, t): far points (y' e^{z'} ~ 1e10) cannot be met to 1e-13 in the
//     frame but their lengths are exact.
//   - The straight lines (t/√2, ±t/√2, 0), t <= √2π, minimise up to their
//     period √2π, where they are conjugate: taken directly (within 1e-13).
// Certificate. A geodesic from the origin minimises exactly up to one
// z-period T (Coiculescu–Schwartz, docs/mathematics.md): any connection found with
// length t <= T is a minimiser, so its length is the distance. When the
// continuation from one plane arrives with t > T its mirror (a, b, -c) is
// polished as a seed (near the cut locus the minimiser is next to it), then
// the other plane is tried, then a scan (below) and the mirrors of its finds.
// On the cut locus (z' = 0, t = T) the mirror direction (a, b, -c) reaches
// the same point at the same length T (the shift of a whole period depends
// only on a and b), so both minimisers are returned.
//
// Stiff targets. Far targets near a plane (ends of directions with a tiny
// |a| or |b|, coordinates up to ~1e9) stall both paths above; they are
// retried with Newton in (ψ, log of the tiny component, t), the other two
// components √(1 - e^{2β})(cos ψ, sin ψ), residual in (log x, log y, z):
// the end point depends on the tiny component through log(ab), so relative
// steps of it are the well-conditioned unknown. Only targets the plain
// paths fail pay for this pass.
//
// Known limits: of directions with |b| (or |a|) in [1e-9, 1e-4] at lengths
// 18–30 (4 x 400 random ends, test Connection.StiffFarTargetsUpToThirty),
// 6 of 1600 still throw OutOfRange (no minimiser found; before the stiff
// pass 861 of 1600 did): ends near the cut locus (z' ~ 0, length near the
// period) or whose Newton stops at a length error estimate ~1e-10, just
// above the acceptance 1e-12 max(1, t). Found distances are within 3e-10
// relative of the generating length where that is <= its period.
//
// Longer connections (geodesics_between with max_length above the distance).
// x(t) is strictly increasing, so along each direction there is exactly one
// length t_x with x(t_x) = x' (when x' > 0; y is used when x' = 0). The
// connections are the zeros of the two-dimensional map
//   F(direction) = (e^{z}(y' - y), z' - z) at t_x
// over the open quarter sphere a, b > 0. geodesics_between scans F on a grid
// of ConnectionOptions::scan_polar x scan_azimuth directions (uniform in the
// polar angle and in the azimuth), takes every local minimum of |F| as a seed
// and polishes it by Newton; solutions are merged when their directions agree
// to 1e-7. "Every" therefore means: every connection whose basin under that
// Newton iteration contains a grid direction of a local minimum of |F|. The
// tests check it against a brute-force scan at four times the resolution.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "sol/kernel_constants.h"
#include "sol/log_series.h"

namespace sol {

/// A geodesic from p: unit direction in frame components at p, and its length.
struct Connection {
  glm::dvec3 direction{0.0, 0.0, 1.0};
  double length = 0.0;
};

/// Settings of the connection solver.
struct ConnectionOptions {
  /// Newton stops when the end point is within this distance of q (frame
  /// components at the end point), or at the rounding floor of the problem,
  /// 1e-14 x max(1, |x'| e^{-z'}, |y'| e^{z'}, |z'|) for q' = p⁻¹q.
  double tolerance = 1e-13;
  int scan_polar = 48;    ///< grid of directions for the longer connections (>= 4)
  int scan_azimuth = 24;  ///< (>= 2)
};

/// The Sol distance between p and q (accuracy ~1e-12 relative to the
/// rounding floor above). Throws InvalidArgument on NaN or infinite input.
double distance(const glm::dvec3& p, const glm::dvec3& q);
double distance(const glm::dvec3& p, const glm::dvec3& q, const ConnectionOptions& options);

/// Every geodesic from p to q no longer than max_length (see the header
/// comment for what "every" means), shortest first: flow({p, direction},
/// length).position == q. The first has length distance(p, q) (on the cut
/// locus the first two, both minimisers). Empty when max_length <
/// distance(p, q). Throws InvalidArgument on NaN or infinite input or a
/// negative max_length.
std::vector<Connection> geodesics_between(const glm::dvec3& p, const glm::dvec3& q, double max_length);
std::vector<Connection> geodesics_between(const glm::dvec3& p, const glm::dvec3& q, double max_length,
                                          const ConnectionOptions& options);

/// The minimising geodesics only (one, or two on the cut locus), without the
/// scan for longer ones: what distance() computes.
std::vector<Connection> minimising_geodesics(const glm::dvec3& p, const glm::dvec3& q,
                                             const ConnectionOptions& options = {});

/// Sol's logarithm at the origin by its Taylor series (sol/log_series.h,
/// order kernel::kLogSeriesOrder): the initial vector v (coordinates at
/// the origin, |v| the length) of the geodesic from the origin that ends
/// at w, for |w| < kernel::kLogSeriesReach, where it is within 5e-5 of the
/// shortest (test Connection.LogSeriesInvertsTheExponentialMap). By left
/// invariance log_series(p⁻¹q) starts a solve for the geodesic from p to
/// q. What the kernels' exact balls start Newton from (docs/exact.md).
/// Throws InvalidArgument for a w that is not finite or not within the
/// reach (beyond it the series diverges).
glm::dvec3 log_series(const glm::dvec3& w);

/// Where exact balls switch from the bound to the exact distance: sphere
/// tracing steps by distance_lower_bound(q, centre) - radius while that
/// exceeds this band, by distance(q, centre) - radius within it.
inline constexpr double kExactBallBand = 0.25;

/// Signed distance to the geodesic ball (center, radius), exact within
/// `band` of its bound: a sphere-tracing distance whose zero set is the true
/// geodesic sphere (never above the true signed distance, so no tunnelling).
/// Falls back to the bound if the solver throws (far extreme points).
double sdf_ball_exact(const glm::dvec3& q, const glm::dvec3& center, double radius, double band = kExactBallBand);

/// The exact unit normal of the geodesic sphere about `center` through q
/// (frame components at q): the gradient of distance(center, ·), the tangent
/// at q of the minimising geodesic from the centre (the first one on the cut
/// locus).
glm::dvec3 sdf_ball_exact_gradient(const glm::dvec3& q, const glm::dvec3& center);

/// Seeds for the kernels' connection solver (compute/shaders/
/// sol_connection.glsl, exact point lights), which has no scan and no
/// homotopy: it polishes the seeds of the grid cell holding the target by
/// Newton's method on the float closed-form flow. The grid covers w = p⁻¹q
/// with x, y >= 0 (the symmetries (±x, ±y, z) act on directions as (±a, ±b,
/// c)) at the nodes (sinh u_i, sinh v_j, z_k), u, v in [0, kExtent] and z in
/// [-kHeight, kHeight], all with step kStep. The connections from the origin
/// to each node are computed by the double solver: the minimisers
/// (minimising_geodesics), and with `longer` also the others up to distance
/// + kReach + kMargin (geodesics_between). A cell's seeds are the union of
/// its eight corners' connections (so that a connection that continues
/// across the cell from any corner is seeded, and both branches at the cut
/// locus z = 0 are), merged when their initial vectors t·(a, b, c) agree to
/// kMerge max(1, t), shortest first, at most kSlots, as (a, b, c, t) (unit
/// direction, length; t = 0: empty). Accuracy of the kernel's solver: docs/exact.md
/// "Exact spheres and point lights" (tests vk.Kernel.Connections*).
struct ConnectionTable {
  // The grid's geometry, shared with the kernel (sol/kernel_constants.h).
  static constexpr int kSlots = kernel::kSeedSlots;
  static constexpr double kStep = kernel::kSeedStep;
  static constexpr double kExtent = kernel::kSeedExtent;  ///< u = asinh x, v = asinh y in [0, kExtent]: x, y up to 74
  static constexpr double kHeight = kernel::kSeedHeight;  ///< z in [-kHeight, kHeight]
  static constexpr int kCellsXY = kernel::kSeedCellsXY;   ///< kExtent / kStep cells along u and v
  static constexpr int kCellsZ = kernel::kSeedCellsZ;     ///< 2 kHeight / kStep cells along z
  static_assert(kCellsXY * kStep == kExtent && kCellsZ * kStep == 2.0 * kHeight, "cells cover the grid");
  static constexpr double kReach = 3.0;   ///< longest reach a table with `longer` serves
  static constexpr double kMargin = 0.5;  ///< connections kept beyond distance + kReach (the distance varies over a cell)
  static constexpr double kMerge = 0.1;   ///< corners' seeds closer than kMerge max(1, t) in t·(a, b, c) are merged
  /// (a, b, c, t) per slot, index ((k kCellsXY + j) kCellsXY + i) kSlots + s for the cell [u_i, u_i+1] x [v_j, v_j+1] x [z_k, z_k+1].
  std::vector<float> seeds;
  int failed_nodes = 0;     ///< nodes where the solver found no connection (left out; expected 0)
  int overflow_cells = 0;   ///< cells whose union held more than kSlots seeds (the longest dropped)

  /// Builds the table with `threads` threads (0: all cores): about 1 s of
  /// CPU for the minimisers, 7 s with `longer`.
  static ConnectionTable build(bool longer, unsigned threads = 0);
  /// Built once per process for each value of `longer`, and shared.
  static const ConnectionTable& shared(bool longer);
};

}  // namespace sol
