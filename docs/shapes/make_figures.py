#!/usr/bin/env python3
"""The extrinsic figures of docs/shapes.md, from the project's own outputs
(the Python module sol): geodesics leaving the origin, geodesic spheres of
radius 1 to 4 and beyond sqrt(2) pi (with the cut locus on their creases)
as shaded meshes, the rays of the plane scene coloured by hit or miss beside
the renderer's image, and an exact ball seen from inside beside its mesh.

    PYTHONPATH=build/ci/python/package python3 docs/shapes/make_figures.py OUT_DIR
(docs/shapes as OUT_DIR replaces the figures the docs show)
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import sol  # noqa: E402

if len(sys.argv) != 2:
    sys.exit("usage: PYTHONPATH=build/ci/python/package python3 docs/shapes/make_figures.py OUT_DIR")
out = sys.argv[1]
os.makedirs(out, exist_ok=True)


def geodesics_from_the_origin(path):
    """Geodesics from the origin in a spread of directions, to arc length 3."""
    fig = plt.figure(figsize=(6, 5))
    ax = fig.add_subplot(projection="3d")
    ts = np.linspace(0.0, 3.0, 120)  # 119 segments
    rng = np.random.default_rng(2)
    directions = rng.normal(size=(60, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    for d, points in zip(directions, sol.geodesic_polylines((0, 0, 0), directions, 3.0, len(ts) - 1)):
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


def shaded(ax, vertices, triangles, light=np.array([0.4, -0.5, 0.77]), cmap=plt.cm.copper, alpha=1.0):
    """A mesh shaded by a light from one direction."""
    tri = vertices[triangles]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    shade = 0.25 + 0.75 * np.clip(normals @ (light / np.linalg.norm(light)), 0.0, 1.0)
    ax.add_collection3d(Poly3DCollection(tri, facecolors=cmap(shade), linewidths=0, alpha=alpha))


def creased_spheres(path):
    """Spheres beyond sqrt(2) pi: the creases where they meet the cut locus of the centre (drawn in black)."""
    fig = plt.figure(figsize=(12, 3.8))
    for k, r in enumerate((4.6, 5.0, 5.5)):
        vertices, triangles = sol.geodesic_sphere((0, 0, 0), r, 64)
        # The middle of the sphere (its four arms reach 40 and more along x and y): the triangles within 7 of
        # the axis, z stretched to show the crease.
        inside = (np.abs(vertices[triangles][:, :, :2]) <= 7.0).all(axis=(1, 2))
        ax = fig.add_subplot(1, 3, k + 1, projection="3d")
        shaded(ax, vertices, triangles[inside], light=np.array([0.3, -0.6, 0.75]))
        for arc in sol.cut_locus_curves((0, 0, 0), [r], 48):
            ax.plot(arc[:, 0], arc[:, 1], arc[:, 2], color="black", linewidth=1.5, zorder=10)
        zmax = np.abs(vertices[:, 2]).max()
        ax.set_xlim(-7, 7)
        ax.set_ylim(-7, 7)
        ax.set_zlim(-zmax, zmax)
        ax.set_box_aspect((1, 1, 0.6))
        ax.view_init(elev=28, azim=-50)
        ax.set_title(f"r = {r:g} (|x|, |y| <= 7; z not to scale)")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    fig.suptitle("geodesic spheres beyond sqrt(2) pi: creases on the cut locus, in the plane z = 0 (black)")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def ray_cluster(path):
    """The plane scene (z = 0 seen from (0, 0, 1.5) looking down): the rays of the image's middle column, which
    hit the plane (blue) or turn back up (red) as the renderer found, beside the renderer's image."""
    scene = sol.preset_scene("plane")
    width, height = 160, 120
    image = sol.render_cpu(scene, width, height)
    directions = sol.camera_rays(scene, width, height)
    column = width // 2
    start = scene.camera_position
    fig = plt.figure(figsize=(11, 4.6))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    hits = 0
    for j in range(0, height, 3):
        hit = image["object"][j, column] > 0
        length = float(image["distance"][j, column]) if hit else 6.0
        line = sol.geodesic_polylines(tuple(start), directions[j, column], length, 80)[0]
        if hit:  # the renderer's hit lies on the plane, where the flow ends
            assert abs(line[-1, 2]) < 1e-3, line[-1]
            hits += 1
        else:  # a miss never comes down to the plane
            assert line[:, 2].min() > 0.0
        line[line[:, 2] > 3.0] = np.nan  # cut at the top of the box
        ax.plot(line[:, 0], line[:, 1], line[:, 2], color="tab:blue" if hit else "tab:red", linewidth=0.9)
    xs = np.linspace(-3, 3, 2)
    X, Y = np.meshgrid(xs, xs)
    ax.plot_surface(X, Y, 0 * X, color="goldenrod", alpha=0.25)
    ax.scatter([start[0]], [start[1]], [start[2]], color="black", s=12)
    ax.set_xlim(-3, 3)
    ax.set_ylim(-3, 3)
    ax.set_zlim(-0.2, 3)
    ax.view_init(elev=12, azim=-20)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title("rays of the middle column from (0, 0, 1.5):\nblue reach z = 0, red turn back up")
    ax2 = fig.add_subplot(1, 2, 2)
    rgb = np.clip(image["rgba"][..., :3], 0, 1) ** (1 / 2.2)
    ax2.imshow(rgb)
    ax2.axvline(column, color="white", linewidth=0.8, linestyle="--")
    ax2.set_title("what the observer sees (solrender's CPU renderer):\nthe band of hits, dark above and below")
    ax2.set_xticks([])
    ax2.set_yticks([])
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return hits


