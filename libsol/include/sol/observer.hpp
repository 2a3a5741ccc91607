// An observer walking along Sol geodesics: a position and an orthonormal frame.
//
// The frame (right, up, forward) is stored by its frame components at the
// observer's position, following the camera convention of docs/conventions.md:
// right = normalize(forward × up), up = right × forward. Moving flows along a
// geodesic and parallel-transports the frame; rotations turn the frame in
// place. After every change the frame is re-orthonormalised (Gram–Schmidt on
// forward, then up), so rounding never accumulates into drift.
#pragma once

#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sol/geodesic.hpp"
#include "sol/lattice.hpp"

namespace sol {

class Observer {
 public:
  /// At the origin, looking along E1 (+x) with up E3 (+z).
  Observer();

  /// At `position` looking along `forward` with `up` (frame components at
  /// `position`, need not be unit or orthogonal but must not be parallel).
  /// Throws InvalidArgument on non-finite, zero or parallel input.
  Observer(const glm::dvec3& position, const glm::dvec3& forward, const glm::dvec3& up);

  const glm::dvec3& position() const { return m_position; }
  glm::dvec3 right() const { return m_frame[0]; }
  glm::dvec3 up() const { return m_frame[1]; }
  glm::dvec3 forward() const { return m_frame[2]; }
  /// Columns right, up, forward: maps observer-local components to frame
  /// components. With right = forward × up this matrix has determinant -1.
  const glm::dmat3& frame() const { return m_frame; }

  /// Moves `distance` along the geodesic whose initial direction is
  /// `local_direction` given in the observer's own frame as (right, up,
  /// forward) components (normalised; must be non-zero). The frame is
  /// parallel-transported along the geodesic. Negative distance moves back.
  void move(const glm::dvec3& local_direction, double distance);

  /// Turns right by `angle` radians about up (forward → right).
  void yaw(double angle);
  /// Looks up by `angle` radians about right (forward → up).
  void pitch(double angle);
  /// Rolls clockwise (as seen from behind) by `angle` radians about forward (up → right).
  void roll(double angle);
  /// Turns to look along `forward` (frame components at the position, need
  /// not be unit): up becomes the nearest to the old up that is orthogonal to
  /// it; where `forward` runs along the old up (within 1e-9), the whole
  /// frame turns by the least rotation that takes the old forward to it
  /// instead. Throws InvalidArgument on a zero or non-finite `forward`.
  void face(const glm::dvec3& forward);

  /// Binds the observer to a lattice: from now on its position is always
  /// teleported into the fundamental domain D (the frame is left-invariant,
  /// so its components do not change under teleport). std::nullopt unbinds.
  void bind(std::optional<Lattice> lattice);
  const std::optional<Lattice>& lattice() const { return m_lattice; }
  /// Bound: the copy of D the observer is in, in the cover: the element w
  /// of Γ with (position in the cover) = w · position(), accumulated from
  /// every teleport since bind() (which starts it at the identity, then
  /// teleports). The identity when unbound. A walk far enough along z
  /// (about 40 heights of the lattice) takes the word's coefficients past
  /// ±2^62: from then on the copy is no longer tracked (copy_known() false,
  /// copy() the last one known), while the position and frame go on.
  const LatticeWord& copy() const { return m_copy; }
  bool copy_known() const { return m_copy_known; }

  /// Options used by move (method, tolerance).
  void set_flow_options(const FlowOptions& options);
  const FlowOptions& flow_options() const { return m_options; }

 private:
  void orthonormalise();
  void keep_in_domain();

  glm::dvec3 m_position{0.0};
  glm::dmat3 m_frame{1.0};
  std::optional<Lattice> m_lattice;
  LatticeWord m_copy;
  bool m_copy_known = true;
  FlowOptions m_options;
};

struct Scene;

/// An observer at the scene's camera, bound to its world's lattice
/// (World::lattice) in a quotient, so that its walks stay in the domain:
/// what every program walks a scene with.
Observer observer_at(const Scene& scene);

}  // namespace sol
