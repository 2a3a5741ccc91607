// Depth of field: a thin lens at the eye (docs/conventions.md "Depth of
// field"). The lens is the disk of radius Camera::aperture in the eye's
// tangent plane spanned by right and up; the lens point of a disk point
// (ξ, η) is δ = exp(aperture (ξ right + η up)), the end of the geodesic from
// the eye with that initial velocity. The points in focus are those at arc
// length Camera::focus_distance f along each pixel's geodesic from the eye,
// F = exp(f u) for its direction u. A thin lens sends every ray of the
// pixel through F: from δ along the geodesic that meets F. In Euclidean
// space that ray leaves along f u − δ; in Sol geodesics spread, and that
// guess passes F at a share of the aperture that grows with f (0.7 to 0.8
// apertures at f = 3, Lens.TheEuclideanGuessMissesTheFocus), so the ray is
// found as the solution v of
// exp(v) = δ⁻¹ F near f u by Newton's method (left translations are
// isometries that keep frame components: the ray from δ with frame
// components v/|v| is δ times the geodesic from the origin along v).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sol/camera.hpp"

namespace sol {

/// The k-th lens sample (k >= 0), a point of the unit disk: sample 0 is its
/// centre (so that sample 0 of a render, which writes the AOVs, is the
/// pinhole's ray), sample k > 0 the concentric map (Shirley and Chiu 1997,
/// area-preserving) of the Halton point (radical inverses of k in bases 2
/// and 3), a low-discrepancy sequence unrelated to sol::pixel_sample's. As
/// pixel_sample, every pixel takes the same lens point for sample k: a few
/// samples show an out-of-focus object as a few sharp copies, many as its
/// blur.
glm::dvec2 lens_sample(int k);

/// A ray of the lens: where it starts, relative to the eye (the eye is at
/// multiply(camera.position, start)), and its unit direction in frame
/// components there.
struct LensRay {
  glm::dvec3 start{0.0};
  glm::dvec3 direction{1.0, 0.0, 0.0};
  /// The arc length from the start to the focus point along the ray.
  double focus_length = 0.0;
  /// Whether it meets the focus point (false where Newton's method found no
  /// solution near f u, as beyond a conjugate point of the pixel's
  /// geodesic, where the bundle does not refocus: the ray then leaves the
  /// lens point along u).
  bool focused = true;
};

/// The ray through lens point `disk` (of the unit disk) of the pixel ray
/// `direction` (unit, frame components at the eye) of a camera with
/// aperture a and focus distance f (the camera's basis gives right and up).
/// With a = 0 or disk at the centre, the pixel ray itself. The ray meets F =
/// exp(f u) within 1e-12 of its scale (Lens.EveryLensRayMeetsTheFocus).
LensRay lens_ray(const Camera& camera, const glm::dvec3& direction, const glm::dvec2& disk);

/// The end of the geodesic from the origin with initial velocity v (frame
/// components): its position after arc length |v|.
glm::dvec3 exp_map(const glm::dvec3& v);

}  // namespace sol
