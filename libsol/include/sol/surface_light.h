// Glowing boxes, bound balls and tubes as lights, written once for the
// CPU renderer (double) and the kernels (float): next-event estimation
// draws a point of the surface with a density per unit area known in
// closed form (docs/lighting.md, "Glowing boxes and bound balls", "Glowing
// tubes").
//
// Boxes: uniformly by area. In the box's own frame w = centre⁻¹·q
// the box is [−a, a] × [−b, b] × [−c, c], (a, b, c) its half size, and the
// metric e^{−2z}dx² + e^{2z}dy² + dz² gives its faces the area elements
//   z = ±c: dx dy             (area 4ab each)
//   x = ±a: e^{z} dy dz       (area 4b sinh c each)
//   y = ±b: e^{−z} dx dz      (area 4a sinh c each),
// and each face's unit normal is a frame vector, ±E1, ±E2 or ±E3, which a
// left translation keeps: the same at the box's world point. Valid C++
// (namespace sol::kernel, double) and GLSL (float), as sol/patterns.h.
#ifndef SOL_SURFACE_LIGHT_H
#define SOL_SURFACE_LIGHT_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
namespace sol::kernel {
#define SOL_SHARED_FUNCTION inline
#define SOL_LIGHT_VEC3 glm::dvec3
using std::abs;
using std::asinh;
using std::atan;
using std::cos;
using std::cosh;
using std::exp;
using std::log;
using std::sin;
using std::sinh;
using std::sqrt;
using std::tan;
using std::max;
using std::min;
#else
#define SOL_SHARED_FUNCTION
#define SOL_LIGHT_VEC3 vec3
#endif

/// The area of the box's surface: 8ab + 8(a + b) sinh c.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_area(SOL_LIGHT_VEC3 half_size) {
  return 8.0 * half_size.x * half_size.y + 8.0 * (half_size.x + half_size.y) * sinh(half_size.z);
}

/// The size next-event estimation picks a box by, as a ball's radius
/// (about its solid angle): its half size's Euclidean length.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_radius(SOL_LIGHT_VEC3 half_size) {
  return sqrt(half_size.x * half_size.x + half_size.y * half_size.y + half_size.z * half_size.z);
}

/// The point of the box's surface (in its own frame) that three uniform
/// numbers in [0, 1) draw with density 1 / sol_box_light_area per unit
/// area: u0 picks a face by its area (z = +c, −c, x = +a, −a, y = +b, −b),
/// u1 and u2 place the point on it, where z follows e^{±z} on the side faces.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_box_light_point(SOL_LIGHT_VEC3 half_size, SOL_REAL u0, SOL_REAL u1, SOL_REAL u2) {
  const SOL_REAL a = half_size.x, b = half_size.y, c = half_size.z;
  const SOL_REAL top = 4.0 * a * b, side_x = 4.0 * b * sinh(c), side_y = 4.0 * a * sinh(c);
  SOL_REAL left = u0 * (2.0 * (top + side_x + side_y));
  const SOL_REAL s = 2.0 * u1 - 1.0;
  // z with density e^{z} on [−c, c]: the inverse of its distribution.
  const SOL_REAL rising = log(exp(-c) + u2 * (exp(c) - exp(-c)));
  if (left < 2.0 * top) return SOL_LIGHT_VEC3(a * s, b * (2.0 * u2 - 1.0), left < top ? c : -c);
  left -= 2.0 * top;
  if (left < 2.0 * side_x) return SOL_LIGHT_VEC3(left < side_x ? a : -a, b * s, rising);
  left -= 2.0 * side_x;
  return SOL_LIGHT_VEC3(a * s, left < side_y ? b : -b, -rising);
}

