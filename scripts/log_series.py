#!/usr/bin/env python3
"""Sol's logarithm at the origin as a Taylor series: writes
libsol/include/sol/log_series.h.

The exponential map at the origin sends v to the end of the geodesic from
the origin with initial velocity v at time 1. Its inverse near 0, the
logarithm, is analytic, and its Taylor series is what the kernel's exact
balls start their Newton solves from (compute/shaders/sol_connection.glsl,
sol_shortest): within kLogSeriesReach the series lands within 5e-5 of
the solution, so one Newton step or none reaches float rounding, where a
seed of the connection table needed three or four (docs/exact.md).

Derivation, in exact rational arithmetic (pure Python, no dependencies):

1. The geodesic equations of ds^2 = e^{-2z} dx^2 + e^{2z} dy^2 + dz^2
   (the project's convention, docs/mathematics.md):
       x'' = 2 x' z',   y'' = -2 y' z',   z'' = -e^{-2z} x'^2 + e^{2z} y'^2,
   from (0, 0, 0) with velocity (a, b, c). The coefficient of t^n of the
   solution is a homogeneous polynomial of degree n in (a, b, c), so the
   Taylor series of exp(v) at t = 1 is the sum of those coefficients, found
   order by order from the equations (e^{+-2z} by the series of exp).
2. The inverse series: v = w - H(v), H the terms of degree >= 2 of exp,
   iterated ORDER times with every product truncated at degree ORDER (each
   iteration fixes one more degree).

The symmetries (x, y, z) -> (-x, y, z), (x, -y, z) and the swap
(x, y, z) -> (y, x, -z) hold for the series, so it is written
    log w = (w_x f(w_x^2, w_y^2, w_z), w_y f(w_y^2, w_x^2, -w_z), h(w_x^2, w_y^2, w_z))
and the header holds f and h, nested Horner forms in (p, q, z); the script
checks those symmetries on the coefficients.

Usage:
    scripts/log_series.py [--order N] [--reach R]    print the header
    scripts/log_series.py --check FILE               exit 1 unless FILE is what it would print
The tests run --check on the committed header (tests/CMakeLists.txt); the
series' accuracy is held to libsol's double closed form by
Connection.LogSeriesInvertsTheExponentialMap and, in float on the kernel,
Kernel.LogSeriesInvertsTheExponentialMap.
"""

import argparse
import sys
from collections import defaultdict
from fractions import Fraction

ORDER = 11
REACH = "0.8"


class Series:
    """Polynomials in three variables truncated at a total degree."""

    def __init__(self, order):
        self.order = order

    def add(self, p, q, s=1):
        r = defaultdict(Fraction)
        for k, v in p.items():
            r[k] += v
        for k, v in q.items():
            r[k] += s * v
        return {k: v for k, v in r.items() if v != 0}

    def mul(self, p, q):
        r = defaultdict(Fraction)
        for k1, v1 in p.items():
            d1 = sum(k1)
            for k2, v2 in q.items():
                if d1 + sum(k2) <= self.order:
                    r[(k1[0] + k2[0], k1[1] + k2[1], k1[2] + k2[2])] += v1 * v2
        return {k: v for k, v in r.items() if v != 0}

    @staticmethod
    def scale(p, s):
        return {k: v * s for k, v in p.items() if v * s != 0}

    def exp(self, p):
        """exp of a polynomial without constant term."""
        r = {(0, 0, 0): Fraction(1)}
        term = dict(r)
        for k in range(1, self.order + 1):
            term = self.scale(self.mul(term, p), Fraction(1, k))
            r = self.add(r, term)
        return r

    def by_degree(self, p):
        out = [{} for _ in range(self.order + 1)]
        for k, v in p.items():
            out[sum(k)][k] = v
        return out

    def compose(self, p, q):
        """p(q_0, q_1, q_2)."""
        powers = [{0: {(0, 0, 0): Fraction(1)}} for _ in range(3)]

        def power(i, e):
            if e not in powers[i]:
                powers[i][e] = self.mul(power(i, e - 1), q[i])
            return powers[i][e]

        r = {}
        for (i, j, k), v in p.items():
            r = self.add(r, self.scale(self.mul(self.mul(power(0, i), power(1, j)), power(2, k)), v))
        return r


