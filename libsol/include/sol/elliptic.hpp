// Jacobi elliptic functions and Legendre elliptic integrals, float and double.
//
// Every function takes the parameter m = k² together with its complement
// m1 = 1 - m, both computed exactly by the caller (for Sol geodesics
// m1 = 4|ab|/(1+2|ab|), docs/mathematics.md): near m = 1 everything is driven by m1
// and k' = √m1, so precision survives m1 down to the smallest normal numbers.
// m and m1 must lie in [0, 1] and add up to 1 within a few ulp; otherwise, or
// for NaN/inf arguments, sol::InvalidArgument is thrown.
//
// Methods (square roots, one sin/cos pair, no series in m, no angle recursion):
//  - K: π / (2 AGM(1, k')) in double-double (K and its rounding error K_lo),
//    E: Carlson, (m1/3)(R_D(0, m1, 1) + R_D(0, 1, m1)) (DLMF 19.25.1, every
//    term positive).
//  - F(φ|m): Carlson s R_F(c², Δ², 1); E(φ|m) as the sum of positive terms
//    k'² F + (k²k'²/3) s³ R_D(c², 1, Δ²) + k² s c / Δ (DLMF 19.25.10), with
//    Δ² = c² + m1 s², after reducing φ by multiples of π.
//  - sn, cn, dn: u = nK + r with r ∈ [-K/2, K/2], reduced exactly (fma with
//    K + K_lo), so arguments up to 2^50 K keep full relative accuracy, also at
//    the zeros of sn and cn. On r: the AGM of 1 and k' with Bulirsch's
//    multiplicative back-substitution (Numer. Math. 7, 1965), which keeps cn
//    and dn relatively accurate as m → 1; odd n by the quarter shift
//    sn(K + r) = cd r, cn(K + r) = -k' sd r, dn(K + r) = k' nd r.
//  - am(u) = hπ + atan2(sn v, cn v), ε(u) = E(am u | m) = 2hE + E(am v | m)
//    with u = 2hK + v, v ∈ [-K, K]; Z(u) = E(am v | m) - (E/K) v, accurate to
//    rounding relative to max(|E(am v)|, |(E/K) v|) (Z itself is O(m) and
//    loses relative accuracy as m → 0; use ε where that matters).
#pragma once

namespace sol::elliptic {

/// Per-parameter precomputation.
template <class T>
struct Parameter {
  T m = 0;   ///< k²
  T m1 = 1;  ///< 1 - m, exact
  T k = 0;   ///< √m
  T kc = 1;  ///< k' = √m1
  T K = 0;   ///< complete integral of the first kind K(m), correctly rounded
  double K_lo = 0;  ///< K(m) - K (double in both precisions): K + K_lo is good to ~1e-31, so period reduction stays exact for huge arguments
  T E = 0;   ///< complete integral of the second kind E(m)
};

template <class T>
Parameter<T> make_parameter(T m, T m1);

template <class T>
struct Jacobi {
  T sn, cn, dn;
};

template <class T>
T complete_k(T m, T m1);
template <class T>
T complete_e(T m, T m1);
/// F(φ|m) for any real φ.
template <class T>
T incomplete_f(T phi, T m, T m1);
/// E(φ|m) for any real φ.
template <class T>
T incomplete_e(T phi, T m, T m1);

template <class T>
Jacobi<T> jacobi(T u, const Parameter<T>& p);
template <class T>
Jacobi<T> jacobi(T u, T m, T m1);
/// am u, continuous and increasing in u.
template <class T>
T amplitude(T u, const Parameter<T>& p);
template <class T>
T amplitude(T u, T m, T m1);
/// ε(u) = E(am u | m).
template <class T>
T epsilon(T u, const Parameter<T>& p);
template <class T>
T epsilon(T u, T m, T m1);
/// Jacobi's zeta function Z(u|m) = ε(u) - (E/K) u.
template <class T>
T zeta(T u, const Parameter<T>& p);
template <class T>
T zeta(T u, T m, T m1);

}  // namespace sol::elliptic
