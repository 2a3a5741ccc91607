#include "sphere_exit.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "sol/error.hpp"
#include "sol/group.hpp"
#include "log_series_at.hpp"
#include "newton_step.hpp"

namespace sol::detail {
namespace {

using Geodesic = ClosedFormGeodesic<double>;

// The residual of (w, s): the sphere's point exp(level ŵ) seen from the
// ray's point p in the frame at the sphere's point (the group difference,
// whose norm is their distance to first order), and its derivative in s.
struct Residual {
  glm::dvec3 e{0.0};
  glm::dvec3 de_ds{0.0};
  glm::dvec3 end_direction{0.0};  // the geodesic from the centre's tangent at its end
  glm::dvec3 ray_direction{0.0};
};

Residual residual(const glm::dvec3& w, double s, double level, const glm::dvec3& base, const Geodesic& ray) {
  const Geodesic::State end = Geodesic(glm::normalize(w)).at(level);
  const Geodesic::State at = ray.at(s);
  const glm::dvec3 p = multiply(base, at.position), E = end.position;
  const double ex = std::exp(-E.z), ey = std::exp(E.z);
  Residual r;
  r.e = {(p.x - E.x) * ex, (p.y - E.y) * ey, p.z - E.z};
  // dp/ds in coordinates is (e^{z} u1, e^{-z} u2, u3), u the frame tangent.
  const glm::dvec3& u = at.direction;
  r.de_ds = {std::exp(p.z) * u.x * ex, std::exp(-p.z) * u.y * ey, u.z};
  r.end_direction = end.direction;
  r.ray_direction = u;
  return r;
}

// J += (y − J d) dᵀ / dᵀd (Broyden's rule), J 3 x 4 over (w, s).
void broyden(double (&J)[3][4], const double (&d)[4], const glm::dvec3& y) {
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3];
  if (!(dd > 0.0)) return;
  for (int k = 0; k < 3; ++k) {
    const double u = (y[k] - (J[k][0] * d[0] + J[k][1] * d[1] + J[k][2] * d[2] + J[k][3] * d[3])) / dd;
    for (int j = 0; j < 4; ++j) J[k][j] += u * d[j];
  }
}

constexpr int kMostIterations = 16;
constexpr double kTolerance = 1e-12;

}  // namespace

std::optional<SphereExit> sphere_exit(const glm::dvec3& centre, double level, const glm::dvec3& from,
                                      const ClosedFormGeodesic<double>& ray, double s0, double limit) {
  try {
    const glm::dvec3 base = multiply(inverse(centre), from);  // the ray's start seen from the centre
    double s = std::clamp(s0, 0.0, limit);
    const glm::dvec3 p0 = multiply(base, ray.at(s).position);
    // The start: the logarithm's series at the ray's point at s0 (a guess
    // beyond its reach too: it need only fall in Newton's basin).
    glm::dvec3 w = log_series_at(p0);
    if (!(glm::length(w) > 0.0) || !std::isfinite(glm::length(w))) w = p0;
    if (!(glm::length(w) > 0.0)) return std::nullopt;
    w = glm::normalize(w);
    Residual r = residual(w, s, level, base, ray);
    double norm = glm::length(r.e);
    double J[3][4] = {};
    bool fresh = false;  // whether J holds differences (else Broyden's updates of them)
    bool have = false;
    for (int it = 0; it < kMostIterations && norm > kTolerance; ++it) {
      if (!have) {
        // The w columns by forward differences (ŵ's radial direction does
        // nothing); the s column exact.
        for (int i = 0; i < 3; ++i) {
          glm::dvec3 wi = w;
          const double h = 1e-7 * std::abs(w[i]) + 1e-9;
          wi[i] += h;
          const glm::dvec3 ei = residual(wi, s, level, base, ray).e;
          for (int k = 0; k < 3; ++k) J[k][i] = (ei[k] - r.e[k]) / h;
        }
        have = fresh = true;
      }
      for (int k = 0; k < 3; ++k) J[k][3] = r.de_ds[k];
      double step[4];
      if (!minimum_norm_step(J, r.e, step)) {  // (J Jᵀ singular)
        if (fresh) return std::nullopt;
        have = false;
        continue;
      }
      // Trusted region: w by at most 0.5, s by at most half the level.
      double lambda = 1.0;
      const double dw = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
      if (dw > 0.5) lambda = 0.5 / dw;
      if (std::abs(step[3]) * lambda > 0.5 * level) lambda = 0.5 * level / std::abs(step[3]);
      bool accepted = false;
      // Broyden's Jacobian gets one trial, which must halve |e|; differences
      // get backtracking.
      for (int halving = 0; halving < (fresh ? 30 : 1); ++halving, lambda *= 0.5) {
        const glm::dvec3 w1 = glm::normalize(w + lambda * glm::dvec3(step[0], step[1], step[2]));
        const double s1 = std::clamp(s + lambda * step[3], 0.0, limit);
        const Residual r1 = residual(w1, s1, level, base, ray);
        const double norm1 = glm::length(r1.e);
        if (!(std::isfinite(norm1) && norm1 < (fresh ? norm : 0.5 * norm))) continue;
        const double d[4] = {w1.x - w.x, w1.y - w.y, w1.z - w.z, s1 - s};
        broyden(J, d, r1.e - r.e);
        w = w1;
        s = s1;
        r = r1;
        norm = norm1;
        accepted = true;
        break;
      }
      if (!accepted && fresh) return std::nullopt;
      fresh = false;
      if (!accepted) {  // differences again (this try not counted)
        have = false;
        --it;
      }
    }
    if (!(norm <= kTolerance)) return std::nullopt;
    if (!(s > 0.0 && s <= limit) || !(glm::dot(r.end_direction, r.ray_direction) > 0.0)) return std::nullopt;
    return SphereExit{s, r.end_direction, r.ray_direction};
  } catch (const OutOfRange&) {
    return std::nullopt;
  }
}

}  // namespace sol::detail
