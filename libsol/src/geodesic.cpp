#include "sol/geodesic.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "check.hpp"
#include "ode.hpp"
#include "sol/closed_form.hpp"
#include "sol/group.hpp"

// The geodesic and transport equations in the frame E1 = e^{z}∂x,
// E2 = e^{-z}∂y, E3 = ∂z. Brackets: [E3,E1] = E1, [E3,E2] = -E2, [E1,E2] = 0.
// The Koszul formula gives the Levi-Civita connection
//   ∇_{E1}E1 = E3, ∇_{E1}E3 = -E1, ∇_{E2}E2 = -E3, ∇_{E2}E3 = E2,
// all other ∇_{Ei}Ej = 0. A vector w transported along a curve with frame
// velocity u satisfies w' + ∇_u w = 0, i.e.
//   w1' = u1 w3, w2' = -u2 w3, w3' = -u1 w1 + u2 w2   (w' = -B w),
// and the geodesic equation is the case w = u.

namespace sol {
namespace {

using detail::State;

// (x, y, z, u1, u2, u3): position relative to the start and frame velocity.
State<6> geodesic_rhs(const State<6>& s) {
  const double ez = std::exp(s[2]);
  return {ez * s[3], s[4] / ez, s[5], s[3] * s[5], -s[4] * s[5], s[4] * s[4] - s[3] * s[3]};
}

// Geodesic state followed by Q in column-major order (Q' = -B Q).
State<15> transport_rhs(const State<15>& s) {
  State<15> r;
  const State<6> g = geodesic_rhs(State<6>{s[0], s[1], s[2], s[3], s[4], s[5]});
  for (int i = 0; i < 6; ++i) r[i] = g[i];
  const double u1 = s[3], u2 = s[4];
  for (int c = 0; c < 3; ++c) {
    const double w1 = s[6 + 3 * c], w2 = s[7 + 3 * c], w3 = s[8 + 3 * c];
    r[6 + 3 * c] = u1 * w3;
    r[7 + 3 * c] = -u2 * w3;
    r[8 + 3 * c] = -u1 * w1 + u2 * w2;
  }
  return r;
}

void validate(const GeodesicState& start, double t, const FlowOptions& options, const char* function) {
  detail::require_finite(start.position, function, "start.position");
  detail::require_finite(start.direction, function, "start.direction");
  detail::require_finite(t, function, "t");
  if (glm::length(start.direction) == 0.0) {
    throw InvalidArgument(std::string(function) + ": argument 'start.direction' is zero");
  }
  if (!(options.rk4_step > 0.0) || !std::isfinite(options.rk4_step)) {
    throw InvalidArgument(std::string(function) + ": FlowOptions::rk4_step must be finite and > 0");
  }
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw InvalidArgument(std::string(function) + ": FlowOptions::tolerance must be finite and > 0");
  }
}

template <std::size_t N>
void require_finite_result(const State<N>& y, const char* function);

Method resolve(Method method) { return method == Method::Auto ? Method::ClosedForm : method; }

// Q' = -B(u(t)) Q with u(t) from the closed form, integrated by Dormand–Prince
// (state: Q column-major, then t): the transport ODE alone, no geodesic ODE.
glm::dmat3 transport_along(const ClosedFormGeodesic<double>& geodesic, double t, double tolerance,
                            const char* function) {
  auto rhs = [&geodesic](const State<10>& s) {
    const glm::dvec3 u = geodesic.direction_at(s[9]);
    State<10> r;
    for (int c = 0; c < 3; ++c) {
      const double w1 = s[3 * c], w2 = s[3 * c + 1], w3 = s[3 * c + 2];
      r[3 * c] = u.x * w3;
      r[3 * c + 1] = -u.y * w3;
      r[3 * c + 2] = -u.x * w1 + u.y * w2;
    }
    r[9] = 1.0;
    return r;
  };
  State<10> absolute;
  absolute.fill(1.0);
  const State<10> y = detail::integrate_dormand_prince(rhs, State<10>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, t, tolerance, absolute, function);
  return glm::dmat3(y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8]);
}

// origin * p: the end point of the geodesic from `origin` whose end from
// the origin is p (left invariance), refused naming `function` where it
// overflows double.
glm::dvec3 moved_end(const glm::dvec3& origin, const glm::dvec3& p, const char* function) {
  try {
    return multiply(origin, p);
  } catch (const OutOfRange&) {
    throw OutOfRange(std::string(function) + ": the end point overflows double (start.position " +
                     "is too far from the origin)");
  }
}

