// Where a geodesic leaves a small sphere it is inside of, solved at once
// (libsol-internal; the CPU renderer's exit search from an exact ball's inner
// wall, docs/lighting.md, "Enclosures").
#pragma once

#include <optional>

#include <glm/vec3.hpp>

#include "sol/closed_form.hpp"

namespace sol::detail {

struct SphereExit {
  double s = 0.0;             ///< arc length along the ray
  glm::dvec3 outward{0.0};    ///< the sphere's outward unit normal there (frame components)
  glm::dvec3 direction{0.0};  ///< the ray's unit tangent there (frame components)
};

/// Where the geodesic `ray` from the point `from` crosses the sphere of
/// radius `level` about `centre` heading out, by Newton's method on the
/// direction w from the centre and the arc length s at once, for
/// exp_centre(level ŵ) = from · ray(s), started at arc length s0. The sphere
/// must be smaller than Sol's injectivity radius (a geodesic from the centre
/// that short is its only minimiser, so level is the distance there): the
/// callers' balls are below kConvexBallRadius. Nothing where Newton does not
/// converge, the crossing found heads in, or s is not in (0, limit].
std::optional<SphereExit> sphere_exit(const glm::dvec3& centre, double level, const glm::dvec3& from,
                                      const ClosedFormGeodesic<double>& ray, double s0, double limit);

}  // namespace sol::detail
