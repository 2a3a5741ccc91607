#!/usr/bin/env python3
"""The extrinsic figures of the Sol manifolds (docs/mathematics.md, "Every
lattice"), from the project's own lattices (the Python module sol): for each
monodromy A, the Anosov map on the torus (the unit square, its image under A,
A's eigen-directions) and the mapping torus as a stack of fibres (the
fundamental domain D in Sol coordinates, its top glued to its bottom by γ3).

    PYTHONPATH=build/release/python/package python3 docs/manifolds/make_figures.py OUT_DIR
(docs/manifolds as OUT_DIR replaces the figures the docs show)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import sol  # noqa: E402

if len(sys.argv) != 2:
    sys.exit("usage: PYTHONPATH=build/release/python/package python3 docs/manifolds/make_figures.py OUT_DIR")
out = sys.argv[1]
os.makedirs(out, exist_ok=True)

MONODROMIES = {"golden": [[2, 1], [1, 1]], "trace4": [[3, 1], [2, 1]]}


def anosov(ax, name, a):
    """The torus R²/Z² in the coordinates w of the lattice words γ1^w1 γ2^w2: the unit square, its image
    under A and A's eigen-directions. γ(w) = w1 γ1 + w2 γ2 has Sol coordinates (u+·w, u-·w): the expanding
    direction (A v = λ v) is where the y of γ(w) vanishes, the contracting one where its x does."""
    lattice = sol.Lattice(a)
    g1, g2, _ = (np.array(g) for g in lattice.generators)
    m = np.array(a, dtype=float)
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], dtype=float)
    image = square @ m.T
    ax.fill(square[:, 0], square[:, 1], color="#9ecae1", alpha=0.6, label="unit square (the fibre torus)")
    ax.plot(image[:, 0], image[:, 1], color="#e6550d", linewidth=1.6, label="its image under A")
    lam = np.exp(lattice.height)
    for v, colour, text in (((g2[1], -g1[1]), "#31a354", f"expanding, × {lam:.3f}"),
                            ((g2[0], -g1[0]), "#756bb1", f"contracting, × {1 / lam:.3f}")):
        v = np.array(v) / np.linalg.norm(v)
        assert np.allclose(m @ v, (lam if "expanding" in text else 1 / lam) * v, atol=1e-12)
        t = np.array([-6.0, 6.0])
        ax.plot(t * v[0], t * v[1], color=colour, linestyle="--", linewidth=1.2, label=text)
    # The lattice points, and the image folded back into the square (the map on the torus).
    grid = np.arange(-1, 6)
    for i in grid:
        ax.plot([i, i], [-1, 6], color="#dddddd", linewidth=0.5, zorder=0)
        ax.plot([-1, 6], [i, i], color="#dddddd", linewidth=0.5, zorder=0)
    lo = image.min(axis=0) - 0.5
    hi = image.max(axis=0) + 0.5
    ax.set_xlim(min(lo[0], -0.5), max(hi[0], 1.5))
    ax.set_ylim(min(lo[1], -0.5), max(hi[1], 1.5))
    ax.set_aspect("equal")
    ax.set_xlabel("w1 (γ1)")
    ax.set_ylabel("w2 (γ2)")
    ax.set_title(f"{name}: A = {a}, trace {a[0][0] + a[1][1]}")
    ax.legend(loc="upper left", fontsize=7)


def mapping_torus(ax, name, a):
    """D = P × [0, h) in Sol coordinates, P the parallelogram of γ1, γ2, drawn as fibres z = k h / 4; the
    top fibre is glued to the bottom one by γ3 (x scaled by 1/λ, y by λ going down): its parallelogram lands
    on the bottom as γ3⁻¹ P, another fundamental parallelogram of the same lattice ⟨γ1, γ2⟩."""
    lattice = sol.Lattice(a)
    g1, g2, g3 = (np.array(g) for g in lattice.generators)
    h = lattice.height
    corners = np.array([[0, 0, 0], g1, g1 + g2, g2, [0, 0, 0]])
    for k in range(5):
        z = k * h / 4
        ring = corners + [0, 0, z]
        ax.plot(ring[:, 0], ring[:, 1], ring[:, 2], color="#3182bd", linewidth=1.4 if k in (0, 4) else 0.6)
    for c in corners[:4]:
        ax.plot([c[0], c[0]], [c[1], c[1]], [0, h], color="#3182bd", linewidth=0.5)
    # γ3⁻¹ applied to the top fibre's corners (as points of Sol), the gluing.
    down = np.array([sol.multiply(sol.inverse(tuple(g3)), tuple(c + [0, 0, h])) for c in corners])
    assert np.allclose(down[:, 2], 0.0, atol=1e-12)
    ax.plot(down[:, 0], down[:, 1], down[:, 2], color="#e6550d", linewidth=1.6, label="top fibre glued down: γ3⁻¹ P")
    for c, d in zip(corners[:4], down[:4]):
        ax.plot([c[0], d[0]], [c[1], d[1]], [h, 0], color="#e6550d", linewidth=0.4, linestyle=":")
    # The lattice points of the bottom fibre near P: γ3⁻¹ P is a fundamental parallelogram of them.
    w = np.array([[i, j] for i in range(-4, 6) for j in range(-4, 6)], dtype=float)
    pts = w[:, :1] * g1 + w[:, 1:] * g2
    near = (np.abs(pts[:, 0]) < 4) & (np.abs(pts[:, 1]) < 4)
    ax.scatter(pts[near, 0], pts[near, 1], 0 * pts[near, 0], s=4, color="black")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(f"{name}: the mapping torus, h = ln λ = {h:.3f}")
    ax.legend(loc="upper left", fontsize=7)


for name, a in MONODROMIES.items():
    fig = plt.figure(figsize=(11, 4.6))
    anosov(fig.add_subplot(1, 2, 1), name, a)
    mapping_torus(fig.add_subplot(1, 2, 2, projection="3d"), name, a)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"manifold-{name}.png"), dpi=80)
    plt.close(fig)
    print(f"{out}/manifold-{name}.png")
