#include "sol/observer.hpp"

#include <cmath>

#include <glm/geometric.hpp>

#include "check.hpp"
#include "sol/error.hpp"
#include "sol/scene.hpp"

namespace sol {

Observer::Observer() : Observer({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}) {}

Observer::Observer(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up)
    : m_position(position) {
  constexpr const char* function = "sol::Observer::Observer";
  detail::require_finite(position, function, "position");
  detail::require_finite(forward, function, "forward");
  detail::require_finite(up, function, "up");
  const double f = glm::length(forward), u = glm::length(up);
  if (f == 0.0 || u == 0.0) throw InvalidArgument("sol::Observer: forward and up must be non-zero");
  if (glm::length(glm::cross(forward / f, up / u)) < 1e-9) {
    throw InvalidArgument("sol::Observer: forward and up must not be parallel");
  }
  m_frame[2] = forward;
  m_frame[1] = up;
  orthonormalise();
}

void Observer::orthonormalise() {
  // The camera convention of docs/conventions.md: forward first, right = forward × up, up = right × forward.
  const glm::dvec3 f = glm::normalize(m_frame[2]);
  const glm::dvec3 r = glm::normalize(glm::cross(f, m_frame[1]));
  m_frame[0] = r;
  m_frame[1] = glm::cross(r, f);
  m_frame[2] = f;
}

void Observer::keep_in_domain() {
  if (!m_lattice) return;
  // point = e · p: the cover position w · p is (w e⁻¹) · point.
  const Teleport t = m_lattice->teleport(m_position);
  m_position = t.point;
  // A teleport that turns (a lattice of negative trace) turns the frame:
  // E1, E2 -> -E1, -E2, so every frame vector's first two components.
  if (t.turned) m_frame = glm::dmat3(glm::dvec3(-1.0, 0.0, 0.0), glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0)) * m_frame;
  const LatticeWord e = m_lattice->word_of(t.element);
  if (e == LatticeWord{} || !m_copy_known) return;
  try {
    m_copy = m_lattice->multiply(m_copy, m_lattice->inverse(e));
  } catch (const OutOfRange&) {
    m_copy_known = false;  // past ±2^62: no longer tracked (copy_known)
  }
}

void Observer::move(const glm::dvec3& local_direction, double distance) {
  constexpr const char* function = "sol::Observer::move";
  detail::require_finite(local_direction, function, "local_direction");
  detail::require_finite(distance, function, "distance");
  if (glm::length(local_direction) == 0.0) throw InvalidArgument("sol::Observer::move: zero direction");
  if (distance == 0.0) return;
  const GeodesicState start{m_position, m_frame * glm::normalize(local_direction)};
  const FlowTransport moved = flow_with_transport(start, distance, m_options);
  m_position = moved.state.position;
  // Every frame vector is carried along the geodesic: frame' = Q * frame.
  m_frame = moved.transport * m_frame;
  orthonormalise();
  keep_in_domain();
}

namespace {

// Rotates `a` towards `b` by `angle` (a and b orthonormal); returns the new (a, b).
void rotate_pair(glm::dvec3& a, glm::dvec3& b, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const glm::dvec3 na = c * a + s * b;
  const glm::dvec3 nb = -s * a + c * b;
  a = na;
  b = nb;
}

}  // namespace

void Observer::yaw(double angle) {
  detail::require_finite(angle, "sol::Observer::yaw", "angle");
  rotate_pair(m_frame[2], m_frame[0], angle);  // forward towards right
  orthonormalise();
}

void Observer::pitch(double angle) {
  detail::require_finite(angle, "sol::Observer::pitch", "angle");
  rotate_pair(m_frame[2], m_frame[1], angle);  // forward towards up
  orthonormalise();
}

void Observer::roll(double angle) {
  detail::require_finite(angle, "sol::Observer::roll", "angle");
  rotate_pair(m_frame[1], m_frame[0], angle);  // up towards right
  orthonormalise();
}

void Observer::face(const glm::dvec3& forward) {
  detail::require_finite(forward, "sol::Observer::face", "forward");
  if (glm::length(forward) == 0.0) throw InvalidArgument("sol::Observer::face: zero forward");
  const glm::dvec3 f = glm::normalize(forward);
  if (glm::length(glm::cross(f, m_frame[1])) > 1e-9) {
    m_frame[2] = f;
    orthonormalise();
    return;
  }
  // Along the old up: the least rotation from the old forward to f, about
  // their common normal (the old forward is orthogonal to the old up, so
  // the two are never parallel here).
  const glm::dvec3 old = m_frame[2];
  const glm::dvec3 axis = glm::normalize(glm::cross(old, f));
  const double angle = std::atan2(glm::length(glm::cross(old, f)), glm::dot(old, f));
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 v = m_frame[i];
    m_frame[i] = v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) + axis * glm::dot(axis, v) * (1.0 - std::cos(angle));
  }
  m_frame[2] = f;
  orthonormalise();
}

void Observer::bind(std::optional<Lattice> lattice) {
  m_lattice = std::move(lattice);
  m_copy = {};
  m_copy_known = true;
  keep_in_domain();
}

void Observer::set_flow_options(const FlowOptions& options) {
  if (!(options.rk4_step > 0.0) || !(options.tolerance > 0.0) || !std::isfinite(options.rk4_step) ||
      !std::isfinite(options.tolerance)) {
    throw InvalidArgument("sol::Observer::set_flow_options: rk4_step and tolerance must be finite and > 0");
  }
  m_options = options;
}

Observer observer_at(const Scene& scene) {
  Observer o(scene.camera.position, scene.camera.forward, scene.camera.up);
  o.bind(scene.lattice());
  return o;
}

}  // namespace sol
