#include "sol/aim.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "check.hpp"
#include "sol/connection.hpp"
#include "sol/distance.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"

namespace sol {
namespace {

constexpr double kTie = 1e-9;  // minimisers this close in length are one length

// The minimising geodesic from p to q in Sol, the upward one on the cut locus.
Aim aim_in_sol(const glm::dvec3& p, const glm::dvec3& q) {
  const std::vector<Connection> found = minimising_geodesics(p, q);
  if (found.empty()) throw OutOfRange("sol::aim: no minimising geodesic found");
  Aim a;
  a.direction = found[0].direction;
  a.distance = found[0].length;
  for (std::size_t i = 1; i < found.size(); ++i) {
    if (std::abs(found[i].length - a.distance) > kTie) continue;
    a.cut_locus = true;
    if (found[i].direction.z > a.direction.z) a.direction = found[i].direction;
  }
  a.end = q;
  return a;
}

}  // namespace

Aim aim(const glm::dvec3& eye, const glm::dvec3& target, const std::optional<Lattice>& lattice) {
  detail::require_finite(eye, "sol::aim", "eye");
  detail::require_finite(target, "sol::aim", "target");
  if (!lattice) {
    if (distance_lower_bound(eye, target) < kTie && glm::length(eye - target) < kTie) {
      throw InvalidArgument("sol::aim: the target is at the eye, which sees it in no direction");
    }
    return aim_in_sol(eye, target);
  }
  // Into the domain: the eye by the isometry phi(x) = E h(x) of its teleport
  // (h the half-turn where it turned), the target by its own; the nearest
  // image of the target to phi(eye) is searched among the words that bring
  // it within the identity image's distance of D (phi(eye) lies in D).
  const Teleport from = lattice->teleport(eye);
  const glm::dvec3 p = from.point;
  const glm::dvec3 q = lattice->teleport(target).point;
  const double first = distance(p, q);
  double best = first;
  glm::dvec3 nearest = q;
  bool tie = false;
  for (const LatticeWord& w : lattice->words_near_domain(ImageAnchor{ImageAnchor::Along::Point, q, {}}, first + kTie)) {
    const glm::dvec3 image = lattice->apply(w, q);
    if (w == LatticeWord{} || distance_lower_bound(p, image) > best + kTie) continue;
    const double d = distance(p, image);
    if (d < best - kTie) {
      best = d;
      nearest = image;
      tie = false;
    } else if (d <= best + kTie) {
      tie = true;
    }
  }
  if (best < kTie) throw InvalidArgument("sol::aim: the target is at the eye (or one of its images), which sees it in no direction");
  Aim a = aim_in_sol(p, nearest);
  a.cut_locus = a.cut_locus || tie;
  // Back to the eye's coordinates: phi^-1(y) = h(E^-1 y); frame components
  // keep under left translations and turn (a, b, c) -> (-a, -b, c) under h.
  a.end = multiply(inverse(from.element), a.end);
  if (from.turned) {
    a.end = half_turn(a.end);
    a.direction = glm::dvec3(-a.direction.x, -a.direction.y, a.direction.z);
  }
  return a;
}

double focus_on(const Aim& aim, double otherwise) {
  return aim.distance > 0.0 && aim.distance <= 100.0 ? aim.distance : otherwise;
}

Camera looking_at(Camera camera, const glm::dvec3& target, const std::optional<Lattice>& lattice) {
  const Aim to = aim(camera.position, target, lattice);
  const glm::dvec3 forward = to.direction;
  if (!(glm::length(camera.up) > 0.0) || glm::length(glm::cross(forward, glm::normalize(camera.up))) < 1e-9) {
    throw InvalidArgument("sol::looking_at: the target is seen straight along the camera's up, which leaves the image's "
                          "orientation undefined; give an up not parallel to the direction towards it");
  }
  camera.forward = forward;
  camera.focus_distance = focus_on(to, camera.focus_distance);
  return camera;
}

}  // namespace sol