def ball_inside_and_out(path):
    """An exact ball of radius 2 seen from inside Sol (the CPU renderer) beside the same geodesic sphere as a mesh,
    with the observer and the geodesic from it to the centre."""
    center, radius = (0.0, 0.0, 0.0), 2.0
    eye = (2.5, -3.0, 1.2)
    ahead = sol.minimising_geodesics(eye, center)[0][0]  # the exact direction towards the centre
    scene = sol.parse_scene(json.dumps({
        "camera": {"position": list(eye), "forward": list(ahead), "up": [0, 0, 1], "fov": 80},
        "objects": [{"type": "ball", "center": list(center), "radius": radius, "exact": True, "pattern": "checker",
                     "color": [0.9, 0.55, 0.3]}],
        "lights": [{"type": "directional", "direction": [0.4, -0.5, 0.77], "color": [1, 1, 1], "intensity": 1.0}],
        "ambient": 0.2, "max_distance": 20.0}))
    image = sol.render_cpu(scene, 200, 200)
    fig = plt.figure(figsize=(10, 4.6))
    ax = fig.add_subplot(1, 2, 1)
    ax.imshow(np.clip(image["rgba"][..., :3], 0, 1) ** (1 / 2.2))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(f"inside: an exact ball of radius {radius:g} seen from {eye}")
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    vertices, triangles = sol.geodesic_sphere(center, radius, 32)
    shaded(ax3, vertices, triangles, alpha=0.35)
    path_to_centre = sol.geodesic_polylines(eye, np.array(ahead), sol.distance(eye, center), 60)[0]
    ax3.plot(path_to_centre[:, 0], path_to_centre[:, 1], path_to_centre[:, 2], color="black", linewidth=1.5, zorder=10)
    ax3.scatter([eye[0]], [eye[1]], [eye[2]], color="black", s=15)
    lo = np.minimum(vertices.min(axis=0), eye)
    hi = np.maximum(vertices.max(axis=0), eye)
    ax3.set_xlim(lo[0], hi[0])
    ax3.set_ylim(lo[1], hi[1])
    ax3.set_zlim(lo[2], hi[2])
    ax3.set_box_aspect(hi - lo)
    ax3.set_xlabel("x")
    ax3.set_ylabel("y")
    ax3.set_title("outside: the same sphere as a (printable) mesh,\nthe observer and the geodesic to the centre")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


geodesics_from_the_origin(os.path.join(out, "geodesics.png"))
spheres(os.path.join(out, "spheres.png"))
creased_spheres(os.path.join(out, "creased-spheres.png"))
ray_cluster(os.path.join(out, "ray-cluster.png"))
ball_inside_and_out(os.path.join(out, "ball-inside-and-out.png"))
