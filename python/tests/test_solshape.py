"""solshape (the C++ program) against the library it is built on, read
back from its files: the PLY's vertices lie on the geodesic sphere (by
sol.distances), the STL is closed and scaled to the size asked for, bad
input leaves no file. ctest names the program in SOLSHAPE."""
import os
import struct
import subprocess
import tempfile

import numpy as np
import pytest

import sol

pytestmark = pytest.mark.skipif("SOLSHAPE" not in os.environ, reason="solshape not built")


def run(*args):
    return subprocess.run([os.environ["SOLSHAPE"], *args], capture_output=True, text=True)


def read_ascii_ply(path):
    with open(path) as f:
        lines = f.read().splitlines()
    end = lines.index("end_header")
    vertices = int(next(l for l in lines if l.startswith("element vertex")).split()[-1])
    faces = int(next(l for l in lines if l.startswith("element face")).split()[-1])
    v = np.array([[float(x) for x in l.split()] for l in lines[end + 1:end + 1 + vertices]])
    f = np.array([[int(x) for x in l.split()[1:]] for l in lines[end + 1 + vertices:end + 1 + vertices + faces]])
    return v, f


def test_ply_vertices_lie_on_the_sphere():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.ply")
        assert run("sphere", "--radius", "2.5", "--center", "0.5,-0.2,0.3", "--resolution", "6", "-o", path).returncode == 0
        v, f = read_ascii_ply(path)
    assert v.shape == (4 * 36 + 2, 3) and f.shape == (8 * 36, 3)
    # The file holds 32-bit floats: 1e-6 of the coordinates' size, which moves distances by about as much.
    assert np.allclose(sol.distances((0.5, -0.2, 0.3), v), 2.5, atol=1e-5)
    ref, _ = sol.geodesic_sphere((0.5, -0.2, 0.3), 2.5, 6)
    assert np.allclose(v, ref, rtol=1e-6, atol=1e-6)


def test_stl_is_closed_and_scaled():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.stl")
        assert run("sphere", "--radius", "3", "--resolution", "5", "--size-mm", "60", "-o", path).returncode == 0
        data = open(path, "rb").read()
    count = struct.unpack_from("<I", data, 80)[0]
    assert count == 8 * 25 and len(data) == 84 + 50 * count
    corners = np.array([struct.unpack_from("<9f", data, 84 + 50 * i + 12) for i in range(count)]).reshape(-1, 3, 3)
    extent = corners.reshape(-1, 3).max(axis=0) - corners.reshape(-1, 3).min(axis=0)
    assert extent.max() == pytest.approx(60.0, rel=1e-6)
    # Closed: with the vertices welded by their exact coordinates, every edge bounds two triangles, once each way.
    keys = {}
    index = lambda p: keys.setdefault(tuple(p), len(keys))
    edges = {}
    for tri in corners:
        ids = [index(p) for p in tri]
        for a, b in ((ids[0], ids[1]), (ids[1], ids[2]), (ids[2], ids[0])):
            edges[(a, b)] = edges.get((a, b), 0) + 1
    assert all(n == 1 and edges.get((b, a)) == 1 for (a, b), n in edges.items())
    assert len(keys) - len(edges) // 2 + count == 2  # Euler characteristic


@pytest.mark.parametrize("args,words", [
    (["sphere", "--radius", "6.5", "-o", "x.ply"], "--radius must be in (0, 6]"),
    (["sphere", "--radius", "5.5", "--resolution", "8", "-o", "x.ply"], "needs at least 16 subdivisions"),
    (["geodesics", "--directions", "3", "--length", "2", "-o", "x.stl"], "STL holds no lines"),
    (["geodesics", "--length", "2", "-o", "x.ply"], "--directions N is required"),
    (["cut-locus", "--radii", "5,4", "-o", "x.ply"], "--radii must be in (sqrt(2) pi"),
    (["cut-locus", "--radii", "5,", "-o", "x.ply"], "--radii"),
    (["cut-locus", "-o", "x.ply"], "--radii R1,R2,... is required"),
    (["sphere", "--radius", "-1", "-o", "x.ply"], "--radius must be in"),
    (["sphere", "--radius", "nan", "-o", "x.ply"], "finite number"),
    (["sphere", "--radius", "1", "-o", "x.xyz"], "unknown mesh format"),
    (["sphere", "-o", "x.ply"], "--radius R is required"),
    (["cube", "-o", "x.ply"], "unknown shape 'cube'"),
])
def test_bad_input_exits_2_and_writes_nothing(args, words):
    with tempfile.TemporaryDirectory() as tmp:
        args = [os.path.join(tmp, a) if a.startswith("x.") else a for a in args]
        r = run(*args)
        assert r.returncode == 2 and words in r.stderr
        assert os.listdir(tmp) == []


def test_unwritable_file_fails_cleanly():
    r = run("sphere", "--radius", "1", "-o", "/nonexistent-dir/s.ply")
    assert r.returncode != 0 and "nonexistent-dir" in r.stderr


def test_geodesics_follow_the_flow():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "g.ply")
        r = run("geodesics", "--from", "0.2,0,-0.1", "--directions", "7", "--length", "3", "--segments", "6", "-o", path)
        assert r.returncode == 0, r.stderr
        v, f = read_ascii_ply(path)  # segments: two-vertex faces
    assert v.shape == (7 * 7, 3) and f.shape == (7 * 6, 2)
    # Each polyline: its start, then the flow along its first segment's direction (recovered from the file as
    # the direction whose flow reaches the first point: checked at every later point against sol.flow).
    for k in range(7):
        line = v[7 * k:7 * k + 7]
        assert np.allclose(line[0], (0.2, 0, -0.1), atol=1e-7)
        ways = sol.minimising_geodesics((0.2, 0, -0.1), tuple(line[1]))
        direction, length = ways[0]
        assert length == pytest.approx(0.5, abs=1e-5)  # 32-bit floats in the file
        for i in range(1, 7):
            assert np.allclose(sol.flow((0.2, 0, -0.1), direction, 0.5 * i)[0], line[i], atol=1e-4 * (1 + abs(line[i]).max()))
    # The segments join consecutive points of one polyline.
    assert all(b == a + 1 and a % 7 != 6 for a, b in f)


def test_cut_locus_points_have_two_minimisers():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "c.obj")
        r = run("cut-locus", "--radii", "4.8,5.6", "--samples", "5", "-o", path)
        assert r.returncode == 0, r.stderr
        with open(path) as fh:
            points = np.array([[float(x) for x in l.split()[1:]] for l in fh if l.startswith("v ")])
    assert points.shape == (2 * 4 * 5, 3)
    assert np.allclose(points[:, 2], 0.0, atol=1e-6)
    for i, p in enumerate(points):
        if i % 5 in (0, 4):
            continue  # the arcs' ends: the two minimisers coincide there
        ways = sol.minimising_geodesics((0, 0, 0), tuple(p))
        assert len(ways) == 2
        assert ways[0][1] == pytest.approx(4.8 if i < 20 else 5.6, abs=1e-5)
