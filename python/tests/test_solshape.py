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
    (["sphere", "--radius", "5", "-o", "x.ply"], "--radius must be in (0, sqrt(2) pi"),
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