/// The box's bound at w (its own frame): the largest of the signed exact
/// distances to its three slabs (as sol::Box::distance), 0 on its surface.
SOL_SHARED_FUNCTION SOL_REAL sol_box_light_bound(SOL_LIGHT_VEC3 w, SOL_LIGHT_VEC3 half_size) {
  const SOL_REAL tx = asinh((abs(w.x) - half_size.x) * exp(-w.z));
  const SOL_REAL ty = asinh((abs(w.y) - half_size.y) * exp(w.z));
  const SOL_REAL tz = abs(w.z) - half_size.z;
  return tx > ty ? (tx > tz ? tx : tz) : (ty > tz ? ty : tz);
}

/// The outward unit normal (frame components) of the face nearest w, a
/// point on or near the box's surface in its own frame: the face of the
/// slab whose exact distance term is largest (as sol_box_pattern_uv).
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_box_light_normal(SOL_LIGHT_VEC3 w, SOL_LIGHT_VEC3 half_size) {
  const SOL_REAL tx = asinh((abs(w.x) - half_size.x) * exp(-w.z));
  const SOL_REAL ty = asinh((abs(w.y) - half_size.y) * exp(w.z));
  const SOL_REAL tz = abs(w.z) - half_size.z;
  if (tx >= ty && tx >= tz) return SOL_LIGHT_VEC3(w.x >= 0.0 ? 1.0 : -1.0, 0.0, 0.0);
  if (ty >= tz) return SOL_LIGHT_VEC3(0.0, w.y >= 0.0 ? 1.0 : -1.0, 0.0);
  return SOL_LIGHT_VEC3(0.0, 0.0, w.z >= 0.0 ? 1.0 : -1.0);
}

/// Whether a path's vertex at wx (the box's own frame) lies on the face
/// that holds the light point wy: within 1e-3 of the surface, on the same
/// face. Next-event estimation leaves such a point to reflection sampling:
/// on a face x or y = const (totally geodesic) their geodesic runs in the
/// face, and on a face z = const it grazes it, a march that may not end.
SOL_SHARED_FUNCTION bool sol_box_light_same_face(SOL_LIGHT_VEC3 wx, SOL_LIGHT_VEC3 wy, SOL_LIGHT_VEC3 half_size) {
  return abs(sol_box_light_bound(wx, half_size)) < 1e-3 &&
         sol_box_light_normal(wx, half_size) == sol_box_light_normal(wy, half_size);
}

// Balls drawn by their bound (sol::sdf_ball): in the ball's own frame w =
// centre⁻¹·q the surface is max(d_xz, d_yz) = r, d_xz the distance of the
// projections to the hyperbolic plane (x, z) (metric e^{−2z}dx² + dz²,
// cosh d_xz = cosh z + x² e^{−z}/2) and d_yz that to (y, z) (e^{2z}dy² +
// dz², cosh d_yz = cosh z + y² e^{z}/2). It has two pieces: A, where
// d_xz = r and d_yz <= r, a cylinder along y over the hyperbolic circle of
// radius r, and B, where d_yz = r and d_xz <= r, one along x. In the upper
// half-plane model (x, e^{z}) of the first plane the circle is Euclidean,
// centre (0, cosh r), radius sinh r: x = sinh r cos φ, e^{z} = cosh r +
// sinh r sin φ, with hyperbolic arc length sinh r dφ / e^{z}; the y-lines
// have |∂y| = e^{z}, orthogonal to it, so A's area element is
// sinh r dφ dy, and |y| <= Y(z) = √(2 (cosh r − cosh z) e^{−z}) on it.
// Likewise B: y = sinh r cos φ, e^{−z} = cosh r + sinh r sin φ, area
// element sinh r dφ dx, |x| <= X(z) = √(2 (cosh r − cosh z) e^{z}).

/// The piece of the bound ball's surface nearest w (its own frame): A
/// (true) where the (x, z) term is the larger, else B.
SOL_SHARED_FUNCTION bool sol_ball_light_piece_a(SOL_LIGHT_VEC3 w) {
  return w.x * w.x * exp(-w.z) >= w.y * w.y * exp(w.z);
}

