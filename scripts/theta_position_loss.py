#!/usr/bin/env python3
"""How much float loses when a geodesic's x and y come from E(u) and sn(u).

The kernel's positions take the time integrals of e^{±2w} by Carlson's
R_D between two points (carlson_piece in compute/shaders/sol_ray.glsl),
which is exact in float but is the larger part of a quotient march step's
cost (docs/renderer.md, "The quotient's rays off the plane regime"). A
cheaper path would take them from the antiderivatives, with e^{w} =
(dn u + k cn u)/k' (docs/mathematics.md) and E(u) = ∫ dn² (Jacobi's
epsilon):

  ∫ e^{ 2w} du = (2 E(u) + 2k sn u - k'² u) / k'²,
  ∫ e^{-2w} du = (2 E(u) - 2k sn u - k'² u) / k'²,

so that x = |b| ΔF / λ and y = |a| ΔG / λ between u0 and u = λt + u0. Both
are differences of terms of size 1/k'² = λ²/(4μ), which cancel where the
integral is small; this script measures the loss for the best a float
evaluation could do: E(u), E(u0), sn u, sn u0, u and the ray's constants
each correctly rounded to binary32 and every operation after them rounded
to binary32, against the same formula in 30 digits (mpmath), for random
unit directions with |ab| = μ, at arc lengths 0.3, 1 and 3 (a quotient
march restarts its ray at every face of D it crosses).

Measured (seed 1, 6 directions a μ): worst |Δx|, |Δy| 6.2e-7 at μ = 0.3,
1.1e-6 at 0.1, 1.4e-6 at 0.03, 2.8e-6 at 0.01, 1.3e-5 at 0.003; the
kernel's Carlson positions are within 1.4e-5 of the double closed form
over |t| <= 50 (Kernel.FlowMatchesTheDoubleClosedForm). Needs mpmath; not
part of the build or the tests.
"""

import random
import struct

import mpmath as mp

mp.mp.dps = 30


def f32(x):
    """x rounded to binary32."""
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def epsilon(u, m):
    """Jacobi's epsilon E(u | m) = ∫_0^u dn² (parameter m)."""
    return mp.quad(lambda v: mp.ellipfun("dn", v, m=m) ** 2, [0, u])


def worst_loss(mu, directions, rng):
    worst = 0.0
    for _ in range(directions):
        a = mp.mpf(rng.uniform(mu**0.5, 1.0))
        b = mu / a
        if a * a + b * b >= 1:
            continue
        c = mp.sqrt(1 - a * a - b * b) * rng.choice([-1, 1])
        lam = mp.sqrt(1 + 2 * mu)
        m = ((a - b) ** 2 + c * c) / lam**2
        k = mp.sqrt(m)
        kc2 = 4 * mu / lam**2
        # The start's phase from sn u0, cn u0 (docs/mathematics.md).
        root = mp.sqrt((a - b) ** 2 + c * c)
        u0 = mp.ellipf(mp.atan2(-c / root, (a - b) / root), m)
        e0, s0 = epsilon(u0, m), mp.ellipfun("sn", u0, m=m)
        fk, fkc2, fa, fb, flam = f32(k), f32(kc2), f32(a), f32(b), f32(lam)

        def part(e, s, u, sign):
            # 2E ± 2k sn - k'² u, each input and operation in binary32.
            return f32(f32(f32(2 * f32(e)) + sign * f32(2 * fk * f32(s))) - f32(fkc2 * f32(u)))

        for t in (0.3, 1.0, 3.0):
            u = lam * t + u0
            e, s = epsilon(u, m), mp.ellipfun("sn", u, m=m)
            exact_x = b * (2 * (e - e0) + 2 * k * (s - s0) - kc2 * (u - u0)) / kc2 / lam
            exact_y = a * (2 * (e - e0) - 2 * k * (s - s0) - kc2 * (u - u0)) / kc2 / lam
            x = f32(fb * f32(f32(part(e, s, u, 1) - part(e0, s0, u0, 1)) / fkc2) / flam)
            y = f32(fa * f32(f32(part(e, s, u, -1) - part(e0, s0, u0, -1)) / fkc2) / flam)
            worst = max(worst, float(abs(x - exact_x)), float(abs(y - exact_y)))
    return worst


def main():
    rng = random.Random(1)
    for mu in (0.3, 0.1, 0.03, 0.01, 0.003):
        print(f"mu {mu:.3f}: worst |dx|, |dy| in float {worst_loss(mu, 6, rng):.2e}")


if __name__ == "__main__":
    main()
