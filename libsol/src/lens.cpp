#include "sol/lens.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "sol/closed_form.hpp"
#include "sol/error.hpp"
#include "sol/group.hpp"

namespace sol {
namespace {

double radical_inverse(int k, int base) {
  double inverse = 1.0 / base, result = 0.0, digit = inverse;
  for (int n = k; n > 0; n /= base) {
    result += (n % base) * digit;
    digit *= inverse;
  }
  return result;
}

// Shirley and Chiu's concentric map of [0, 1)² onto the unit disk.
glm::dvec2 concentric(double u, double v) {
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  if (a == 0.0 && b == 0.0) return {0.0, 0.0};
  constexpr double quarter = 0.25 * std::numbers::pi;
  const bool wide = std::abs(a) > std::abs(b);
  const double r = wide ? a : b;
  const double phi = wide ? quarter * (b / a) : 2.0 * quarter - quarter * (a / b);
  return {r * std::cos(phi), r * std::sin(phi)};
}

}  // namespace

glm::dvec2 lens_sample(int k) {
  if (k < 0) throw InvalidArgument("sol::lens_sample: k must be >= 0, got " + std::to_string(k));
  if (k == 0) return {0.0, 0.0};
  return concentric(radical_inverse(k, 2), radical_inverse(k, 3));
}

glm::dvec3 exp_map(const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!(length > 0.0)) return glm::dvec3(0.0);
  return ClosedFormGeodesic<double>(v / length).at(length).position;
}

LensRay lens_ray(const Camera& camera, const glm::dvec3& direction, const glm::dvec2& disk) {
  LensRay ray{glm::dvec3(0.0), direction, camera.focus_distance, true};
  if (camera.aperture == 0.0 || (disk.x == 0.0 && disk.y == 0.0)) return ray;
  const CameraBasis basis = camera_basis(camera);
  ray.start = exp_map(camera.aperture * (disk.x * basis.right + disk.y * basis.up));
  // The focus point seen from the lens point, and Newton's method for
  // exp(v) = target from the pixel ray's f u (its Jacobian by central
  // differences, good to about 1e-10 relative: enough for quadratic
  // convergence to the rounding of exp).
  const glm::dvec3 target = multiply(inverse(ray.start), exp_map(camera.focus_distance * direction));
  const double scale = std::max(1.0, glm::length(target));
  glm::dvec3 v = camera.focus_distance * direction;
  for (int iteration = 0; iteration < 16; ++iteration) {
    const glm::dvec3 residual = target - exp_map(v);
    if (glm::length(residual) <= 1e-12 * scale) {
      ray.direction = glm::normalize(v);
      ray.focus_length = glm::length(v);
      return ray;
    }
    const double h = 1e-6 * std::max(1.0, glm::length(v));
    glm::dmat3 jacobian;
    for (int i = 0; i < 3; ++i) {
      glm::dvec3 e(0.0);
      e[i] = h;
      jacobian[i] = (exp_map(v + e) - exp_map(v - e)) / (2.0 * h);
    }
    const double det = glm::determinant(jacobian);
    if (!(std::abs(det) > 1e-12)) break;
    const glm::dvec3 step = glm::inverse(jacobian) * residual;
    // A step beyond the lens's reach leaves the pixel ray's bundle.
    if (!(glm::length(step) <= 0.5 * glm::length(v) + 2.0 * camera.aperture)) break;
    v += step;
  }
  ray.direction = direction;
  ray.focused = false;
  return ray;
}

}  // namespace sol