/// The point of the bound ball's surface (its own frame) that three
/// uniform numbers in [0, 1) draw: u0 picks a piece (A below 1/2), u1 its
/// angle φ = 2π u1, u2 the coordinate along it, uniform on [−Y(z), Y(z)]
/// (A) or [−X(z), X(z)] (B): density sol_ball_light_density per unit area.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_ball_light_point(SOL_REAL radius, SOL_REAL u0, SOL_REAL u1, SOL_REAL u2) {
  const SOL_REAL phi = 6.28318530717958647692 * u1;
  const SOL_REAL lift = log(cosh(radius) + sinh(radius) * sin(phi)), across = sinh(radius) * cos(phi);
  const SOL_REAL room = 2.0 * max(SOL_REAL(0.0), cosh(radius) - cosh(lift));
  const SOL_REAL along = 2.0 * u2 - 1.0;
  if (u0 < 0.5) return SOL_LIGHT_VEC3(across, along * sqrt(room * exp(-lift)), lift);
  return SOL_LIGHT_VEC3(along * sqrt(room * exp(-lift)), across, -lift);
}

/// sol_ball_light_point's density per unit area at w on the surface: a
/// half (the piece) over 2π (the angle), over the coordinate's range 2Y
/// (or 2X), over the area element's sinh r.
SOL_SHARED_FUNCTION SOL_REAL sol_ball_light_density(SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_REAL room = 2.0 * max(SOL_REAL(0.0), cosh(radius) - cosh(w.z));
  const SOL_REAL half_range = sqrt(room * exp(sol_ball_light_piece_a(w) ? -w.z : w.z));
  return 1.0 / (8.0 * 3.14159265358979323846 * sinh(radius) * max(half_range, SOL_REAL(1e-30)));
}

/// The bound's outward unit normal at w (its own frame) on the piece that
/// holds it: the gradient of d_xz, (x, 0, sinh z − x² e^{−z}/2) / sinh d_xz
/// in frame components (A), or of d_yz, (0, y, sinh z + y² e^{z}/2) / sinh d_yz (B).
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_ball_light_normal(SOL_LIGHT_VEC3 w) {
  if (sol_ball_light_piece_a(w)) return normalize(SOL_LIGHT_VEC3(w.x, 0.0, sinh(w.z) - 0.5 * w.x * w.x * exp(-w.z)));
  return normalize(SOL_LIGHT_VEC3(0.0, w.y, sinh(w.z) + 0.5 * w.y * w.y * exp(w.z)));
}

/// The bound at w less the radius (sol::sdf_ball about the origin): 0 on the surface.
SOL_SHARED_FUNCTION SOL_REAL sol_ball_light_bound(SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_REAL a = max(0.5 * w.x * w.x * exp(-w.z), 0.5 * w.y * w.y * exp(w.z));
  const SOL_REAL sh = sinh(0.5 * w.z);
  return 2.0 * asinh(sqrt(sh * sh + 0.5 * a)) - radius;
}

// Tubes about a coordinate axis are infinite: next-event estimation draws
// a point of a window of them about the diffuse point x's foot f on the
// axis (sol_tube_light_foot), in the frame w = f⁻¹·q, with a density per
// unit area in closed form that depends on x's distance bound h to the
// tube (which sets the window's half size W, sol_light_window, and how
// the points gather about the foot), 0 outside the window: reflection
// sampling's alone there.
// The tubes are those of sol::sdf_tube: axis 2 (vertical), |x| e^{−z} <= S
// and |y| e^{z} <= S (S = sinh r): four faces x = ±S e^{z}, y = ±S e^{−z},
// area elements e^{z} cosh r dy dz and e^{−z} cosh r dx dz, each of area
// 2S cosh r = sinh 2r per unit of z; axis 0 (along x), |y| e^{z} <= S and
// |z| <= r: faces z = ±r (dx dy: 2S e^{∓r} per unit of x) and y = ±S e^{−z}
// (e^{−z} cosh r dx dz: sinh 2r per unit of x); 4 sinh 2r a unit of length
// either way. Axis 1 (along y) is axis 0's image under the isometry and
// automorphism (x, y, z) -> (y, x, −z) (sol_axis_swap), which maps the
// frame E1, E2, E3 to E2, E1, −E3. Along the axis the coordinate t
// follows a Cauchy density a / (a² + t²) on [−W, W], a = h + r (the light
// of a line at distance a falls off about so), uniformly across it.

