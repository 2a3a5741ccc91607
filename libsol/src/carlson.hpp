// Carlson's symmetric elliptic integrals R_F and R_D (not installed).
//
// B. C. Carlson, "Numerical computation of real or complex elliptic
// integrals", Numerical Algorithms 10 (1995) 13–26, Algorithms 1 and 4;
// DLMF §19.36(i). Duplication until the arguments agree to the precision of
// T, then a fifth-order Taylor series. Arguments must be >= 0 with at most
// one zero (R_F) / x + y > 0 and z > 0 (R_D); square roots only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace sol::detail {

template <class T>
T carlson_rf(T x, T y, T z) {
  const T a0 = (x + y + z) / T(3);
  // Stop when 4^{-n} Q < |A_n|: Q = (3 eps)^{-1/6} max|A0 - arg| (Carlson 1995 eq. 2.2).
  T q = std::pow(T(3) * std::numeric_limits<T>::epsilon(), T(-1) / T(6)) *
        std::max({std::abs(a0 - x), std::abs(a0 - y), std::abs(a0 - z)});
  T a = a0;
  T scale = T(1);  // 4^{-n}
  while (q * scale >= std::abs(a)) {
    const T sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const T lambda = sx * sy + sy * sz + sz * sx;
    x = (x + lambda) / T(4);
    y = (y + lambda) / T(4);
    z = (z + lambda) / T(4);
    a = (a + lambda) / T(4);
    scale /= T(4);
  }
  // X = (A0 - x0) 4^{-n} / A_n equals 1 - x_n / A_n.
  const T X = T(1) - x / a, Y = T(1) - y / a, Z = -(X + Y);
  const T e2 = X * Y - Z * Z, e3 = X * Y * Z;
  return (T(1) - e2 / T(10) + e3 / T(14) + e2 * e2 / T(24) - T(3) * e2 * e3 / T(44)) / std::sqrt(a);
}

template <class T>
T carlson_rd(T x, T y, T z) {
  const T a0 = (x + y + T(3) * z) / T(5);
  T q = std::pow(std::numeric_limits<T>::epsilon() / T(4), T(-1) / T(6)) *
        std::max({std::abs(a0 - x), std::abs(a0 - y), std::abs(a0 - z)});
  T a = a0;
  T scale = T(1);  // 4^{-n}
  T sum = T(0);
  while (q * scale >= std::abs(a)) {
    const T sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const T lambda = sx * sy + sy * sz + sz * sx;
    sum += scale / (sz * (z + lambda));
    x = (x + lambda) / T(4);
    y = (y + lambda) / T(4);
    z = (z + lambda) / T(4);
    a = (a + lambda) / T(4);
    scale /= T(4);
  }
  const T X = T(1) - x / a, Y = T(1) - y / a, Z = -(X + Y) / T(3);
  const T xy = X * Y, z2 = Z * Z;
  const T e2 = xy - T(6) * z2, e3 = (T(3) * xy - T(8) * z2) * Z, e4 = T(3) * (xy - z2) * z2, e5 = xy * z2 * Z;
  const T series = T(1) - T(3) * e2 / T(14) + e3 / T(6) + T(9) * e2 * e2 / T(88) - T(3) * e4 / T(22) -
                   T(9) * e2 * e3 / T(52) + T(3) * e5 / T(26);
  return scale * series / (a * std::sqrt(a)) + T(3) * sum;
}

}  // namespace sol::detail
