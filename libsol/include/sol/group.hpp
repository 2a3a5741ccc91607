// The Sol group law and the left-invariant orthonormal frame.
//
// Sol is R^3 with the metric ds^2 = e^{-2z}dx^2 + e^{2z}dy^2 + dz^2 and the
// group law (x1,y1,z1)*(x2,y2,z2) = (e^{z1}x2 + x1, e^{-z1}y2 + y1, z1+z2),
// whose left translations are isometries. The left-invariant orthonormal
// frame is E1 = e^{z}∂x, E2 = e^{-z}∂y, E3 = ∂z; libsol stores tangent vectors
// by their frame components (a,b,c), whose coordinate velocity is
// (e^{z}a, e^{-z}b, c). See docs/conventions.md.
#pragma once

#include <glm/vec3.hpp>

namespace sol {

/// Group product p * q. Throws InvalidArgument on non-finite input.
glm::dvec3 multiply(const glm::dvec3& p, const glm::dvec3& q);

/// Group inverse: multiply(p, inverse(p)) == (0,0,0).
glm::dvec3 inverse(const glm::dvec3& p);

/// Coordinate velocity (dx/dt, dy/dt, dz/dt) at `point` of the tangent vector
/// with frame components `frame` (components along E1, E2, E3).
glm::dvec3 velocity_from_frame(const glm::dvec3& point, const glm::dvec3& frame);

/// Frame components at `point` of the tangent vector with coordinate
/// velocity `velocity`; the inverse of velocity_from_frame.
glm::dvec3 frame_from_velocity(const glm::dvec3& point, const glm::dvec3& velocity);

}  // namespace sol