/// The window's half size for a diffuse point at distance bound h from a tube.
SOL_SHARED_FUNCTION SOL_REAL sol_light_window(SOL_REAL h) {
  return min(kLightWindowBase + kLightWindowSlope * max(h, SOL_REAL(0.0)), kLightWindowMost);
}

SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_axis_swap(SOL_LIGHT_VEC3 w) { return SOL_LIGHT_VEC3(w.y, w.x, -w.z); }

/// A tube's coordinate axis from its direction: 2 vertical, 0 along x
/// (dy = 0), 1 along y (dx = 0); -1 along another horizontal direction (a
/// lattice's), which is no target.
SOL_SHARED_FUNCTION int sol_tube_light_axis(bool vertical, SOL_REAL dx, SOL_REAL dy) {
  return vertical ? 2 : (dy == 0.0 ? 0 : (dx == 0.0 ? 1 : -1));
}

/// The point of the tube's axis (through `through` along coordinate axis
/// `axis`) with x's coordinate along it: the window's centre.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_tube_light_foot(int axis, SOL_LIGHT_VEC3 through, SOL_LIGHT_VEC3 x) {
  if (axis == 2) return SOL_LIGHT_VEC3(through.x, through.y, x.z);
  return axis == 0 ? SOL_LIGHT_VEC3(x.x, through.y, through.z) : SOL_LIGHT_VEC3(through.x, x.y, through.z);
}

/// The tube's bound at w (the frame of a point of its axis): sol::sdf_tube's.
SOL_SHARED_FUNCTION SOL_REAL sol_tube_light_bound(int axis, SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_LIGHT_VEC3 v = axis == 1 ? sol_axis_swap(w) : w;
  const SOL_REAL across = asinh(abs(v.y) * exp(v.z));
  return max(axis == 2 ? asinh(abs(v.x) * exp(-v.z)) : abs(v.z), across) - radius;
}

/// The outward unit normal (frame components) of the tube's face nearest w
/// (the larger term of its bound): vertical, (±1, 0, −S)/cosh r on x =
/// ±S e^{z} and (0, ±1, S)/cosh r on y = ±S e^{−z}; along x, (0, 0, ±1) on
/// z = ±r and (0, ±1, S)/cosh r on y = ±S e^{−z}.
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_tube_light_normal(int axis, SOL_LIGHT_VEC3 w, SOL_REAL radius) {
  const SOL_LIGHT_VEC3 v = axis == 1 ? sol_axis_swap(w) : w;
  const SOL_REAL across = asinh(abs(v.y) * exp(v.z));
  const SOL_REAL other = axis == 2 ? asinh(abs(v.x) * exp(-v.z)) : abs(v.z);
  const SOL_REAL s = sinh(radius), ch = cosh(radius);
  SOL_LIGHT_VEC3 n = SOL_LIGHT_VEC3(0.0, v.y >= 0.0 ? 1.0 : -1.0, s) / ch;
  if (other > across) {
    n = axis == 2 ? SOL_LIGHT_VEC3(v.x >= 0.0 ? 1.0 : -1.0, 0.0, -s) / ch : SOL_LIGHT_VEC3(0.0, 0.0, v.z >= 0.0 ? 1.0 : -1.0);
  }
  return axis == 1 ? sol_axis_swap(n) : n;
}

