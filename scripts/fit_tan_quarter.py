#!/usr/bin/env python3
"""The coefficients of sol_tan_quarter (compute/shaders/sol_elliptic.glsl).

The kernel's Jacobi functions need cot x and the sign of sin x for
|x| <= pi/4 (jacobi_agm). tan x there is written x + x^3 P(x^2) with P of
degree 5, fitted here to the least relative error: least squares on 400
Chebyshev nodes of [0, pi/4], reweighted (Lawson's iteration) towards the
minimax fit. tan is odd, so [0, pi/4] covers [-pi/4, pi/4].

The script prints the coefficients (constant term first) and the worst
relative error of the polynomial in double and of its evaluation in float
(each operation rounded to binary32, as the kernel does it), in float ulps
(2^-24 relative). Pure Python; not part of the build or the tests (the
kernel tests hold the Jacobi values that use it to the double closed form).
"""

import math
import struct

DEGREE = 6  # coefficients: P has degree 5
NODES = 400


def f32(v):
    """v rounded to binary32."""
    return struct.unpack("f", struct.pack("f", v))[0]


def solve(a, b):
    """Gaussian elimination with partial pivoting."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c:
                f = m[r][c] / m[c][c]
                for k in range(c, n + 1):
                    m[r][k] -= f * m[c][k]
    return [m[i][n] / m[i][i] for i in range(n)]


def fit():
    xs = [math.pi / 4 * (0.5 + 0.5 * math.cos(math.pi * (i + 0.5) / NODES)) for i in range(NODES)]
    weights = [1.0] * NODES
    coefficients = []
    for _ in range(30):
        a = [[0.0] * DEGREE for _ in range(DEGREE)]
        b = [0.0] * DEGREE
        for x, w in zip(xs, weights):
            t = math.tan(x)
            # The relative residual (x + x^3 P(x^2) - t)/t is linear in P's coefficients.
            phi = [x**3 * (x * x) ** j / t for j in range(DEGREE)]
            y = (t - x) / t
            for i in range(DEGREE):
                b[i] += w * phi[i] * y
                for j in range(DEGREE):
                    a[i][j] += w * phi[i] * phi[j]
        coefficients = solve(a, b)
        errors = [abs(evaluate(coefficients, x) / math.tan(x) - 1.0) for x in xs]
        worst = max(errors)
        weights = [w * (e / worst + 0.1) for w, e in zip(weights, errors)]
    return coefficients


def evaluate(c, x):
    z = x * x
    p = 0.0
    for cj in reversed(c):
        p = p * z + cj
    return x + x * z * p


def evaluate_float(c, x):
    """As the kernel: Horner's rule in float, every operation rounded."""
    c = [f32(v) for v in c]
    x = f32(x)
    z = f32(x * x)
    p = c[-1]
    for cj in reversed(c[:-1]):
        p = f32(f32(p * z) + cj)
    return f32(x + f32(f32(x * z) * p))


def main():
    c = fit()
    print("coefficients (z^0 .. z^5):", ", ".join("%.10e" % v for v in c))
    samples = [math.pi / 4 * i / 200000 for i in range(1, 200001)]
    ulp = 2.0**-24
    exact = max(abs(evaluate(c, x) / math.tan(x) - 1.0) for x in samples)
    rounded = max(abs(evaluate_float(c, x) / math.tan(f32(x)) - 1.0) for x in samples)
    print("worst relative error: %.2f ulps in double, %.2f ulps in float" % (exact / ulp, rounded / ulp))


if __name__ == "__main__":
    main()
