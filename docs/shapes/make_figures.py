#!/usr/bin/env python3
"""The extrinsic figures of docs/shapes.md, from the project's own outputs
(the Python module sol): geodesics leaving the origin, and geodesic spheres
of radius 1 to 4 as shaded meshes.

    PYTHONPATH=build/ci/python/package python3 docs/shapes/make_figures.py [OUT_DIR]   (default docs/shapes)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import sol  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("docs", "shapes")


def geodesics_from_the_origin(path):
    """Geodesics from the origin in a spread of directions, to arc length 3."""
    fig = plt.figure(figsize=(6, 5))
    ax = fig.add_subplot(projection="3d")
    ts = np.linspace(0.0, 3.0, 120)
    rng = np.random.default_rng(2)
    directions = rng.normal(size=(60, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    for d in directions:
        points = np.array([sol.flow((0, 0, 0), d, t)[0] for t in ts])
        colour = plt.cm.coolwarm(0.5 + 0.5 * d[2])  # by the initial vertical component c
        ax.plot(points[:, 0], points[:, 1], points[:, 2], color=colour, linewidth=0.8)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title("geodesics from the origin, arc length 3\n(colour: initial vertical component, blue down, red up)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def spheres(path):
    """Geodesic spheres of radius 1 to 4 about the origin, shaded by the light from one direction."""
    fig = plt.figure(figsize=(12, 3.6))
    light = np.array([0.4, -0.5, 0.77])
    for k, r in enumerate((1.0, 2.0, 3.0, 4.0)):
        vertices, triangles = sol.geodesic_sphere((0, 0, 0), r, 40)
        tri = vertices[triangles]
        normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        shade = 0.25 + 0.75 * np.clip(normals @ light, 0.0, 1.0)
        ax = fig.add_subplot(1, 4, k + 1, projection="3d")
        ax.add_collection3d(Poly3DCollection(tri, facecolors=plt.cm.copper(shade), linewidths=0))
        m = np.abs(vertices).max(axis=0)
        ax.set_xlim(-m[0], m[0])
        ax.set_ylim(-m[1], m[1])
        ax.set_zlim(-m[2], m[2])
        ax.set_box_aspect(2 * m)
        ax.set_title(f"r = {r:g}")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.suptitle("geodesic spheres about the origin (axes to scale)")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


geodesics_from_the_origin(os.path.join(out, "geodesics.png"))
spheres(os.path.join(out, "spheres.png"))
