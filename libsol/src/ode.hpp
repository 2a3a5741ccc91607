// Explicit Runge–Kutta integrators for libsol's small ODE systems (not installed).
//
// Both integrate y' = f(y) (autonomous) from s = 0 to s = t, t of either sign.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>

#include "sol/error.hpp"

namespace sol::detail {

/// The most steps either integrator takes: about a second of work for these
/// small systems on one core (RK4's count is known before the first step,
/// Dormand–Prince's is counted as it goes). Beyond it, OutOfRange naming
/// the caller: an arc length that would take minutes, or never end, is
/// refused rather than followed.
inline constexpr long long kMaxRk4Steps = 10'000'000;
inline constexpr long long kMaxDormandPrinceSteps = 1'000'000;

[[noreturn]] inline void too_many_steps(const char* function, long long limit, double t) {
  char text[160];
  std::snprintf(text, sizeof text, ": t = %g needs more than %lld integration steps; shorten t", t, limit);
  throw OutOfRange(function + std::string(text));
}

template <std::size_t N>
using State = std::array<double, N>;

template <std::size_t N>
inline State<N> axpy(const State<N>& y, double h, const State<N>& k) {
  State<N> r;
  for (std::size_t i = 0; i < N; ++i) r[i] = y[i] + h * k[i];
  return r;
}

/// Classical RK4 with ceil(|t| / max_step) equal steps (at most kMaxRk4Steps,
/// else OutOfRange naming `function`).
template <std::size_t N, class F>
State<N> integrate_rk4(const F& f, State<N> y, double t, double max_step, const char* function) {
  if (t == 0.0) return y;
  const double steps = std::max(1.0, std::ceil(std::abs(t) / max_step));
  if (!(steps <= static_cast<double>(kMaxRk4Steps))) too_many_steps(function, kMaxRk4Steps, t);
  const auto n = static_cast<long long>(steps);
  const double h = t / steps;
  for (long long step = 0; step < n; ++step) {
    const State<N> k1 = f(y);
    const State<N> k2 = f(axpy(y, 0.5 * h, k1));
    const State<N> k3 = f(axpy(y, 0.5 * h, k2));
    const State<N> k4 = f(axpy(y, h, k3));
    for (std::size_t i = 0; i < N; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  return y;
}

/// Adaptive Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, Solving ODE I,
/// Table 5.2), local extrapolation, FSAL. The error of each step is measured
/// as max_i |err_i| / (tolerance * (absolute_i + max(|y_i|, |y_new_i|))):
/// absolute_i = 1 gives mixed control (absolute for small components,
/// relative for large ones, as x grows like e^{2z}); absolute_i = 0 gives
/// purely relative control, needed for components such as u1 = a e^{z} that
/// decay exponentially but whose relative value carries the geodesic. At
/// most kMaxDormandPrinceSteps trial steps, else OutOfRange naming
/// `function` (also where a step no longer advances s: |t| beyond 2^53
/// steps' worth of rounding).
template <std::size_t N, class F>
State<N> integrate_dormand_prince(const F& f, State<N> y, double t, double tolerance, const State<N>& absolute,
                                  const char* function) {
  if (t == 0.0) return y;
  constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
  constexpr double a21 = 1.0 / 5;
  constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
  constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
  constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                   a54 = -212.0 / 729;
  constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                   a64 = 49.0 / 176, a65 = -5103.0 / 18656;
  constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784,
                   b6 = 11.0 / 84;
  // e_i = b_i - b*_i (difference between the 5th- and 4th-order weights).
  constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920,
                   e5 = -17253.0 / 339200, e6 = 22.0 / 525, e7 = -1.0 / 40;
  (void)c2; (void)c3; (void)c4; (void)c5;

  const double direction = t > 0 ? 1.0 : -1.0;
  const double length = std::abs(t);
  double done = 0.0;
  // Initial step: a 5th-order method with local error ~ h^5 meets the tolerance near h = tol^{1/5}.
  double h = std::min(length, 0.5 * std::pow(tolerance, 0.2));
  State<N> k1 = f(y);
  for (long long trials = 0; done < length; ++trials) {
    if (trials == kMaxDormandPrinceSteps) too_many_steps(function, kMaxDormandPrinceSteps, t);
    if (done + h >= length) h = length - done;
    const double hs = direction * h;
    State<N> tmp;
    for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + hs * a21 * k1[i];
    const State<N> k2 = f(tmp);
    for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + hs * (a31 * k1[i] + a32 * k2[i]);
    const State<N> k3 = f(tmp);
    for (std::size_t i = 0; i < N; ++i) tmp[i] = y[i] + hs * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    const State<N> k4 = f(tmp);
    for (std::size_t i = 0; i < N; ++i)
      tmp[i] = y[i] + hs * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    const State<N> k5 = f(tmp);
    for (std::size_t i = 0; i < N; ++i)
      tmp[i] = y[i] + hs * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    const State<N> k6 = f(tmp);
    State<N> next;
    for (std::size_t i = 0; i < N; ++i)
      next[i] = y[i] + hs * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
    const State<N> k7 = f(next);
    double error = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
      const double err = hs * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      const double scale = tolerance * (absolute[i] + std::max(std::abs(y[i]), std::abs(next[i])));
      if (err != 0.0) error = std::max(error, std::abs(err) / scale);
    }
    if (!std::isfinite(error)) error = 1e10;  // overflow in a trial step: shrink
    if (error <= 1.0) {
      if (done + h == done) too_many_steps(function, kMaxDormandPrinceSteps, t);  // s no longer advances
      done += h;
      y = next;
      k1 = k7;  // first same as last
    }
    // Standard controller: safety 0.9, growth limited to [0.2, 5].
    const double factor = error == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(error, -0.2), 0.2, 5.0);
    h *= factor;
    if (h < 1e-300) break;  // cannot make progress (overflow); the caller checks finiteness
  }
  return y;
}

}  // namespace sol::detail
