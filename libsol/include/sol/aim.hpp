// Aiming a camera at a point: its forward is the initial direction of the
// minimising geodesic from the eye to the point, so that the point is seen
// at the image's centre (geodesics bend: the coordinate difference of the
// two points is not where the point is seen).
//
// In a quotient the point has an image in every copy of the fundamental
// domain, and the eye sees each of them; aim takes the nearest image, the
// one joined by the quotient's minimising geodesic. On the cut locus
// (two or more minimisers of one length) the choice is fixed: in Sol the
// minimiser that starts upward (the larger frame component along E3; the
// two minimisers of a cut point differ by the sign of that component); in a
// quotient the image in the eye's own copy of the domain, else the first of
// equally near images in Lattice::words_near_domain's order, then the same rule.
#pragma once

#include <optional>

#include <glm/vec3.hpp>

#include "sol/camera.hpp"
#include "sol/lattice.hpp"

namespace sol {

/// The geodesic aim() found: where it starts, how long it is, where it ends.
struct Aim {
  /// Unit initial direction, frame components at the eye: a camera's forward.
  glm::dvec3 direction{1.0, 0.0, 0.0};
  /// Its length: the distance from the eye to the target (in the quotient,
  /// to its nearest image).
  double distance = 0.0;
  /// Where it ends, in the coordinates of the eye: the target itself in Sol;
  /// in a quotient the image of the target that the geodesic reaches.
  glm::dvec3 end{0.0};
  /// Whether another minimiser of the same length (to within 1e-9) exists:
  /// the target lies on the eye's cut locus, and the choice above was made.
  bool cut_locus = false;
};

/// The minimising geodesic from `eye` to `target`, in Sol or in the quotient
/// of `lattice`. Throws InvalidArgument for non-finite input or a target at
/// the eye (closer than 1e-9: it has no direction); what the connection
/// solver throws where it finds no minimiser (OutOfRange, far stiff
/// targets: sol/connection.hpp).
Aim aim(const glm::dvec3& eye, const glm::dvec3& target, const std::optional<Lattice>& lattice = std::nullopt);

/// The focus distance at which a lens sees an aimed point sharp: the aim's
/// distance where it is a valid Camera::focus_distance ((0, 100]), else
/// `otherwise`.
double focus_on(const Aim& aim, double otherwise);

/// The camera turned to look at `target` (the scene key camera.look_at):
/// its forward aim(camera.position, target, lattice).direction, its up
/// kept (the image's up is the part of it orthogonal to forward, as for any
/// camera), and its lens focused on the point (focus_on). Throws
/// InvalidArgument as aim does, and where the target is seen straight
/// along the camera's up (within 1e-9), which leaves the image's
/// orientation undefined.
Camera looking_at(Camera camera, const glm::dvec3& target, const std::optional<Lattice>& lattice = std::nullopt);

}  // namespace sol
