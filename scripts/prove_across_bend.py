#!/usr/bin/env python3
"""Proof that the across term of a horizontal tube bends by at most 1.

The tube along the horizontal unit direction h = (h_x, h_y) through a point
has the bound term asinh|G| - r with

    G = (h_y dx - h_x dy) / D,   D = |h_x| e^{-z} + |h_y| e^{z}

(sol::tube_terms in libsol/include/sol/clearance.hpp). The quotient march
steps by a clearance that needs M with (asinh|G|)'' >= -M along every unit
speed geodesic (docs/renderer.md, "Clearances"). This script shows M = 1:

1. Symbolically, from the geodesic equations in frame components
   (x' = e^z u1, y' = e^{-z} u2, z' = u3, u1' = u1 u3, u2' = -u2 u3,
   u3' = u2^2 - u1^2), (asinh G)'' (1 + G^2)^{3/2} equals the quadratic form
   u^T S(G, c) u, with c = (|h_y| e^z - |h_x| e^{-z}) / D in [-1, 1]
   (h_x, h_y > 0 and G > 0; the reflections x -> -x, y -> -y are isometries
   and give the other signs).
2. S + (1 + G^2)^{3/2} I is positive semidefinite for every G >= 0 and c in
   [-1, 1]: with G = 2s/(1 - s^2), s in [0, 1), (1 - s^2)^3 times each of its
   seven principal minors is a polynomial in (s, c), and its Bernstein
   coefficients on [0, 1] x [-1, 1], after subdivision, are all >= 0 (exact
   rational arithmetic). A polynomial is bounded below by its Bernstein
   coefficients on a box, and a symmetric matrix whose principal minors are
   all >= 0 is positive semidefinite. Hence (asinh G)'' >= -|u|^2 = -1.
3. The bound is tight: along a vertical geodesic where c = 0,
   (asinh G)'' = -G / sqrt(1 + G^2), which tends to -1.

Needs python3-sympy (Debian); not part of the build or the tests (the
tests check the bend along geodesics: tests/clearance_test.cpp).
Run: python3 scripts/prove_across_bend.py   (about a minute)
"""
from fractions import Fraction
from math import comb

import sympy as sp


def form_numerator(g, c, v1, v2, u3):
    """(asinh G)'' (1 + G^2)^{3/2} as a quadratic form in (v1, v2, u3) = (u1, -u2, u3)
    (G' = beta v1 + alpha v2 - G c u3, alpha = (1 - c)/2, beta = (1 + c)/2)."""
    alpha, beta = (1 - c) / 2, (1 + c) / 2
    return ((1 + g**2) * ((1 - c**2) * u3 * (v1 - v2) + g * u3**2 * (2 * c**2 - 1) + g * c * (v1**2 - v2**2)) -
            g * (beta * v1 + alpha * v2 - g * c * u3)**2)


def derivation_matches():
    x, y, z, u1, u2, u3, hx, hy = sp.symbols("x y z u1 u2 u3 h_x h_y", real=True)
    D = hx * sp.exp(-z) + hy * sp.exp(z)  # h_x, h_y > 0
    G = (hy * x - hx * y) / D

    def along(f):  # d/dt along the geodesic
        return (sp.diff(f, x) * sp.exp(z) * u1 + sp.diff(f, y) * sp.exp(-z) * u2 + sp.diff(f, z) * u3 +
                sp.diff(f, u1) * u1 * u3 - sp.diff(f, u2) * u2 * u3 + sp.diff(f, u3) * (u2**2 - u1**2))

    h2 = along(along(sp.asinh(G)))
    c = (hy * sp.exp(z) - hx * sp.exp(-z)) / D
    form = form_numerator(G, c, u1, -u2, u3) / (1 + G**2)**sp.Rational(3, 2)
    return sp.simplify(h2 - form) == 0


def minors():
    s, c, v1, v2, u3 = sp.symbols("s c v1 v2 u3", real=True)
    g = 2 * s / (1 - s**2)
    w = (1 + s**2) / (1 - s**2)  # sqrt(1 + g^2)
    S = sp.hessian(form_numerator(g, c, v1, v2, u3), (v1, v2, u3)) / 2
    A = ((S + w**3 * sp.eye(3)) * (1 - s**2)**3).applyfunc(lambda e: sp.cancel(sp.together(e)))
    p = sp.symbols("p", real=True)  # c = 2p - 1, p in [0, 1]
    out = {
        "A00": A[0, 0], "A11": A[1, 1], "A22": A[2, 2],
        "A00 A11 - A01^2": A[0, 0] * A[1, 1] - A[0, 1]**2,
        "A00 A22 - A02^2": A[0, 0] * A[2, 2] - A[0, 2]**2,
        "A11 A22 - A12^2": A[1, 1] * A[2, 2] - A[1, 2]**2,
        "det A": A.det(),
    }
    polys = {}
    for name, m in out.items():
        num, den = sp.fraction(sp.cancel(sp.together(sp.expand(m.subs(c, 2 * p - 1)))))
        assert den.is_number and den > 0, name
        polys[name] = sp.Poly(sp.expand(num), s, p)
    return polys, s, p


def bernstein(poly, s, p):
    ds, dp = poly.degree(s), poly.degree(p)
    a = [[Fraction(str(poly.coeff_monomial(s**i * p**j))) for j in range(dp + 1)] for i in range(ds + 1)]
    return [[sum(Fraction(comb(k, i), comb(ds, i)) * Fraction(comb(l, j), comb(dp, j)) * a[i][j]
                 for i in range(k + 1) for j in range(l + 1)) for l in range(dp + 1)] for k in range(ds + 1)]


def halves(row):  # de Casteljau at 1/2
    pts, left, right = list(row), [row[0]], [row[-1]]
    while len(pts) > 1:
        pts = [(pts[i] + pts[i + 1]) / 2 for i in range(len(pts) - 1)]
        left.append(pts[0])
        right.append(pts[-1])
    return left, right[::-1]


def nonnegative(b, depth):
    if min(min(r) for r in b) >= 0:
        return True
    if min(b[0][0], b[0][-1], b[-1][0], b[-1][-1]) < 0 or depth == 0:
        return False  # a negative value, or undecided
    if depth % 2 == 0:  # split along s
        cols = [halves(list(col)) for col in zip(*b)]
        parts = [[list(r) for r in zip(*[cl[k] for cl in cols])] for k in (0, 1)]
    else:  # along p
        rows = [halves(r) for r in b]
        parts = [[r[k] for r in rows] for k in (0, 1)]
    return all(nonnegative(part, depth - 1) for part in parts)


def main():
    ok = derivation_matches()
    print("h'' (1 + G^2)^{3/2} is the quadratic form:", ok)
    polys, s, p = minors()
    for name, poly in polys.items():
        certified = nonnegative(bernstein(poly, s, p), 14)
        print(f"{name}: nonnegative on [0, 1] x [-1, 1]: {certified}")
        ok = ok and certified
    print("M = 1 proven" if ok else "NOT PROVEN")
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
