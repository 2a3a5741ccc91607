// Clearances: how far the geodesic from a point p with unit tangent u
// (frame components) can go before it reaches an object, to second order.
//
// Sphere tracing steps by a distance bound f(p), which is 1-Lipschitz, so a
// step of f(p) never passes the surface {f = 0}. Where the geodesic runs
// beside the surface rather than towards it (a ray grazing a ball, or
// passing a tube), f hardly shrinks along it and the steps crawl. The
// bounds of balls, tubes and planes z = c are maxima of terms h whose
// second derivative along any Sol geodesic is bounded below, h'' >= -M, as
// long as h > 0; then along the geodesic
//   h(p + s) >= h(p) + h'(p) s - ½ M s²,
// and the object (where every term is <= 0) is not reached before the first
// root of that parabola for any one term with h(p) > 0:
//   s_h = (h' + √(h'² + 2 M h)) / M   (= 2h / (√(h'² + 2 M h) - h') for h' < 0).
// The clearance is the largest such root, and at least f(p) itself. A
// grazing ray (h' ≈ 0) steps √(2h/M) instead of h; one moving away steps
// more than 2h'/M.
//
// The terms and their M (proofs in docs/renderer.md, "Clearances"):
//  - |z - c| (planes z = c, horizontal tubes): z'' = u2² − u1² >= −1, M = 1.
//  - a distance in the hyperbolic plane (x, z), metric e^{-2z}dx² + dz², onto
//    which Sol projects without stretching: to a point (the ball's
//    d_xz - r) or to the geodesic x = c (asinh(|x − c| e^{-z}), planes x = c,
//    vertical tubes). Distances to points and to geodesics of H² are convex
//    away from them, and the projection of a Sol geodesic, with frame
//    velocity (u1, u3), has covariant acceleration (0, u2²) there; so
//    h'' >= −u2² >= −1, M = 1. Likewise (y, z) with u1²: d_yz − r,
//    asinh(|y − c| e^{z}).
//  - the across term of a tube along a horizontal h with h_x h_y ≠ 0,
//    asinh(|G|), G = (h_y Δx − h_x Δy)/(|h_x| e^{-z} + |h_y| e^{z}): along
//    a geodesic (asinh G)'' (1 + G²)^{3/2} is a quadratic form in the frame
//    velocity whose coefficients depend on G and the balance
//    c = (|h_y| e^{z} − |h_x| e^{-z}) / (|h_x| e^{-z} + |h_y| e^{z}) alone; the
//    form plus (1 + G²)^{3/2} times the identity is positive semidefinite
//    for every G and c (scripts/prove_across_bend.py: its principal minors
//    are polynomials, certified nonnegative by exact Bernstein
//    coefficients), so M = 1, and no less: along a vertical geodesic where
//    c = 0, (asinh G)'' = −G/√(1 + G²) (docs/renderer.md).
// The kinds give their terms (clearance_terms in sol/objects.hpp). The
// kernel mirrors these (object_clearances in compute/shaders/march/objects.glsl).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/distance.hpp"
#include "sol/kernel_constants.h"