GeodesicState closed_form_state(const ClosedFormGeodesic<double>& geodesic, const glm::dvec3& origin, double t,
                                const char* function) {
  const ClosedFormGeodesic<double>::State s = geodesic.at(t);
  const State<6> y{s.position.x, s.position.y, s.position.z, s.direction.x, s.direction.y, s.direction.z};
  require_finite_result(y, function);
  return {moved_end(origin, s.position, function), s.direction};
}

// Error control per component: u1 = a e^{z} and u2 = b e^{-z} decay
// exponentially along most geodesics, yet their relative size steers the
// rest of the path (e^{-z}u1 = a is a first integral), so they are controlled
// relatively; everything else mixed absolute/relative.
template <std::size_t N>
State<N> absolute_weights() {
  State<N> w;
  w.fill(1.0);
  w[3] = w[4] = 0.0;
  return w;
}

template <std::size_t N, class F>
State<N> integrate(const F& f, const State<N>& y0, double t, Method method, const FlowOptions& options,
                   const char* function) {
  return method == Method::RK4
             ? detail::integrate_rk4(f, y0, t, options.rk4_step, function)
             : detail::integrate_dormand_prince(f, y0, t, options.tolerance, absolute_weights<N>(), function);
}

template <std::size_t N>
void require_finite_result(const State<N>& y, const char* function) {
  for (double v : y) {
    if (!std::isfinite(v)) {
      throw OutOfRange(std::string(function) +
                       ": the geodesic leaves the range of double (e^{z} overflows); shorten t");
    }
  }
}

}  // namespace

GeodesicState flow(const GeodesicState& start, double t, Method method) {
  FlowOptions options;
  options.method = method;
  return flow(start, t, options);
}

GeodesicState flow(const GeodesicState& start, double t, const FlowOptions& options) {
  constexpr const char* function = "sol::flow";
  validate(start, t, options, function);
  const Method method = resolve(options.method);
  const glm::dvec3 u = glm::normalize(start.direction);
  if (method == Method::ClosedForm) return closed_form_state(ClosedFormGeodesic<double>(u), start.position, t, function);
  const State<6> y = integrate(geodesic_rhs, State<6>{0, 0, 0, u.x, u.y, u.z}, t, method, options, function);
  require_finite_result(y, function);
  // Left-invariance: the geodesic from p is p * (geodesic from the origin).
  return {moved_end(start.position, {y[0], y[1], y[2]}, function), {y[3], y[4], y[5]}};
}

glm::dmat3 transport(const GeodesicState& start, double t, Method method) {
  FlowOptions options;
  options.method = method;
  return transport(start, t, options);
}

glm::dmat3 transport(const GeodesicState& start, double t, const FlowOptions& options) {
  return flow_with_transport(start, t, options).transport;
}

FlowTransport flow_with_transport(const GeodesicState& start, double t, const FlowOptions& options) {
  constexpr const char* function = "sol::transport";
  validate(start, t, options, function);
  const Method method = resolve(options.method);
  const glm::dvec3 u = glm::normalize(start.direction);
  if (method == Method::ClosedForm) {
    const ClosedFormGeodesic<double> geodesic(u);
    const glm::dmat3 q = transport_along(geodesic, t, options.tolerance, function);
    const State<9> values{q[0][0], q[0][1], q[0][2], q[1][0], q[1][1], q[1][2], q[2][0], q[2][1], q[2][2]};
    require_finite_result(values, function);
    return {closed_form_state(geodesic, start.position, t, function), q};
  }
  // Q depends only on the frame velocity u(t), which is left-invariant, so
  // the start position does not enter.
  const State<15> y = integrate(transport_rhs, State<15>{0, 0, 0, u.x, u.y, u.z, 1, 0, 0, 0, 1, 0, 0, 0, 1},
                                t, method, options, function);
  require_finite_result(y, function);
  return {{multiply(start.position, {y[0], y[1], y[2]}), {y[3], y[4], y[5]}},
          glm::dmat3(y[6], y[7], y[8], y[9], y[10], y[11], y[12], y[13], y[14])};
}

glm::dvec3 geodesic_acceleration(const glm::dvec3& direction) {
  detail::require_finite(direction, "sol::geodesic_acceleration", "direction");
  return {direction.x * direction.z, -direction.y * direction.z,
          direction.y * direction.y - direction.x * direction.x};
}

}  // namespace sol