def exp_series(s):
    """The exponential map's Taylor series: its three components."""
    unit = [{(1, 0, 0): Fraction(1)}, {(0, 1, 0): Fraction(1)}, {(0, 0, 1): Fraction(1)}]
    # X[n]: the coefficient of t^n of x(t), homogeneous of degree n in (a, b, c).
    X, Y, Z = [{}, unit[0]], [{}, unit[1]], [{}, unit[2]]

    def cauchy(P, Q, n):  # coefficient n of the product of two series in t
        r = {}
        for i in range(n + 1):
            if i < len(P) and n - i < len(Q):
                r = s.add(r, s.mul(P[i], Q[n - i]))
        return r

    for n in range(s.order - 1):
        dX = [s.scale(X[k + 1], k + 1) for k in range(len(X) - 1)]
        dY = [s.scale(Y[k + 1], k + 1) for k in range(len(Y) - 1)]
        dZ = [s.scale(Z[k + 1], k + 1) for k in range(len(Z) - 1)]
        z = {}
        for part in Z:
            z = s.add(z, part)
        # e^{-+2z} as series in t: by homogeneity, degree = power of t.
        e_minus, e_plus = s.by_degree(s.exp(s.scale(z, -2))), s.by_degree(s.exp(s.scale(z, 2)))
        dx2 = [cauchy(dX, dX, k) for k in range(s.order + 1)]
        dy2 = [cauchy(dY, dY, k) for k in range(s.order + 1)]
        ddx = s.scale(cauchy(dX, dZ, n), 2)
        ddy = s.scale(cauchy(dY, dZ, n), -2)
        ddz = s.add(s.scale(cauchy(e_minus, dx2, n), -1), cauchy(e_plus, dy2, n))
        d = Fraction(1, (n + 2) * (n + 1))
        X.append(s.scale(ddx, d))
        Y.append(s.scale(ddy, d))
        Z.append(s.scale(ddz, d))
    total = [{}, {}, {}]
    for n in range(1, s.order + 1):
        total = [s.add(total[0], X[n]), s.add(total[1], Y[n]), s.add(total[2], Z[n])]
    return total


def log_series(order):
    s = Series(order)
    exp = exp_series(s)
    higher = [{k: v for k, v in c.items() if sum(k) >= 2} for c in exp]
    w = [{(1, 0, 0): Fraction(1)}, {(0, 1, 0): Fraction(1)}, {(0, 0, 1): Fraction(1)}]
    v = list(w)
    for _ in range(order):
        v = [s.add(w[i], s.compose(higher[i], v), -1) for i in range(3)]
    return v


def check_symmetries(log):
    x, y, z = log
    assert all(i % 2 == 1 and j % 2 == 0 for (i, j, k) in x), "x is odd in w_x, even in w_y"
    assert all(i % 2 == 0 and j % 2 == 0 for (i, j, k) in z), "z is even in w_x and w_y"
    assert y == {(j, i, k): v * (-1) ** k for (i, j, k), v in x.items()}, "y(w) = x(w_y, w_x, -w_z)"
    assert z == {(j, i, k): -v * (-1) ** k for (i, j, k), v in z.items()}, "z(w) = -z(w_y, w_x, -w_z)"


def literal(f):
    text = repr(float(f))
    return text if ("e" in text or "." in text) else text + ".0"


def horner(terms, var, indent):
    """sum_k terms[k] var^k, nested."""
    top = max(terms)
    out = None
    for k in range(top, -1, -1):
        c = terms.get(k)
        if out is None:
            out = c if c is not None else "0.0"
        elif c is None:
            out = f"{var} * ({out})"
        else:
            out = f"{c} + {var} * ({out})"
    return out