namespace sol {

/// One term h of a bound (the bound being the maximum of its terms) at a
/// point, along the geodesic through it: its value, its rate h' and the bend
/// M, with h'' >= −M wherever h > 0.
struct BoundTerm {
  double value = 0.0;
  double slope = 0.0;
  double bend = 1.0;
};

/// How far the term stays positive: the first root s > 0 of
/// h + h' s − ½ M s² (0 where h <= 0), in the form without cancellation.
inline double clearance_root(const BoundTerm& h) {
  if (!(h.value > 0.0)) return 0.0;
  const double root = std::sqrt(h.slope * h.slope + 2.0 * h.bend * h.value);
  return h.slope >= 0.0 ? (h.slope + root) / h.bend : 2.0 * h.value / (root - h.slope);
}

/// The clearance of a bound that is the maximum of `terms`: the bound
/// itself (the largest value) or the longest root, whichever is larger.
template <std::size_t N>
double clearance(const std::array<BoundTerm, N>& terms) {
  double best = terms[0].value;
  for (const BoundTerm& h : terms) best = std::max({best, h.value, clearance_root(h)});
  return best;
}

/// A bound's clearances both ways along the geodesic through p: ahead
/// along u and back along −u.
struct Clearances {
  double ahead = 0.0;
  double back = 0.0;
};

/// clearance() of `terms` (taken along u) and of the same terms along −u,
/// whose values are the same and whose rates, linear in the tangent, change
/// sign (the bends do not depend on it): one evaluation of the terms for
/// both (the quotient march's check of an over-relaxed step needs the
/// clearance back from its end).
template <std::size_t N>
Clearances clearances(std::array<BoundTerm, N> terms) {
  Clearances both;
  both.ahead = clearance(terms);
  for (BoundTerm& h : terms) h.slope = -h.slope;
  both.back = clearance(terms);
  return both;
}

/// |z − c|: its rate is ±u3, z'' = u2² − u1² >= −1.
inline BoundTerm plane_z_term(const glm::dvec3& p, const glm::dvec3& u, double c) {
  return {std::abs(p.z - c), p.z >= c ? u.z : -u.z, 1.0};
}

/// asinh(|x − c| e^{-z}) − r, the slab of half-width r around the plane
/// x = c: its rate is the plane's gradient (sol/distance.hpp) along u.
inline BoundTerm slab_x_term(const glm::dvec3& p, const glm::dvec3& u, double c, double r) {
  const double w = std::abs(p.x - c) * std::exp(-p.z);
  return {std::asinh(w) - r, ((p.x >= c ? 1.0 : -1.0) * u.x - w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

/// asinh(|y − c| e^{z}) − r.
inline BoundTerm slab_y_term(const glm::dvec3& p, const glm::dvec3& u, double c, double r) {
  const double w = std::abs(p.y - c) * std::exp(p.z);
  return {std::asinh(w) - r, ((p.y >= c ? 1.0 : -1.0) * u.y + w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

/// The ball (center, radius) of sol::sdf_ball: the points where both
/// projected distances d_xz, d_yz are at most r. With S = sinh(d/2),
///   S_x² = sinh²(Δz/2) + ¼ Δx² e^{-(z + z_c)},   S_y² = sinh²(Δz/2) + ¼ Δy² e^{z + z_c},
/// d = 2 asinh S, d' = (S²)' / (S √(1 + S²)), and along u (x' = e^{z} u1,
/// y' = e^{-z} u2, z' = u3)
///   (S_x²)' = ½ sinh(Δz) u3 + ½ Δx u1 e^{-z_c} − ¼ Δx² e^{-(z + z_c)} u3,
///   (S_y²)' = ½ sinh(Δz) u3 + ½ Δy u2 e^{z_c} + ¼ Δy² e^{z + z_c} u3.
/// The terms d_xz − r and d_yz − r; their maximum is sdf_ball.
inline std::array<BoundTerm, 2> ball_terms(const glm::dvec3& p, const glm::dvec3& u, const glm::dvec3& center,
                                           double radius) {
  const double dz = p.z - center.z, dx = p.x - center.x, dy = p.y - center.y;
  const double e = std::exp(p.z + center.z), ec = std::exp(center.z);
  const double sh = std::sinh(0.5 * dz), half_sinh_dz = sh * std::sqrt(1.0 + sh * sh);  // ½ sinh Δz
  const double s2[2] = {sh * sh + 0.25 * dx * dx / e, sh * sh + 0.25 * dy * dy * e};
  const double rate[2] = {half_sinh_dz * u.z + 0.5 * dx * u.x / ec - 0.25 * dx * dx / e * u.z,
                          half_sinh_dz * u.z + 0.5 * dy * u.y * ec + 0.25 * dy * dy * e * u.z};
  std::array<BoundTerm, 2> terms;
  for (int i = 0; i < 2; ++i) {
    const double s = std::sqrt(s2[i]);
    terms[i] = {2.0 * std::asinh(s) - radius, s > 0.0 ? rate[i] / (s * std::sqrt(1.0 + s2[i])) : 0.0, 1.0};
  }
  return terms;
}

/// The tube of sol::sdf_tube (vertical) or sol::sdf_tube_horizontal (unit
/// coordinate direction h): vertical, the slabs around x = x0 and y = y0;
/// horizontal, the across term asinh|G| − r, G = L/D with
/// L = h_y Δx − h_x Δy, D = |h_x| e^{-z} + |h_y| e^{z} (a slab's term along
/// x or y), and the z slab |Δz| − r; every term bends by at most 1.
inline std::array<BoundTerm, 2> tube_terms(const glm::dvec3& p, const glm::dvec3& u, const glm::dvec3& through,
                                           bool vertical, const glm::dvec2& h, double radius) {
  if (vertical) return {slab_x_term(p, u, through.x, radius), slab_y_term(p, u, through.y, radius)};
  BoundTerm z = plane_z_term(p, u, through.z);
  z.value -= radius;
  if (h.x == 0.0) return {slab_x_term(p, u, through.x, radius), z};
  if (h.y == 0.0) return {slab_y_term(p, u, through.y, radius), z};
  const double ez = std::exp(p.z);
  const double L = h.y * (p.x - through.x) - h.x * (p.y - through.y);
  const double D = std::abs(h.x) / ez + std::abs(h.y) * ez;
  const double rate_L = h.y * ez * u.x - h.x / ez * u.y, rate_D = (std::abs(h.y) * ez - std::abs(h.x) / ez) * u.z;
  const double G = L / D, rate_G = rate_L / D - G * rate_D / D;
  const BoundTerm across{std::asinh(std::abs(G)) - radius, (G >= 0.0 ? rate_G : -rate_G) / std::sqrt(1.0 + G * G),
                         1.0};
  return {across, z};
}

}  // namespace sol
