#include "sol/connection.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <thread>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "check.hpp"
#include "sol/closed_form.hpp"
#include "sol/distance.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"
#include "log_series_at.hpp"
#include "newton_step.hpp"
#include "warm_solves.hpp"

// Method and the facts it rests on: see connection.hpp.

namespace sol {
namespace {

using Geodesic = ClosedFormGeodesic<double>;

struct Solution {
  glm::dvec3 v{0.0, 0.0, 1.0};  // unit direction, reduced frame (a, b >= 0)
  double t = 0.0;
  double period = std::numeric_limits<double>::infinity();
};

// q' = p⁻¹q reduced by (±x, ±y, z) to x, y >= 0; directions map back by the
// same signs on (a, b).
struct Reduction {
  glm::dvec3 q{0.0};
  double sx = 1.0, sy = 1.0;
  glm::dvec3 unreduce(const glm::dvec3& v) const { return {sx * v.x, sy * v.y, v.z}; }
};

Reduction reduce(const glm::dvec3& p, const glm::dvec3& q) {
  const glm::dvec3 r = multiply(inverse(p), q);
  Reduction out;
  out.sx = r.x < 0.0 ? -1.0 : 1.0;
  out.sy = r.y < 0.0 ? -1.0 : 1.0;
  out.q = {std::abs(r.x), std::abs(r.y), r.z};
  return out;
}

// The end point's error in frame components at the end point: e⁻¹q exactly
// (the group difference), whose norm is the distance to first order.
glm::dvec3 frame_error(const glm::dvec3& end, const glm::dvec3& q) {
  return {(q.x - end.x) * std::exp(-end.z), (q.y - end.y) * std::exp(end.z), q.z - end.z};
}

// Far from the origin the flow is exponentially sensitive in frame
// components; in (log x, log y, z) (x, y > 0 along a, b > 0) it is close to
// linear, so the homotopy solves in these and polishes in frame components.
enum class Residual { Frame, Log };

glm::dvec3 residual(const glm::dvec3& end, const glm::dvec3& q, Residual kind) {
  if (kind == Residual::Frame) return frame_error(end, q);
  if (!(end.x > 0.0) || !(end.y > 0.0)) return glm::dvec3(std::numeric_limits<double>::infinity());
  return {std::log(end.x / q.x), std::log(end.y / q.y), end.z - q.z};
}

// What the end point can be trusted to: the closed form is exact to ~1e-15 of
// each coordinate (docs/numerics.md), seen in the frame at q.
double rounding_floor(const glm::dvec3& q) {
  return 1e-14 * std::max({1.0, q.x * std::exp(-q.z), q.y * std::exp(q.z), std::abs(q.z)});
}

// The geodesic of the hyperbolic plane y = 0 from the origin to (X, 0, Z),
// X > 0. In the upper half-plane (x, w = e^{z}) it is the circle through
// (0, 1) and (X, e^{Z}) centred on the axis at x0 = (X² + e^{2Z} - 1)/(2X);
// its tangent at (0, 1) is (1, x0), and there ∂x = E1, ∂w = E3. The length
// from cosh d = cosh Z + ½X² e^{-Z} (docs/mathematics.md), written without
// cancellation as d = 2 asinh √(sinh²(Z/2) + X² e^{-Z}/4).
Solution plane_solution(double X, double Z) {
  Solution s;
  const double a = 2.0 * X, c = X * X + std::expm1(2.0 * Z);
  const double n = std::hypot(a, c);
  s.v = {a / n, 0.0, c / n};
  const double sh = std::sinh(0.5 * Z);
  s.t = 2.0 * std::asinh(std::sqrt(sh * sh + 0.25 * X * X * std::exp(-Z)));
  return s;
}

// Newton's method on (direction, t) for flow(origin, v, t) = q. The Jacobian
// (3 x 4: the unnormalised direction and t) by forward differences of the
// closed form; the minimum-norm step (the radial direction of v does nothing)
// with backtracking on |error|. Returns whether |error| <= tolerance.
bool newton(glm::dvec3& v, double& t, const glm::dvec3& q, double tolerance, int max_iterations,
            double* error_out = nullptr, Residual kind = Residual::Frame) {
  glm::dvec3 e = residual(Geodesic(v).at(t).position, q, kind);
  double r = glm::length(e);
  for (int it = 0; it < max_iterations && r > tolerance; ++it) {
    const Geodesic g(v);
    double J[3][4];
    // Steps relative to each component: near the planes (a or b -> 0) the
    // period depends on log(ab), so an absolute step would leave the region
    // where the flow is linear in the component.
    for (int i = 0; i < 3; ++i) {
      glm::dvec3 vi = v;
      const double h = 1e-7 * std::abs(v[i]) + 1e-13;
      vi[i] += h;
      const glm::dvec3 ei = residual(Geodesic(vi).at(t).position, q, kind);
      for (int k = 0; k < 3; ++k) J[k][i] = (ei[k] - e[k]) / h;
    }
    {
      const double h = 1e-7 * std::max(1.0, t);
      const glm::dvec3 et = residual(g.at(t + h).position, q, kind);
      for (int k = 0; k < 3; ++k) J[k][3] = (et[k] - e[k]) / h;
    }
    double step[4];
    if (!detail::minimum_norm_step(J, e, step)) break;
    // Keep the step in a region where the linearisation can be trusted.
    const double dv = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
    double lambda = 1.0;
    if (dv > 0.5) lambda = 0.5 / dv;
    if (std::abs(step[3]) * lambda > std::max(1.0, 0.5 * t)) lambda = std::max(1.0, 0.5 * t) / std::abs(step[3]);
    bool accepted = false;
    for (int halving = 0; halving < 40; ++halving, lambda *= 0.5) {
      const glm::dvec3 v1 = v + lambda * glm::dvec3(step[0], step[1], step[2]);
      const double n1 = glm::length(v1);
      if (!(n1 > 0.0)) continue;
      const double t1 = std::max(0.0, t + lambda * step[3]);
      const glm::dvec3 vn = v1 / n1;
      glm::dvec3 e1;
      try {
        e1 = residual(Geodesic(vn).at(t1).position, q, kind);
      } catch (const OutOfRange&) {
        continue;
      }
      const double r1 = glm::length(e1);
      if (std::isfinite(r1) && r1 < r) {
        v = vn;
        t = t1;
        e = e1;
        r = r1;
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
  }
  if (error_out != nullptr) *error_out = r;
  return r <= tolerance;
}

// Newton's method for stiff directions, one of whose horizontal components
// (index `small`: 0 for a, 1 for b) is tiny: unknowns (ψ, β, t) with the
// small component e^β and the other two √(1 - e^{2β}) (cos ψ, sin ψ), so
// that relative changes of the small component are steps of β (the end
// point depends on it through log(ab)), residual in (log x, log y, z).
bool newton_stiff(glm::dvec3& v, double& t, const glm::dvec3& q, double tolerance, int max_iterations, int small,
                  double* error_out = nullptr) {
  const int big = 1 - small;
  if (!(v[small] > 0.0) || !(v[small] < 1.0)) return false;
  auto direction = [&](double psi, double beta) {
    const double e = std::exp(beta), r = std::sqrt(std::max(0.0, 1.0 - e * e));
    glm::dvec3 d;
    d[small] = e;
    d[big] = r * std::cos(psi);
    d[2] = r * std::sin(psi);
    return d;
  };
  double u[3] = {std::atan2(v[2], v[big]), std::log(v[small]), t};
  auto eval = [&](const double* w) {
    if (!(w[1] < 0.0) || !(w[2] >= 0.0)) return glm::dvec3(std::numeric_limits<double>::infinity());
    return residual(Geodesic(direction(w[0], w[1])).at(w[2]).position, q, Residual::Log);
  };
  glm::dvec3 e = eval(u);
  double r = glm::length(e);
  for (int it = 0; it < max_iterations && r > tolerance; ++it) {
    glm::dmat3 J(0.0);  // J[col][row]
    for (int i = 0; i < 3; ++i) {
      double w[3] = {u[0], u[1], u[2]};
      const double h = i == 2 ? 1e-7 * std::max(1.0, u[2]) : 1e-7 * std::max(1.0, std::abs(u[i]));
      w[i] += h;
      const glm::dvec3 ei = eval(w);
      if (!std::isfinite(glm::length(ei))) return false;
      J[i] = (ei - e) / h;
    }
    const double det = glm::determinant(J);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) break;
    const glm::dvec3 step = glm::inverse(J) * (-e);
    double lambda = 1.0;
    if (std::abs(step[0]) > 0.5) lambda = 0.5 / std::abs(step[0]);
    if (std::abs(step[1]) * lambda > 3.0) lambda = 3.0 / std::abs(step[1]);
    if (std::abs(step[2]) * lambda > std::max(1.0, 0.5 * u[2])) lambda = std::max(1.0, 0.5 * u[2]) / std::abs(step[2]);
    bool accepted = false;
    for (int halving = 0; halving < 40; ++halving, lambda *= 0.5) {
      const double w[3] = {u[0] + lambda * step[0], std::min(-1e-300, u[1] + lambda * step[1]),
                           std::max(0.0, u[2] + lambda * step[2])};
      glm::dvec3 e1;
      try {
        e1 = eval(w);
      } catch (const OutOfRange&) {
        continue;
      }
      const double r1 = glm::length(e1);
      if (std::isfinite(r1) && r1 < r) {
        for (int k = 0; k < 3; ++k) u[k] = w[k];
        e = e1;
        r = r1;
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
  }
  v = direction(u[0], u[1]);
  t = u[2];
  if (error_out != nullptr) *error_out = r;
  return r <= tolerance;
}

// The period of a direction. The closed form reports no period for the
// straight lines |a| = |b|, c = 0 (z does not move), but their neighbours
// have periods tending to 4K(0)/√2 = √2π, where the straight line stops
// minimising (docs/mathematics.md).
double period_of(const glm::dvec3& v) {
  const Geodesic g(v);
  if (std::isinf(g.period()) && v.x != 0.0 && v.y != 0.0) return std::numbers::sqrt2 * std::numbers::pi;
  return g.period();
}

// First-order error of the length t as the distance to q when the geodesic
// ends at `end` instead: the gradient of the distance at q is the unit
// tangent there, (a e^{z}, b e^{-z}, w') in the frame, so in coordinates
// ∂d/∂x = a, ∂d/∂y = b, |∂d/∂z| <= 1. Far points whose frame error cannot
// reach the tolerance (y e^{z} ~ 1e10 leaves rounding of 1e-6 in the frame)
// still have lengths exact to this estimate.
double length_error_estimate(const glm::dvec3& v, const glm::dvec3& end, const glm::dvec3& q) {
  return std::abs(v.x * (q.x - end.x)) + std::abs(v.y * (q.y - end.y)) + std::abs(q.z - end.z);
}

// Newton in (log x, log y, z), then in frame components; converged when the
// frame error is within tolerance or the length error estimate within
// 1e-12 max(1, t).
bool polish(glm::dvec3& v, double& t, const glm::dvec3& q, double tolerance) {
  newton(v, t, q, 1e-15, 6, nullptr, Residual::Log);
  if (newton(v, t, q, tolerance, 40)) return true;
  return length_error_estimate(v, Geodesic(v).at(t).position, q) <= 1e-12 * std::max(1.0, t);
}

// Homotopy from the plane solution of (X, 0, Z) (from_y_plane) or (0, Y, Z)
// to q (X, Y > 0). The plane direction is tilted off its plane by 1e-8 so
// that its end point p0 has x, y > 0; the targets run from p0 to q linearly
// in (log x, log y, z), and Newton (in those) follows the solution from the
// previous one, the step doubling on success and shrinking fourfold on
// failure; finally Newton in frame components polishes to `tolerance`.
// With `stiff` the path is followed by newton_stiff in (ψ, log of the
// tilted component, t), and polished by it before the frame polish: far
// targets reached by directions with a tiny a or b, where the plain
// iteration stalls on the path or at its end.
bool continuation(const glm::dvec3& q, bool from_y_plane, double tolerance, Solution& out, bool stiff = false) {
  Solution start;
  if (from_y_plane) {
    start = plane_solution(q.x, q.z);
    start.v.y = 1e-8;
  } else {  // the plane x = 0 is y = 0 after (x, y, z) -> (y, x, -z), frame (b, a, -c)
    start = plane_solution(q.y, -q.z);
    start.v = {1e-8, start.v.x, -start.v.z};
  }
  glm::dvec3 v = glm::normalize(start.v);
  double t = start.t;
  try {
    const glm::dvec3 p0 = Geodesic(v).at(t).position;
    if (!(p0.x > 0.0) || !(p0.y > 0.0)) return false;
    const glm::dvec3 l0(std::log(p0.x), std::log(p0.y), p0.z), l1(std::log(q.x), std::log(q.y), q.z);
    double s = 0.0, ds = 1.0;
    // Secant predictor from the previous solution on the path.
    double s_prev = -1.0, t_prev = t;
    glm::dvec3 v_prev = v;
    while (s < 1.0) {
      const double s1 = std::min(1.0, s + ds);
      const glm::dvec3 l = l0 + s1 * (l1 - l0);
      const glm::dvec3 target = s1 == 1.0 ? q : glm::dvec3(std::exp(l.x), std::exp(l.y), l.z);
      glm::dvec3 v1 = v;
      double t1 = t;
      if (s_prev >= 0.0) {
        const double f = (s1 - s) / (s - s_prev);
        v1 = glm::normalize(v + f * (v - v_prev));
        t1 = std::max(0.0, t + f * (t - t_prev));
      }
      const bool ok = stiff ? newton_stiff(v1, t1, target, 1e-6, 10, from_y_plane ? 1 : 0)
                            : newton(v1, t1, target, 1e-6, 10, nullptr, Residual::Log);
      if (ok) {
        s_prev = s;
        v_prev = v;
        t_prev = t;
        s = s1;
        v = v1;
        t = t1;
        ds *= 2.0;
        if (t > 1.01 * period_of(v)) return false;  // left the minimising branch
      } else {
        // A stall means a fold of the branch (past a conjugate point: not
        // the minimiser) or a hard path: give up, the caller tries another.
        ds *= 0.25;
        if (ds < 1e-4) return false;
      }
    }
    if (stiff) newton_stiff(v, t, q, 1e-15, 20, from_y_plane ? 1 : 0);
    if (!polish(v, t, q, tolerance)) return false;
  } catch (const OutOfRange&) {
    return false;
  }
  out.v = v;
  out.t = t;
  out.period = period_of(v);
  return true;
}

bool minimising(const Solution& s, double tolerance) { return s.t <= s.period * (1.0 + 1e-9) + tolerance; }

// Length t_x with x(t_x) = X along g (x is strictly increasing when a > 0);
// false when x(t_max) < X.
bool time_to_x(const Geodesic& g, double X, double t_max, double& t_out) {
  double lo = 0.0, hi = std::min(1.0, t_max);
  while (g.at(hi).position.x < X) {
    if (hi >= t_max) return false;
    lo = hi;
    hi = std::min(2.0 * hi, t_max);
  }
  double t = 0.5 * (lo + hi);
  for (int it = 0; it < 80; ++it) {
    const Geodesic::State s = g.at(t);
    const double f = s.position.x - X;
    if (f > 0.0) {
      hi = t;
    } else {
      lo = t;
    }
    if (std::abs(f) <= 1e-15 * X || hi - lo <= 1e-14 * hi) break;
    const double slope = std::exp(s.position.z) * s.direction.x;  // x' = e^{z} u1
    double next = t - f / slope;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
  }
  t_out = t;
  return true;
}

void add_unique(std::vector<Solution>& list, const Solution& s) {
  for (const Solution& o : list) {
    if (glm::length(o.v - s.v) < 1e-7 && std::abs(o.t - s.t) < 1e-7 * std::max(1.0, s.t)) return;
  }
  list.push_back(s);
}

// The scan of connection.hpp: local minima of |F| over a grid of directions,
// polished by Newton; every connection found no longer than t_max.
std::vector<Solution> scan(const glm::dvec3& q, double t_max, double tolerance, int n_polar, int n_azimuth) {
  const int np = n_polar, na = n_azimuth;
  std::vector<double> norm(static_cast<std::size_t>(np * na), std::numeric_limits<double>::infinity());
  std::vector<glm::dvec3> dirs(norm.size());
  std::vector<double> times(norm.size(), 0.0);
  for (int i = 0; i < np; ++i) {
    const double theta = std::numbers::pi * (i + 0.5) / np;
    for (int j = 0; j < na; ++j) {
      const double phi = 0.5 * std::numbers::pi * (j + 0.5) / na;
      const std::size_t k = static_cast<std::size_t>(i * na + j);
      dirs[k] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      try {
        const Geodesic g(dirs[k]);
        double t = 0.0;
        if (!time_to_x(g, q.x, t_max * 1.05 + 0.1, t)) continue;
        const glm::dvec3 end = g.at(t).position;
        const double fy = (q.y - end.y) * std::exp(end.z), fz = q.z - end.z;
        norm[k] = std::hypot(fy, fz);
        times[k] = t;
      } catch (const OutOfRange&) {
      }
    }
  }
  std::vector<Solution> found;
  for (int i = 0; i < np; ++i) {
    for (int j = 0; j < na; ++j) {
      const std::size_t k = static_cast<std::size_t>(i * na + j);
      if (!std::isfinite(norm[k])) continue;
      bool minimum = true;
      for (int di = -1; di <= 1 && minimum; ++di) {
        for (int dj = -1; dj <= 1; ++dj) {
          const int ii = i + di, jj = j + dj;
          if ((di == 0 && dj == 0) || ii < 0 || ii >= np || jj < 0 || jj >= na) continue;
          if (norm[static_cast<std::size_t>(ii * na + jj)] < norm[k]) {
            minimum = false;
            break;
          }
        }
      }
      if (!minimum) continue;
      Solution s;
      s.v = dirs[k];
      s.t = times[k];
      try {
        if (!polish(s.v, s.t, q, tolerance)) continue;
      } catch (const OutOfRange&) {
        continue;
      }
      if (s.v.x <= 0.0 || s.v.y <= 0.0 || s.t > t_max + tolerance) continue;
      s.period = period_of(s.v);
      add_unique(found, s);
    }
  }
  return found;
}

// The warm starts of a detail::WarmSolves scope (warm_solves.hpp), per
// thread: the last reduced target answered and its answer, and the last
// general solution.
struct WarmState {
  bool open = false;
  bool answered = false;
  glm::dvec3 answered_q{0.0};
  double answered_tolerance = 0.0;
  std::vector<Solution> answer;
  bool solved = false;
  glm::dvec3 solved_q{0.0};
  Solution solution;
};
thread_local WarmState t_warm;

// How far (coordinates) a target may move from the last solution's for
// Newton to start from that solution: a march's steps are shorter.
constexpr double kWarmReach = 1.0;

// The minimisers from the origin to q (X, Y > 0): see connection.hpp.
std::vector<Solution> general_minimisers(const glm::dvec3& q, const ConnectionOptions& options) {
  const double tolerance = std::max(options.tolerance, rounding_floor(q));
  std::vector<Solution> out;
  // Start from the plane whose neglected displacement is cheaper.
  const bool y_first = q.y * std::exp(q.z) <= q.x * std::exp(-q.z);
  Solution best;
  bool have = false;
  // In a WarmSolves scope: from the last solution, in frame components.
  if (t_warm.open && t_warm.solved && glm::length(q - t_warm.solved_q) < kWarmReach) {
    Solution s = t_warm.solution;
    try {
      if (newton(s.v, s.t, q, tolerance, 8) && s.v.x > 0.0 && s.v.y > 0.0) {
        s.period = period_of(s.v);
        if (minimising(s, tolerance)) {
          best = s;
          have = true;
        }
      }
    } catch (const OutOfRange&) {
    }
  }
  // Points up to |q| = 6: the Euclidean guess (direction q, length |q|) is often in
  // the basin of Newton; the certificate t <= T decides whether it is kept.
  if (!have && glm::length(q) < 6.0) {
    Solution s;
    s.v = glm::normalize(q);
    s.t = glm::length(q);
    try {
      if (newton(s.v, s.t, q, 1e-9, 12, nullptr, Residual::Log) && polish(s.v, s.t, q, tolerance) &&
          s.v.x > 0.0 && s.v.y > 0.0) {
        s.period = period_of(s.v);
        if (minimising(s, tolerance)) {
          best = s;
          have = true;
        }
      }
    } catch (const OutOfRange&) {
    }
  }
  // Near the cut locus (z' ~ 0, large x'y') a branch may arrive just past its
  // period; the minimiser is then next to its mirror (a, b, -c), which meets
  // it on the cut locus: try that seed.
  auto try_mirror = [&](const Solution& s) {
    if (have || minimising(s, tolerance)) return;
    Solution m = s;
    m.v.z = -m.v.z;
    try {
      if (polish(m.v, m.t, q, tolerance) && m.v.x > 0.0 && m.v.y > 0.0) {
        m.period = period_of(m.v);
        if (minimising(m, tolerance)) {
          best = m;
          have = true;
        }
      }
    } catch (const OutOfRange&) {
    }
  };
  for (int side = 0; side < 2 && !have; ++side) {
    Solution s;
    if (continuation(q, side == 0 ? y_first : !y_first, tolerance, s)) {
      if (minimising(s, tolerance)) {
        best = s;
        have = true;
      } else {
        try_mirror(s);
      }
    }
  }
  // Stiff targets (far, near a plane): the same two paths in the stiff
  // parametrisation; tried only after the plain ones, so other targets pay nothing.
  for (int side = 0; side < 2 && !have; ++side) {
    Solution s;
    if (continuation(q, side == 0 ? y_first : !y_first, tolerance, s, true)) {
      if (minimising(s, tolerance)) {
        best = s;
        have = true;
      } else {
        try_mirror(s);
      }
    }
  }
  if (!have) {
    // The scan up to the length of a path that certainly arrives (lower
    // bound of the lengths of the two-plane path: (X,0,Z)-plane then y).
    const double bound = plane_solution(q.x, q.z).t + std::asinh(q.y * std::exp(q.z)) * 2.0 + 1.0;
    const int np = std::max(4, options.scan_polar), na = std::max(2, options.scan_azimuth);
    const std::vector<Solution> found = scan(q, bound, tolerance, np, na);
    for (const Solution& s : found) {
      if (minimising(s, tolerance) && (!have || s.t < best.t)) {
        best = s;
        have = true;
      }
    }
    for (const Solution& s : found) try_mirror(s);
  }
  if (!have) {
    throw OutOfRange("sol::distance: no minimising geodesic found to (" + std::to_string(q.x) + ", " +
                     std::to_string(q.y) + ", " + std::to_string(q.z) + ") from the origin");
  }
  out.push_back(best);
  if (t_warm.open) {
    t_warm.solved = true;
    t_warm.solved_q = q;
    t_warm.solution = best;
  }
  // On the cut locus (t = T) the mirror (a, b, -c) arrives too, at the same length.
  if (std::abs(best.t - best.period) <= 1e-7 * best.period && std::abs(best.v.z) > 1e-9) {
    Solution mirror = best;
    mirror.v.z = -mirror.v.z;
    if (polish(mirror.v, mirror.t, q, tolerance) && std::abs(mirror.t - best.t) <= 1e-9 * std::max(1.0, best.t)) {
      mirror.period = period_of(mirror.v);
      add_unique(out, mirror);
    }
  }
  return out;
}

void validate(const glm::dvec3& p, const glm::dvec3& q, const ConnectionOptions& options, const char* function) {
  detail::require_finite(p, function, "p");
  detail::require_finite(q, function, "q");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    throw InvalidArgument(std::string(function) + ": ConnectionOptions::tolerance must be finite and > 0");
  }
  if (options.scan_polar < 4 || options.scan_azimuth < 2) {
    throw InvalidArgument(std::string(function) + ": ConnectionOptions::scan_polar must be >= 4 and scan_azimuth >= 2");
  }
}

std::vector<Solution> reduced_minimisers_of(const glm::dvec3& q, const ConnectionOptions& options);

// Minimisers of the reduced problem, in the reduced frame; degenerate
// cases exact. In a WarmSolves scope a repeated target takes the last answer.
std::vector<Solution> reduced_minimisers(const glm::dvec3& q, const ConnectionOptions& options) {
  // (Answers are kept for the default scan only: its options then differ in the tolerance alone.)
  const bool plain = options.scan_polar == ConnectionOptions{}.scan_polar &&
                     options.scan_azimuth == ConnectionOptions{}.scan_azimuth;
  if (!t_warm.open || !plain) return reduced_minimisers_of(q, options);
  if (t_warm.answered && q == t_warm.answered_q && options.tolerance == t_warm.answered_tolerance) return t_warm.answer;
  t_warm.answer = reduced_minimisers_of(q, options);
  t_warm.answered = true;
  t_warm.answered_q = q;
  t_warm.answered_tolerance = options.tolerance;
  return t_warm.answer;
}

std::vector<Solution> reduced_minimisers_of(const glm::dvec3& q, const ConnectionOptions& options) {
  if (q.x == 0.0 && q.y == 0.0) {
    Solution s;
    s.v = {0.0, 0.0, q.z < 0.0 ? -1.0 : 1.0};
    s.t = std::abs(q.z);
    return {s};
  }
  if (q.y == 0.0) return {plane_solution(q.x, q.z)};
  const double mid = 0.5 * (q.x + q.y);
  if (std::abs(q.z) + std::abs(q.x - q.y) <= 1e-13 * std::max(1.0, mid) && mid <= std::numbers::pi * (1.0 + 1e-13)) {
    // The straight line (t/√2, t/√2, 0) minimises up to its period √2π, its
    // end point included (there it is conjugate: Newton would be singular).
    // Within 1e-13 of it the straight line's length is the distance to
    // first order (length_error_estimate below 1e-13).
    Solution s;
    s.v = {std::numbers::sqrt2 / 2.0, std::numbers::sqrt2 / 2.0, 0.0};
    s.t = std::numbers::sqrt2 * mid;
    s.period = std::numbers::sqrt2 * std::numbers::pi;
    return {s};
  }
  if (q.x == 0.0) {
    Solution s = plane_solution(q.y, -q.z);
    s.v = {s.v.y, s.v.x, -s.v.z};
    return {s};
  }
  return general_minimisers(q, options);
}

std::vector<Connection> to_connections(const std::vector<Solution>& list, const Reduction& r, const char* function) {
  std::vector<Connection> out;
  out.reserve(list.size());
  for (const Solution& s : list) {
    out.push_back({r.unreduce(s.v), s.t});
    if (!std::isfinite(s.t)) {
      throw OutOfRange(std::string(function) + ": q is too far from p for double (the length overflows)");
    }
    detail::finite_result(out.back().direction, function, "the direction to q");
  }
  return out;
}

}  // namespace

double distance(const glm::dvec3& p, const glm::dvec3& q, const ConnectionOptions& options) {
  validate(p, q, options, "sol::distance");
  const double d = reduced_minimisers(reduce(p, q).q, options).front().t;
  if (!std::isfinite(d)) throw OutOfRange("sol::distance: q is too far from p for double (the length overflows)");
  return d;
}

glm::dvec3 log_series(const glm::dvec3& w) {
  detail::require_finite(w, "sol::log_series", "w");
  if (!(glm::length(w) < kernel::kLogSeriesReach)) {
    throw InvalidArgument("sol::log_series: |w| = " + std::to_string(glm::length(w)) + " is not below the series' reach " +
                          std::to_string(kernel::kLogSeriesReach));
  }
  return detail::log_series_at(w);
}

double distance(const glm::dvec3& p, const glm::dvec3& q) { return distance(p, q, ConnectionOptions{}); }

namespace detail {

WarmSolves::WarmSolves() : m_outer(t_warm.open) {
  if (!m_outer) t_warm = WarmState{.open = true};
}

WarmSolves::~WarmSolves() {
  if (!m_outer) t_warm = WarmState{};
}

}  // namespace detail

std::vector<Connection> minimising_geodesics(const glm::dvec3& p, const glm::dvec3& q,
                                             const ConnectionOptions& options) {
  validate(p, q, options, "sol::minimising_geodesics");
  const Reduction r = reduce(p, q);
  return to_connections(reduced_minimisers(r.q, options), r, "sol::minimising_geodesics");
}

std::vector<Connection> geodesics_between(const glm::dvec3& p, const glm::dvec3& q, double max_length,
                                          const ConnectionOptions& options) {
  constexpr const char* function = "sol::geodesics_between";
  validate(p, q, options, function);
  detail::require_finite(max_length, function, "max_length");
  if (max_length < 0.0) throw InvalidArgument(std::string(function) + ": argument 'max_length' is negative");
  const Reduction r = reduce(p, q);
  std::vector<Solution> list = reduced_minimisers(r.q, options);
  const double d = list.front().t;
  const double tolerance = std::max(options.tolerance, rounding_floor(r.q));
  if (max_length < d - tolerance) return {};
  // Only the general case has more than one connection (connection.hpp).
  if (r.q.x > 0.0 && r.q.y > 0.0 && max_length > d) {
    for (const Solution& s : scan(r.q, max_length, tolerance, options.scan_polar, options.scan_azimuth)) {
      add_unique(list, s);
    }
  }
  std::erase_if(list, [&](const Solution& s) { return s.t > max_length + tolerance; });
  std::stable_sort(list.begin(), list.end(), [](const Solution& a, const Solution& b) { return a.t < b.t; });
  return to_connections(list, r, function);
}

std::vector<Connection> geodesics_between(const glm::dvec3& p, const glm::dvec3& q, double max_length) {
  return geodesics_between(p, q, max_length, ConnectionOptions{});
}

ConnectionTable ConnectionTable::build(bool longer, unsigned threads) {
  constexpr int n = kCellsXY + 1, nz = kCellsZ + 1;
  // The connections from the origin to every node.
  std::vector<std::vector<Connection>> nodes(static_cast<std::size_t>(n * n * nz));
  std::atomic<int> next{0}, failed{0};
  auto work = [&] {
    for (int node = next++; node < n * n * nz; node = next++) {
      const int i = node % n, j = (node / n) % n, k = node / (n * n);
      const glm::dvec3 w(std::sinh(i * kStep), std::sinh(j * kStep), -kHeight + k * kStep);
      if (w == glm::dvec3(0.0)) continue;
      try {
        std::vector<Connection> cs = minimising_geodesics({0, 0, 0}, w);
        if (longer) {
          ConnectionOptions o;
          // Coarser than the default scan: the kernel polishes these seeds,
          // and a cell takes the seeds of all its corners (test
          // vk.Kernel.ConnectionsUpToAReach measures what is found).
          o.scan_polar = 32;
          o.scan_azimuth = 16;
          cs = geodesics_between({0, 0, 0}, w, cs.front().length + kReach + kMargin, o);
        }
        nodes[static_cast<std::size_t>(node)] = std::move(cs);
      } catch (const OutOfRange&) {
        ++failed;
      }
    }
  };
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < threads; ++k) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();

  // Each cell's seeds: the union of its corners' connections.
  ConnectionTable t;
  t.failed_nodes = failed.load();
  t.seeds.assign(static_cast<std::size_t>(kCellsXY * kCellsXY * kCellsZ * kSlots * 4), 0.0f);
  for (int k = 0; k < kCellsZ; ++k) {
    for (int j = 0; j < kCellsXY; ++j) {
      for (int i = 0; i < kCellsXY; ++i) {
        std::vector<Connection> cell;
        for (int corner = 0; corner < 8; ++corner) {
          const int a = i + (corner & 1), b = j + ((corner >> 1) & 1), c = k + ((corner >> 2) & 1);
          for (const Connection& con : nodes[static_cast<std::size_t>((c * n + b) * n + a)]) {
            const glm::dvec3 v = con.length * glm::normalize(con.direction);
            const bool seen = std::any_of(cell.begin(), cell.end(), [&](const Connection& o) {
              return glm::length(o.length * glm::normalize(o.direction) - v) < kMerge * std::max(1.0, con.length);
            });
            if (!seen) cell.push_back(con);
          }
        }
        std::stable_sort(cell.begin(), cell.end(), [](const Connection& x, const Connection& y) { return x.length < y.length; });
        if (cell.size() > static_cast<std::size_t>(kSlots)) {
          ++t.overflow_cells;
          cell.resize(kSlots);
        }
        const std::size_t base = static_cast<std::size_t>(((k * kCellsXY + j) * kCellsXY + i) * kSlots) * 4;
        for (std::size_t s = 0; s < cell.size(); ++s) {
          const glm::dvec3 d = glm::normalize(cell[s].direction);
          for (int c = 0; c < 3; ++c) t.seeds[base + 4 * s + static_cast<std::size_t>(c)] = static_cast<float>(d[c]);
          t.seeds[base + 4 * s + 3] = static_cast<float>(cell[s].length);
        }
      }
    }
  }
  return t;
}

const ConnectionTable& ConnectionTable::shared(bool longer) {
  if (longer) {
    static const ConnectionTable table = build(true);
    return table;
  }
  static const ConnectionTable table = build(false);
  return table;
}

double sdf_ball_exact(const glm::dvec3& q, const glm::dvec3& center, double radius, double band) {
  const double bound = distance_lower_bound(q, center) - radius;
  if (bound > band) return bound;
  try {
    // (From the centre, as sdf_ball_exact_gradient and the renderer's
    // clearances: one problem, which a WarmSolves scope answers once.)
    return distance(center, q) - radius;
  } catch (const OutOfRange&) {
    return bound;
  }
}

glm::dvec3 sdf_ball_exact_gradient(const glm::dvec3& q, const glm::dvec3& center) {
  const std::vector<Connection> cs = minimising_geodesics(center, q);
  if (cs.front().length == 0.0) return {0.0, 0.0, 1.0};
  return glm::normalize(Geodesic(cs.front().direction).direction_at(cs.front().length));
}

}  // namespace sol
