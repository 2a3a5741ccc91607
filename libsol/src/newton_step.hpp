// Newton's minimum-norm step for three equations in four unknowns
// (libsol-internal): the connection solver's (a direction, unnormalised,
// and the length) and the sphere exit's (the direction from the centre and
// the arc length), where the direction's radial component does nothing.
#pragma once

#include <cmath>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

namespace sol::detail {

/// The least-norm `step` with J step = −e: step = Jᵀ (J Jᵀ)⁻¹ (−e). False
/// where J Jᵀ is singular or not finite.
inline bool minimum_norm_step(const double (&J)[3][4], const glm::dvec3& e, double (&step)[4]) {
  glm::dmat3 m(0.0);  // J Jᵀ (symmetric)
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) sum += J[row][j] * J[col][j];
      m[col][row] = sum;
    }
  }
  const double det = glm::determinant(m);
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  const glm::dvec3 y = glm::inverse(m) * (-e);
  for (int j = 0; j < 4; ++j) step[j] = J[0][j] * y[0] + J[1][j] * y[1] + J[2][j] * y[2];
  return true;
}

}  // namespace sol::detail
