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
#include <limits>

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

/// How far the geodesic from p along u stays more than `eps` from the plane
/// z = c: the first root of the term |z − c| less eps (0 within eps). The
/// march's step where the plane is the nearest object: a clearance to the
/// plane itself would land a ray anywhere in the band within eps of it,
/// eps / |u_z| long at a grazing angle, where the hit is taken; this lands
/// it at the band's edge, whence the plane's distance steps into it, so a
/// hit's arc length is where the ray first comes within eps, as by |z − c|
/// steps.
inline double plane_z_step(const glm::dvec3& p, const glm::dvec3& u, double c, double eps) {
  BoundTerm h = plane_z_term(p, u, c);
  h.value -= eps;
  return clearance_root(h);
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

// ---- Seen from inside a solid
//
// Inside a solid (its bound d < 0) the wall is at least −d away: every
// face term h of the bound is negative there, and the ray leaves the solid
// where the first of them reaches 0. Written as distances to the faces
// from inside, g = −h > 0, each with an upper bend of h (h'' <= M while the
// ray is inside), so that g'' >= −M and g stays positive up to the first
// root of g + g' s − ½ M s²: the inside clearance is the least over the
// faces of the larger of g and that root (sol::inside_clearance). A ray
// that leaves a wall inward, or runs along it, then steps by about the
// chord to the next wall instead of crawling by sphere tracing. The terms
// are smooth across the solid, each a face's own (a slab's two faces are
// two terms: |Δ| has a kink where the upper bend fails):
//  - the signed distance σ to a plane x = c, y = c (asinh((x − c) e^{-z}),
//    asinh((y − c) e^{z})) or z = c: |σ''| <= 1 (the Hessian of a signed
//    distance to a geodesic of H² is tanh σ across it, and the projection's
//    acceleration adds at most u2², resp. u1²), M = 1; boxes (six faces)
//    and vertical tubes (the slabs |σ| <= r about x = x0, y = y0: faces
//    r ∓ σ);
//  - the distance d in a hyperbolic plane (x, z) or (y, z) to a ball's
//    centre: d'' <= coth(d)(1 − u2²) + u2² <= coth d; over a step of at most
//    d/2 (the projection is 1-Lipschitz) d stays above d/2, M = coth(d/2),
//    the step capped there (BoundTerm::reach);
//  - a horizontal tube's across term asinh G: its upper bend is not
//    established but along x or y (a plane's distance), so those faces step
//    by g alone (bend infinite), its z faces by M = 1.
// The kernel mirrors these (the kinds' *_inside_clearances in
// compute/shaders/kinds/). Test: Clearance.InsideClearancesNeverLeaveTheSolid.

/// A face of a solid seen from inside: its distance g > 0, rate g', bend
/// (g'' >= −bend) and the step up to which the bend holds.
struct InsideTerm {
  double value = 0.0;
  double slope = 0.0;
  double bend = 1.0;
  double reach = std::numeric_limits<double>::infinity();
};

/// The faces' least clearance: over the terms, the larger of g and the
/// first root of g + g' s − ½ bend s² (at most the term's reach).
template <std::size_t N>
double inside_clearance(const std::array<InsideTerm, N>& terms) {
  double least = std::numeric_limits<double>::infinity();
  for (const InsideTerm& g : terms) {
    const double root = std::isfinite(g.bend) ? clearance_root({g.value, g.slope, g.bend}) : 0.0;
    least = std::min(least, std::max(g.value, std::min(root, g.reach)));
  }
  return least;
}

/// A solid's clearances seen from inside, and the rate of its nearest
/// face (the least g): negative where the ray heads towards that face. A
/// ray that leaves the solid's surface inward passes it while it is near
/// (as any surface it starts on) but only while that face recedes: once
/// the nearest face is one it approaches (another face near an edge, or
/// the same one where it curves back), the pass ends and that face is a
/// hit.
struct InsideClearances {
  double ahead = 0.0;
  double back = 0.0;
  double nearest_rate = 0.0;
};

/// inside_clearance ahead along u and back along −u (whose rates are the
/// negated ones), and the nearest face's rate along u.
template <std::size_t N>
InsideClearances inside_clearances(std::array<InsideTerm, N> terms) {
  InsideClearances both;
  both.ahead = inside_clearance(terms);
  double least = std::numeric_limits<double>::infinity();
  for (InsideTerm& g : terms) {
    if (g.value < least) {
      least = g.value;
      both.nearest_rate = g.slope;
    }
    g.slope = -g.slope;
  }
  both.back = inside_clearance(terms);
  return both;
}

/// The signed distance to the plane x = c, asinh((x − c) e^{-z}), times
/// `side` (+1: the solid lies on the side x > c of its face there), as a
/// face term: g = side σ, g' = side σ', bend 1.
inline InsideTerm face_x(const glm::dvec3& p, const glm::dvec3& u, double c, double side) {
  const double w = (p.x - c) * std::exp(-p.z);
  return {side * std::asinh(w), side * (u.x - w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

/// The same for the plane y = c: asinh((y − c) e^{z}).
inline InsideTerm face_y(const glm::dvec3& p, const glm::dvec3& u, double c, double side) {
  const double w = (p.y - c) * std::exp(p.z);
  return {side * std::asinh(w), side * (u.y + w * u.z) / std::sqrt(1.0 + w * w), 1.0};
}

/// The same for the plane z = c: z − c.
inline InsideTerm face_z(const glm::dvec3& p, const glm::dvec3& u, double c, double side) {
  return {side * (p.z - c), side * u.z, 1.0};
}

/// The two faces of a slab |σ| <= r about a signed distance σ (a face
/// term with side +1): r − σ and r + σ.
inline std::array<InsideTerm, 2> slab_faces(const InsideTerm& sigma, double r) {
  return {InsideTerm{r - sigma.value, -sigma.slope, sigma.bend, sigma.reach},
          InsideTerm{r + sigma.value, sigma.slope, sigma.bend, sigma.reach}};
}

/// The ball of sol::sdf_ball seen from inside: r − d_xz and r − d_yz
/// (ball_terms' distances), bend coth(d/2), each for steps of at most d/2.
inline std::array<InsideTerm, 2> ball_inside_terms(const glm::dvec3& p, const glm::dvec3& u, const glm::dvec3& center,
                                                   double radius) {
  const std::array<BoundTerm, 2> outside = ball_terms(p, u, center, radius);
  std::array<InsideTerm, 2> inside;
  for (std::size_t i = 0; i < 2; ++i) {
    const double d = outside[i].value + radius, half = 0.5 * d;
    inside[i] = {-outside[i].value, -outside[i].slope, half > 0.0 ? std::cosh(half) / std::sinh(half)
                                                                  : std::numeric_limits<double>::infinity(),
                 half};
  }
  return inside;
}

/// The tube of tube_terms seen from inside: vertical, the faces of its
/// slabs about x = x0 and y = y0 (bend 1); horizontal along h, the faces
/// r ∓ asinh G (no established upper bend: g alone) and r ∓ Δz (bend 1).
inline std::array<InsideTerm, 4> tube_inside_terms(const glm::dvec3& p, const glm::dvec3& u, const glm::dvec3& through,
                                                   bool vertical, const glm::dvec2& h, double radius) {
  if (vertical) {
    const std::array<InsideTerm, 2> x = slab_faces(face_x(p, u, through.x, 1.0), radius);
    const std::array<InsideTerm, 2> y = slab_faces(face_y(p, u, through.y, 1.0), radius);
    return {x[0], x[1], y[0], y[1]};
  }
  const double ez = std::exp(p.z);
  const double L = h.y * (p.x - through.x) - h.x * (p.y - through.y);
  const double D = std::abs(h.x) / ez + std::abs(h.y) * ez;
  const double rate_L = h.y * ez * u.x - h.x / ez * u.y, rate_D = (std::abs(h.y) * ez - std::abs(h.x) / ez) * u.z;
  const double G = L / D, rate_G = rate_L / D - G * rate_D / D;
  // (Along x or y the across term is a plane's signed distance: bend 1.)
  const double bend = h.x == 0.0 || h.y == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
  InsideTerm across{std::asinh(G), rate_G / std::sqrt(1.0 + G * G), bend};
  const std::array<InsideTerm, 2> a = slab_faces(across, radius);
  const std::array<InsideTerm, 2> z = slab_faces(face_z(p, u, through.z, 1.0), radius);
  return {a[0], a[1], z[0], z[1]};
}

/// The clearance of an exact ball seen from inside (the kernel's
/// exact_ball_inside_clearance in compute/shaders/march/exact_balls.glsl,
/// the same formula in float): g = r − d > 0 the exact distance to its
/// sphere, d the distance from its centre, `slope` = d' along the ray.
/// Sol's sectional curvatures are at least −1, so by the Hessian comparison
/// theorem Hess d <= coth(d) (g − ∇d ∇d) before any cut point: d'' <=
/// coth(d) along the ray, and over a step of at most d/2 (d stays above
/// d/2: it is 1-Lipschitz) g'' >= −coth(d/2). The step is the first root of
/// g − eps/2 − slope s − ½ coth(d/2) s² (aimed at g = eps/2, so that the
/// rounding of the rate does not carry it through the sphere), at most
/// d/2 and kExactClearanceCap, and at least g: a ray that leaves the wall
/// inward at angle θ to the normal steps about the chord (2r cos θ against
/// the crawl of sphere tracing from g = 0).
inline double exact_ball_inside_clearance(double g, double d, double slope, double eps) {
  const double half_d = 0.5 * d;
  const BoundTerm term{g - 0.5 * eps, -slope, std::cosh(half_d) / std::max(std::sinh(half_d), 1e-300)};
  return std::max(g, std::min({clearance_root(term), half_d, kernel::kExactClearanceCap}));
}

}  // namespace sol
