// Geodesic flow and parallel transport in Sol.
//
// A geodesic state is a point and a unit tangent given by its frame
// components (docs/conventions.md). Geodesics are left-invariant: the geodesic from
// p with direction v is p * γ_v(t), with γ_v the geodesic from the origin, and
// the frame components of the tangent are the same along both. libsol
// therefore integrates from the origin (small coordinates) and left-translates.
//
// In frame components the geodesic equations are
//   u1' = u1 u3,  u2' = -u2 u3,  u3' = u2^2 - u1^2,
//   x' = e^{z} u1, y' = e^{-z} u2, z' = u3,
// and parallel transport along the geodesic is Q' = -B Q with
//   B = [[0,0,-u1],[0,0,u2],[u1,-u2,0]]   (Grayson; derived from the
// Levi-Civita connection of the frame, see geodesic.cpp).
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace sol {

/// A point of Sol with a unit tangent direction in frame components.
struct GeodesicState {
  glm::dvec3 position{0.0};
  glm::dvec3 direction{1.0, 0.0, 0.0};
};

/// How flow and transport follow the geodesic.
enum class Method {
  Auto,           ///< the closed form (exact to rounding, cost independent of t)
  RK4,            ///< classical Runge–Kutta, fixed step FlowOptions::rk4_step
  DormandPrince,  ///< adaptive Dormand–Prince 5(4), tolerance FlowOptions::tolerance
  ClosedForm,     ///< closed form with Jacobi elliptic functions (sol/closed_form.hpp)
};

/// Settings for flow and transport. The defaults are sound: the closed form
/// for flow; for transport the closed-form tangent drives Q' = -B(u(t)) Q,
/// integrated by Dormand–Prince at `tolerance` (1e-12 keeps |Q - Q_exact|
/// near 1e-11 up to t = 50).
struct FlowOptions {
  Method method = Method::Auto;
  double rk4_step = 1e-3;    ///< RK4 step in arc length (> 0); the step is shortened to divide |t| evenly
  double tolerance = 1e-12;  ///< Dormand–Prince mixed absolute/relative tolerance (> 0)
};

/// Follows the geodesic from `start` for arc length `t` (negative `t` goes
/// backwards). `start.direction` need not be unit: it is normalised; a zero
/// or non-finite direction, a non-finite position or `t` throws
/// InvalidArgument.
GeodesicState flow(const GeodesicState& start, double t, Method method = Method::Auto);
GeodesicState flow(const GeodesicState& start, double t, const FlowOptions& options);

/// Parallel-transport matrix Q(t) along the geodesic from `start`: column i is
/// the frame components, at flow(start, t).position, of the frame vector E_i
/// at start.position transported along the geodesic. Q is orthogonal and
/// transport(s, t) * s.direction == flow(s, t).direction.
glm::dmat3 transport(const GeodesicState& start, double t, Method method = Method::Auto);
glm::dmat3 transport(const GeodesicState& start, double t, const FlowOptions& options);

/// flow and transport together, from one integration.
struct FlowTransport {
  GeodesicState state;
  glm::dmat3 transport{1.0};
};
FlowTransport flow_with_transport(const GeodesicState& start, double t, const FlowOptions& options = {});

/// The geodesic's velocity derivative in frame components (the right-hand
/// side of the geodesic equations above), exposed for tests and kernels.
glm::dvec3 geodesic_acceleration(const glm::dvec3& direction);

}  // namespace sol