def nested(poly):
    """poly {(i, j, k): c} in (p, q, z) as Horner in p of Horner in q of Horner in z."""
    by_p = {}
    for (i, j, k), v in poly.items():
        by_p.setdefault(i, {}).setdefault(j, {})[k] = literal(v)
    inner = {i: horner({j: horner(dk, "z", 0) for j, dk in dj.items()}, "q", 0) for i, dj in by_p.items()}
    return horner(inner, "p", 0)


def wrap(expression, width=110, indent="      "):
    """Breaks a long expression at spaces into lines of at most `width`."""
    words, lines, line = expression.split(" "), [], ""
    for word in words:
        if line and len(line) + 1 + len(word) > width - len(indent):
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    lines.append(line)
    return ("\n" + indent).join(lines)


def header(order, reach):
    log = log_series(order)
    check_symmetries(log)
    f = {((i - 1) // 2, j // 2, k): v for (i, j, k), v in log[0].items()}
    h = {(i // 2, j // 2, k): v for (i, j, k), v in log[2].items()}
    return f"""// Sol's logarithm at the origin (the inverse of the exponential map at the
// origin: the initial vector v of the geodesic from the origin that ends at
// w at time 1) as its Taylor series to order {order}, for the kernels' exact
// balls (sol_shortest in compute/shaders/sol_connection.glsl) and libsol
// (sol::log_series):
//   log w = (w_x f(w_x², w_y², w_z), w_y f(w_y², w_x², -w_z), h(w_x², w_y², w_z)).
// GENERATED by scripts/log_series.py (the derivation is there): do not
// edit; the tests check that this file is what the script writes.
// Valid C++ (double, in namespace sol::kernel) and GLSL (float), as
// sol/kernel_constants.h.
#ifndef SOL_LOG_SERIES_H
#define SOL_LOG_SERIES_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#define SOL_SERIES_FUNCTION inline constexpr
namespace sol::kernel {{
#else
#define SOL_SERIES_FUNCTION
#endif

/// The series' order (the highest total degree in w of its terms).
SOL_CONSTANT(int, kLogSeriesOrder, {order});
/// Where the series is taken: |w| below this (coordinates). There it is
/// within 5e-5 of the logarithm (test Connection.LogSeriesInvertsTheExponentialMap).
SOL_CONSTANT(SOL_REAL, kLogSeriesReach, {reach});

/// f(p, q, z): log w's x component over w_x, at p = w_x², q = w_y², z = w_z.
SOL_SERIES_FUNCTION SOL_REAL sol_log_series_f(SOL_REAL p, SOL_REAL q, SOL_REAL z) {{
  return {wrap(nested(f))};
}}

/// h(p, q, z): log w's z component.
SOL_SERIES_FUNCTION SOL_REAL sol_log_series_h(SOL_REAL p, SOL_REAL q, SOL_REAL z) {{
  return {wrap(nested(h))};
}}

#ifdef __cplusplus
}}  // namespace sol::kernel
#else
// The series at w.
vec3 sol_log_series(vec3 w) {{
  const float p = w.x * w.x, q = w.y * w.y;
  return vec3(w.x * sol_log_series_f(p, q, w.z), w.y * sol_log_series_f(q, p, -w.z), sol_log_series_h(p, q, w.z));
}}
#endif
#undef SOL_SERIES_FUNCTION

#endif  // SOL_LOG_SERIES_H
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--order", type=int, default=ORDER)
    parser.add_argument("--reach", default=REACH)
    parser.add_argument("--check", metavar="FILE", help="exit 1 unless FILE is what the script writes")
    args = parser.parse_args()
    if args.order < 2:
        parser.error(f"--order must be at least 2, got {args.order}")
    try:
        if not 0.0 < float(args.reach) < 2.0:
            raise ValueError
    except ValueError:
        parser.error(f"--reach must be a number in (0, 2), got '{args.reach}'")
    text = header(args.order, args.reach)
    if args.check:
        try:
            with open(args.check, encoding="utf-8") as f:
                committed = f.read()
        except OSError as e:
            print(f"log_series.py: --check {args.check}: {e.strerror}", file=sys.stderr)
            return 2
        if committed != text:
            print(f"{args.check} differs from what scripts/log_series.py writes: regenerate it", file=sys.stderr)
            return 1
        return 0
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