/// Whether a path's vertex at wx lies on the tube's face that holds the
/// light point wy (both in the frame of one foot): left to reflection, as
/// a box's (sol_box_light_same_face).
SOL_SHARED_FUNCTION bool sol_tube_light_same_face(int axis, SOL_LIGHT_VEC3 wx, SOL_LIGHT_VEC3 wy, SOL_REAL radius) {
  return abs(sol_tube_light_bound(axis, wx, radius)) < 1e-3 &&
         sol_tube_light_normal(axis, wx, radius) == sol_tube_light_normal(axis, wy, radius);
}

/// The coordinate along the tube's axis of w (its foot's frame).
SOL_SHARED_FUNCTION SOL_REAL sol_tube_light_along(int axis, SOL_LIGHT_VEC3 w) { return axis == 2 ? w.z : (axis == 0 ? w.x : w.y); }

/// The density per unit area of sol_tube_light_point at w (its foot's
/// frame) for a diffuse point at distance h: the Cauchy density of t over
/// the tube's area a unit of length, 4 sinh 2r; 0 beyond the window.
SOL_SHARED_FUNCTION SOL_REAL sol_tube_light_density(int axis, SOL_LIGHT_VEC3 w, SOL_REAL radius, SOL_REAL h) {
  const SOL_REAL window = sol_light_window(h), a = max(h, SOL_REAL(0.0)) + radius, t = sol_tube_light_along(axis, w);
  if (!(abs(t) <= window)) return 0.0;
  return a / ((a * a + t * t) * 2.0 * atan(window / a) * 4.0 * sinh(2.0 * radius));
}

/// The point of the tube's surface (its foot's frame) that three uniform
/// numbers draw for a diffuse point at distance h: u0 picks a face by its
/// share of the area, u1 the coordinate t = a tan θ along the axis (θ
/// uniform), u2 the one across the face (along x, the side faces' z with
/// density e^{−z}).
SOL_SHARED_FUNCTION SOL_LIGHT_VEC3 sol_tube_light_point(int axis, SOL_REAL radius, SOL_REAL h, SOL_REAL u0, SOL_REAL u1,
                                                        SOL_REAL u2) {
  const SOL_REAL window = sol_light_window(h), a = max(h, SOL_REAL(0.0)) + radius;
  // (t held to the window: tan(atan(W / a)) rounds above W / a for u1 near 0 or 1, where the density would be 0.)
  const SOL_REAL s = sinh(radius), across = 2.0 * u2 - 1.0;
  const SOL_REAL t = min(max(a * tan((2.0 * u1 - 1.0) * atan(window / a)), -window), window);
  if (axis == 2) {  // four faces of equal area
    if (u0 < 0.5) return SOL_LIGHT_VEC3(u0 < 0.25 ? s * exp(t) : -s * exp(t), across * s * exp(-t), t);
    return SOL_LIGHT_VEC3(across * s * exp(t), u0 < 0.75 ? s * exp(-t) : -s * exp(-t), t);
  }
  // Along x: z = +r, z = −r, y = +S e^{−z}, y = −S e^{−z}, shares e^{−r}/(4 cosh r), e^{r}/(4 cosh r), 1/4, 1/4.
  const SOL_REAL top = 0.25 * exp(-radius) / cosh(radius), bottom = 0.25 * exp(radius) / cosh(radius);
  SOL_LIGHT_VEC3 p;
  if (u0 < top + bottom) {
    const SOL_REAL z = u0 < top ? radius : -radius;
    p = SOL_LIGHT_VEC3(t, across * s * exp(-z), z);
  } else {
    const SOL_REAL z = -log(exp(radius) - u2 * (exp(radius) - exp(-radius)));  // density e^{−z} on [−r, r]
    p = SOL_LIGHT_VEC3(t, u0 < top + bottom + 0.25 ? s * exp(-z) : -s * exp(-z), z);
  }
  return axis == 1 ? sol_axis_swap(p) : p;
}

#undef SOL_SHARED_FUNCTION
#undef SOL_LIGHT_VEC3
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_SURFACE_LIGHT_H
