// Probes of the kernels' building blocks, for tests and benchmarks: each
// runs one GLSL function (the closed-form flow and its tangents, the zeta
// function's positions, cut times, the spreading J, the exponential map's
// Jacobian, the logarithm's series, the connection solver) over a list of
// queries on the device and reads the results back, so that tests can hold
// the float kernels to libsol's double references. Not for rendering:
// sol::vk::MarchRenderer draws (sol/vk/march.hpp).
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace sol::vk {

class Context;

/// Evaluates the kernel's closed-form geodesic (compute/shaders/flow.comp)
/// for queries (direction xyz, arc length w); returns (position xyz, height
/// from the height-only path w) per query. With `segments` > 1 the arc
/// length is walked in that many equal segments, the ray restarted at each
/// end (sol_ray_advanced, as the quotient march's teleports) and the
/// positions composed: then w is the position's z. For tests and benchmarks.
std::vector<glm::vec4> evaluate_kernel_flow(Context& context, const std::vector<glm::vec4>& queries, int segments = 1);

/// The kernel's position (xyz; w 0) at the arc length w >= 0 of each query's
/// geodesic by Jacobi's zeta function (sol_forward_zeta), as the quotient
/// march's first pass takes it for rays of μ = |ab| >= kZetaLeastMu; walked
/// in `segments` as evaluate_kernel_flow (sol_ray_restarted_zeta). For tests.
std::vector<glm::vec4> evaluate_kernel_flow_by_zeta(Context& context, const std::vector<glm::vec4>& queries, int segments = 1);

/// The kernel's unit tangent (frame components; w 0) at the arc length w >= 0
/// of each query's geodesic, as the quotient march takes it for its
/// clearances (sol_forward in compute/shaders/sol_forward.glsl). For tests.
std::vector<glm::vec4> evaluate_kernel_tangents(Context& context, const std::vector<glm::vec4>& queries);

/// The same by Jacobi's zeta function (sol_forward_zeta), as the quotient
/// march's first pass takes it for rays of μ >= kZetaLeastMu. For tests.
std::vector<glm::vec4> evaluate_kernel_tangents_by_zeta(Context& context, const std::vector<glm::vec4>& queries);

/// The kernel's cut time of each direction (sol_cut_time, the z-period
/// that certifies a minimiser; 1e30 where sol::cut_time is infinite). For tests.
std::vector<float> evaluate_kernel_cut_times(Context& context, const std::vector<glm::vec3>& directions);

/// Evaluates the kernel's J (compute/shaders/sol_spreading.glsl, the
/// spreading of light along a geodesic) for queries (direction xyz, arc
/// length w); the float counterpart of sol::sphere_area_density. For tests
/// and benchmarks.
std::vector<float> evaluate_kernel_spreading(Context& context, const std::vector<glm::vec4>& queries);

/// The kernel's Jacobian of the exponential map at the origin, d exp(v)/dv
/// at v = t·d for queries (direction d xyz, nonzero; length t >= 0 in w),
/// in frame components at exp(v) (sol_exp_jacobian in
/// compute/shaders/sol_spreading.glsl: the connection solver's Newton
/// steps). For tests.
std::vector<glm::mat3> evaluate_kernel_exp_jacobians(Context& context, const std::vector<glm::vec4>& queries);

/// The end point exp(t·d) and the unit tangent there (frame components) of
/// the geodesic from the origin, for queries (direction d xyz, nonzero;
/// length t >= 0 in w), by the kernel's RK4 along with J (sol_spread in
/// compute/shaders/sol_spreading.glsl: a glowing ball's sampled point).
/// For tests.
std::vector<std::pair<glm::vec3, glm::vec3>> evaluate_kernel_spread_ends(Context& context,
                                                                         const std::vector<glm::vec4>& queries);

/// The kernel's series of Sol's logarithm at the origin at each target w
/// (sol_log_series, sol/log_series.h, in float: where the exact balls'
/// Newton solves start), the initial vector of the geodesic from the
/// origin that ends at w; for |w| < kLogSeriesReach. For tests.
std::vector<glm::vec3> evaluate_kernel_log_series(Context& context, const std::vector<glm::vec3>& targets);

/// What the kernel's connection solver (compute/shaders/sol_connection.glsl,
/// the exact point lights' directions) returns for one target.
struct KernelConnections {
  int count = 0;
  std::array<glm::vec4, 16> found{};  // sol::ConnectionTable::kSlots  ///< (unit direction at the origin, length), shortest first
};

/// Runs the kernel's connection solver (compute/shaders/connect.comp) for
/// queries (w xyz: the target seen from the origin, reach w) with the seeds
/// of sol::ConnectionTable::shared(longer), keeping every connection found
/// with `longer` and the shortest 4 without (as the march kernel does for
/// lights with and without a reach); the dispatch time in ms into
/// *device_ms when given. For tests and benchmarks.
std::vector<KernelConnections> evaluate_kernel_connections(Context& context, const std::vector<glm::vec4>& queries,
                                                           bool longer, double* device_ms = nullptr);

}  // namespace sol::vk
