"""Tests of the Python module sol against the C++ programs (solgeodesic,
solrender) and libsol's own identities. Run by ctest (python.pytest), which
puts the built module on PYTHONPATH and names the programs in SOLGEODESIC
and SOLRENDER."""
import json
import math
import os
import subprocess
import tempfile

import numpy as np
import pytest

import sol


def test_group_law_and_inverse():
    p, q = (0.3, -1.2, 0.7), (2.0, 0.5, -0.4)
    # (x1, y1, z1) * (x2, y2, z2) = (x1 + e^{z1} x2, y1 + e^{-z1} y2, z1 + z2), written out here.
    expected = (0.3 + math.exp(0.7) * 2.0, -1.2 + math.exp(-0.7) * 0.5, 0.3)
    assert np.allclose(sol.multiply(p, q), expected, rtol=0, atol=1e-15)
    assert np.allclose(sol.multiply(p, sol.inverse(p)), (0, 0, 0), atol=1e-15)


def solgeodesic_end(start, direction, length):
    """The end of the geodesic as the C++ program solgeodesic prints it (8 decimals)."""
    out = subprocess.run([os.environ["SOLGEODESIC"], "--from", ",".join(map(repr, start)),
                          "--direction", ",".join(map(repr, direction)),
                          "--length", str(length), "--samples", "2"], check=True, capture_output=True, text=True).stdout
    rows = [line.split() for line in out.splitlines() if line.strip() and not line.startswith("#")]
    last = [float(v) for v in rows[-1]]
    return np.array(last[1:4]), np.array(last[4:7])


@pytest.mark.parametrize("direction,length", [((1, 0, 0), 2.0), ((0.3, -0.5, 0.8), 4.5), ((1, 1, 0.01), 7.0)])
def test_flow_matches_solgeodesic(direction, length):
    start = (0.2, -0.1, 0.3)
    position, tangent = sol.flow(start, direction, length)
    cpp_position, cpp_tangent = solgeodesic_end(start, direction, length)
    # solgeodesic prints positions to 8 decimals (relative to their size) and directions to 6.
    assert np.allclose(position, cpp_position, rtol=1e-7, atol=1e-8)
    assert np.allclose(tangent, cpp_tangent, atol=1e-6)
    assert abs(np.linalg.norm(tangent) - 1.0) < 1e-12


def test_vectorised_flow_and_distance_equal_one_at_a_time():
    rng = np.random.default_rng(5)
    directions = rng.normal(size=(20, 3))
    lengths = rng.uniform(0.1, 3.0, size=20)
    start = (0.1, 0.2, -0.3)
    ends, tangents = sol.flow_many(start, directions, lengths)
    for i in range(20):
        p, u = sol.flow(start, directions[i], lengths[i])
        assert np.array_equal(ends[i], p) and np.array_equal(tangents[i], u)
    same_length, _ = sol.flow_many(start, directions, 1.5)
    assert np.array_equal(same_length[3], sol.flow(start, directions[3], 1.5)[0])
    d = sol.distances(start, ends)
    for i in range(20):
        assert d[i] == sol.distance(start, ends[i])
        # The distance never exceeds the length of a geodesic that reaches the point.
        assert d[i] <= lengths[i] + 1e-9


def test_connections_reach_their_targets():
    p, q = (0.0, 0.0, 0.0), (1.5, 0.8, -0.4)
    shortest = sol.minimising_geodesics(p, q)
    assert len(shortest) >= 1
    direction, length = shortest[0]
    assert length == pytest.approx(sol.distance(p, q), rel=1e-12)
    assert np.allclose(sol.flow(p, direction, length)[0], q, atol=1e-9)
    longer = sol.geodesics_between(p, q, length + 2.0)
    assert len(longer) >= len(shortest)
    for d, t in longer:
        assert np.allclose(sol.flow(p, d, t)[0], q, atol=1e-8)


def test_aim_reaches_the_target_and_cameras_look_at_it():
    eye, target = (0.4, 0.3, 0.2), (2.6, -1.9, 1.1)
    a = sol.aim(eye, target)
    assert a["distance"] == pytest.approx(sol.distance(eye, target), rel=1e-12)
    assert np.allclose(sol.flow(eye, a["direction"], a["distance"])[0], target, atol=1e-9)
    golden = sol.Lattice.golden()
    g = sol.aim(eye, target, golden)
    assert g["distance"] < a["distance"] - 0.1  # a nearer image of the target
    assert np.allclose(sol.flow(eye, g["direction"], g["distance"])[0], g["end"], atol=1e-8)
    assert np.allclose(golden.teleport(g["end"])[0], golden.teleport(target)[0], atol=1e-8)
    # The scene key and replace: look_at takes forward's place.
    scene = sol.scene([sol.ball(target, 0.05)], camera={"position": eye, "look_at": target}, quotient="golden")
    assert np.allclose(scene.camera.forward, g["direction"], atol=1e-15)
    turned = sol.preset_scene("spheres").replace(camera={"position": eye, "look_at": target})
    assert np.allclose(turned.camera.forward, a["direction"], atol=1e-15)
    assert np.allclose(sol.camera(position=eye, look_at=target).forward, a["direction"], atol=1e-15)


def test_transport_is_orthogonal_and_carries_the_tangent():
    q = sol.transport((0, 0, 0), (0.4, 0.5, 0.6), 2.0)
    assert np.allclose(q @ q.T, np.eye(3), atol=1e-10)
    u0 = np.array([0.4, 0.5, 0.6]) / np.linalg.norm([0.4, 0.5, 0.6])
    assert np.allclose(q @ u0, sol.flow((0, 0, 0), u0, 2.0)[1], atol=1e-10)


def test_lattice_teleport():
    lattice = sol.Lattice.golden()
    point, (a, b, c) = lattice.teleport((5.0, -3.0, 2.2))
    assert lattice.contains(point)
    assert np.allclose(sol.multiply(lattice.element(a, b, c), (5.0, -3.0, 2.2)), point, atol=1e-9)
    assert lattice.height == pytest.approx(2 * math.log((1 + math.sqrt(5)) / 2), rel=1e-15)


def test_lattice_of_a_monodromy():
    # The torus bundle of A = [[3, 1], [2, 1]]: γ3 γ1 γ3⁻¹ and γ3 γ2 γ3⁻¹ are the words of A's columns, as points.
    lattice = sol.Lattice([[3, 1], [2, 1]])
    assert lattice.monodromy == ((3, 1), (2, 1))
    assert lattice.height == pytest.approx(math.log(2 + math.sqrt(3)), rel=1e-15)
    g1, g2, g3 = lattice.generators
    conjugate = lambda g: sol.multiply(sol.multiply(g3, g), sol.inverse(g3))
    assert np.allclose(conjugate(g1), lattice.element(3, 2, 0), atol=1e-12)
    assert np.allclose(conjugate(g2), lattice.element(1, 1, 0), atol=1e-12)
    assert lattice.multiply((0, 0, 1), (1, 0, 0)) == (3, 2, 1)
    assert sol.Lattice([[3, 1], [2, 1]], fibre_area=10.0).fibre_area == pytest.approx(10.0, rel=1e-14)
    assert all(np.array_equal(a, b) for a, b in zip(sol.Lattice([[2, 1], [1, 1]]).generators, sol.Lattice.golden().generators))
    with pytest.raises(ValueError, match="not hyperbolic"):
        sol.Lattice([[1, 1], [0, 1]])
    # A negative trace: γ3 turns the fibre, γ3(p) = (0, 0, h) · (-x, -y, z).
    minus = sol.Lattice([[-3, -1], [-2, -1]])
    assert minus.turns and not lattice.turns
    p = (0.3, -0.2, 0.1)
    assert np.allclose(minus.apply((0, 0, 1), p), sol.multiply(minus.generators[2], (-0.3, 0.2, 0.1)), atol=1e-14)
    # A scene in it: the ball at the base point seen from the middle of D.
    middle = tuple(0.5 * (np.array(g1) + np.array(g2)) + np.array([0, 0, 0.5 * lattice.height]))
    scene = sol.scene([sol.ball((0, 0, 0), 0.3)], quotient={"monodromy": [[3, 1], [2, 1]]},
                      camera=sol.camera(position=middle, forward=(0, 0, -1), up=(0, 1, 0)))
    assert scene.to_dict()["quotient"] == {"monodromy": [[3, 1], [2, 1]]}
    assert (sol.render_cpu(scene, 16, 12)["object"] > 0).any()


def test_non_compact_quotients():
    # A z loop: gamma3 alone, D = R^2 x [0, h); xy loops: translations alone, D = P x R.
    z = sol.Lattice.z_loop(1.5)
    assert z.loops == "z" and z.height == 1.5
    point, word = z.teleport((4.0, -3.0, 3.2))
    assert word == (0, 0, -2) and z.contains(point)
    assert np.allclose(point, (4.0 * math.exp(-3.0), -3.0 * math.exp(3.0), 0.2), atol=1e-12)
    xy = sol.Lattice.xy_loops((2.0, 0.0), (0.5, 1.5))
    assert xy.loops == "xy" and xy.fibre_area == pytest.approx(3.0, rel=1e-15)
    point, word = xy.teleport((5.3, -0.4, 7.0))
    assert word[2] == 0 and point[2] == 7.0 and xy.contains(point)
    with pytest.raises(ValueError, match="parallel"):
        sol.Lattice.xy_loops((1.0, 2.0), (2.0, 4.0))
    # Scenes in them render, and say what they refuse.
    scene = sol.scene([sol.ball((1.0, 1.0, 0.3), 0.3)], quotient={"z_loop": 1.2},
                      camera=sol.camera(position=(0.2, 0.1, 0.5), forward=(1, 1, 0), up=(0, 0, 1)))
    assert scene.to_dict()["quotient"] == {"z_loop": 1.2}
    assert (sol.render_cpu(scene, 16, 12)["object"] > 0).any()
    with pytest.raises(ValueError, match="objects\\[0\\].axis: a tube along z does not fit xy loops"):
        sol.scene([sol.tube("z", (0, 0, 0), 0.1)], quotient={"xy_loops": [[1, 0], [0, 1]]})


def test_materials():
    # A glowing ball shows its emission over its ambient-lit colour; a mirror's keys round-trip.
    scene = sol.scene([sol.ball((0.7, 0.7, 0.0), 0.3, color=(0.4, 0.4, 0.4), emission=(0.25, 0.5, 1.0)),
                       sol.plane_z(-1.0, mirror=0.5)],
                      camera=sol.camera(position=(0, 0, 0), forward=(1, 1, 0), up=(0, 0, 1), fov=40),
                      lights=[], ambient=0.5, max_bounces=2)
    fields = scene.to_dict()
    assert fields["objects"][0]["emission"] == [0.25, 0.5, 1.0] and fields["objects"][1]["mirror"] == 0.5
    assert fields["max_bounces"] == 2
    image = sol.render_cpu(scene, 9, 9)
    assert np.allclose(image["rgba"][4, 4, :3], (0.45, 0.7, 1.2), atol=1e-6)
    # The material by the file's name: a mirror-material floor round-trips, and its mirror share is refused by name.
    tinted = scene.replace(objects=[fields["objects"][0], sol.plane_z(-1.0, material="mirror", color=(0.9, 0.5, 0.25))])
    assert tinted.to_dict()["objects"][1]["material"] == "mirror"
    with pytest.raises(sol.InvalidArgumentError, match=r"objects\[1\].mirror is the diffuse material's share"):
        sol.scene([sol.ball((0.7, 0.7, 0.0), 0.3), sol.plane_z(-1.0, material="mirror", mirror=0.5)])


def test_spreading_along_the_z_axis():
    assert sol.sphere_area_density((0, 0, 1), 2.0) == pytest.approx(math.sinh(2.0) ** 2, rel=1e-10)


def test_geodesic_sphere_vertices_at_the_radius():
    vertices, triangles = sol.geodesic_sphere((0.2, 0.1, -0.3), 2.0, 4)
    assert vertices.shape == (4 * 16 + 2, 3) and triangles.shape == (8 * 16, 3)
    assert np.allclose(sol.distances((0.2, 0.1, -0.3), vertices), 2.0, atol=1e-9)
    with pytest.raises(ValueError, match="radius must be in"):
        sol.geodesic_sphere((0, 0, 0), 7.0)
    # Beyond sqrt(2) pi: still on the sphere, and equal to the library's own vertices.
    v5, t5 = sol.geodesic_sphere((0, 0, 0), 5.0, 6)
    assert np.allclose(sol.distances((0, 0, 0), v5), 5.0, atol=1e-9)
    assert t5.max() == len(v5) - 1


def test_cut_time_and_curves():
    assert sol.cut_time((1, 1, 0)) == pytest.approx(math.sqrt(2) * math.pi, rel=1e-15)
    assert math.isinf(sol.cut_time((1, 0, 0.5)))
    curves = sol.cut_locus_curves((0, 0, 0), [5.0], 5)
    assert len(curves) == 4 and all(c.shape == (5, 3) for c in curves)
    middle = curves[0][2]
    ways = sol.minimising_geodesics((0, 0, 0), tuple(middle))
    assert len(ways) == 2 and all(w[1] == pytest.approx(5.0, abs=1e-8) for w in ways)
    lines = sol.geodesic_polylines((0.1, 0, 0), np.array([[1.0, 0.2, 0.3], [0, 0, 1]]), 2.0, 4)
    assert len(lines) == 2 and lines[0].shape == (5, 3)
    one = sol.flow((0.1, 0, 0), (1.0, 0.2, 0.3), 1.5)
    assert np.allclose(lines[0][3], one[0], atol=1e-12)
    with pytest.raises(ValueError, match="radii must be in"):
        sol.cut_locus_curves((0, 0, 0), [4.0])
    with pytest.raises(ValueError, match=r"directions must have shape"):
        sol.geodesic_polylines((0, 0, 0), np.zeros((2, 2)), 1.0)
    with pytest.raises(ValueError, match="non-zero"):
        sol.geodesic_polylines((0, 0, 0), np.zeros(3), 1.0)


def test_load_scene_reads_a_file():
    scene = sol.preset_scene("sandwich")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "s.json")
        with open(path, "w") as f:
            f.write(scene.to_json())
        again = sol.load_scene(path)
        assert again.to_json() == scene.to_json()
        with pytest.raises(ValueError):
            sol.load_scene(os.path.join(tmp, "missing.json"))


def test_scenes_round_trip():
    assert "lattice-balls" in sol.preset_names()
    scene = sol.preset_scene("sandwich")
    again = sol.parse_scene(scene.to_json())
    assert again.to_json() == scene.to_json()
    assert scene.object_count == 2


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


@pytest.mark.skipif("SOLRENDER" not in os.environ, reason="solrender not built")
def test_render_matches_solrender():
    import matplotlib.image
    result = sol.render_cpu(sol.preset_scene("sandwich"), 32, 24)
    assert result["rgba"].shape == (24, 32, 4) and result["point"].shape == (24, 32, 3)
    assert np.isfinite(result["rgba"]).all()
    assert (result["object"] > 0).any()
    with tempfile.TemporaryDirectory() as tmp:
        png = os.path.join(tmp, "sandwich.png")
        subprocess.run([os.environ["SOLRENDER"], "--device", "cpu", "--scene", "sandwich", "--width", "32", "--height",
                        "24", "-o", png], check=True, capture_output=True)
        written = matplotlib.image.imread(png)[:, :, :3]
    # solrender's PNG is the same render sRGB-encoded to 8 bits: within rounding (half of 1/255, and a little).
    assert np.abs(srgb(result["rgba"][:, :, :3]) - written).max() < 0.6 / 255


@pytest.mark.skipif("SOLRENDER" not in os.environ, reason="solrender not built")
def test_path_tracing_is_solrenders():
    # transport="path" with a seed is solrender's --transport path --seed on the CPU: the same paths, so the same
    # image to 8-bit rounding; another seed gives another image; a name other than "direct" or "path", or a negative
    # seed, is refused by name.
    import matplotlib.image
    scene = sol.parse_scene('{"camera": {"position": [0, 0, 0], "forward": [1, 0.2, 0.1]}, "lights": [],'
                            ' "objects": [{"type": "box", "center": [0, 0, 0], "half_size": [0.5, 0.4, 0.3], "color": [0.6, 0.6, 0.6],'
                            ' "emission": [0.2, 0.3, 0.4]}]}')
    result = sol.render_cpu(scene, 12, 8, samples=4, transport="path", seed=3)
    assert np.isfinite(result["rgba"]).all() and (result["object"] == 1).all()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "inside.json")
        with open(path, "w") as f:
            f.write(scene.to_json())
        png = os.path.join(tmp, "inside.png")
        subprocess.run([os.environ["SOLRENDER"], "--device", "cpu", "--scene", path, "--width", "12", "--height", "8",
                        "--spp", "4", "--transport", "path", "--seed", "3", "-o", png], check=True, capture_output=True)
        written = matplotlib.image.imread(png)[:, :, :3]
    assert np.abs(srgb(result["rgba"][:, :, :3]) - written).max() < 0.6 / 255
    other = sol.render_cpu(scene, 12, 8, samples=4, transport="path", seed=4)
    assert not np.array_equal(other["rgba"], result["rgba"])
    with pytest.raises(ValueError, match="transport"):
        sol.render_cpu(scene, 12, 8, transport="paths")
    with pytest.raises(ValueError, match="seed"):
        sol.CpuRenderer(scene).render(12, 8, transport="path", seed=-1)


def test_cpu_renderer_keeps_its_world():
    # A renderer prepares the world once and renders it again and again: each render is render_cpu's, to the bit,
    # and set_scene moves it to another world.
    lattice = sol.preset_scene("lattice-balls")
    renderer = sol.CpuRenderer(lattice)
    once = sol.render_cpu(lattice, 24, 16)
    for _ in range(2):
        again = renderer.render(24, 16)
        for key in ("rgba", "object", "distance", "point", "steps"):
            assert np.array_equal(again[key], once[key]), key
    plane = sol.preset_scene("plane")
    renderer.set_scene(plane)
    assert np.array_equal(renderer.render(24, 16)["rgba"], sol.render_cpu(plane, 24, 16)["rgba"])
    assert not np.array_equal(renderer.render(24, 16)["rgba"], once["rgba"])
    with pytest.raises(ValueError, match="width"):
        renderer.render(0, 16)


def test_cpu_renderer_takes_a_new_scene_while_a_thread_renders():
    # set_scene from one thread while another renders with the same renderer (which once freed the world under
    # the render: a segmentation fault): the render finishes with the world it started with, to the bit, and the
    # renders after it take the new one.
    import threading
    import time
    lattice, plane = sol.preset_scene("lattice-balls"), sol.preset_scene("plane")
    renderer = sol.CpuRenderer(lattice)
    results = {}
    started = threading.Event()

    def render():
        started.set()
        results["image"] = renderer.render(96, 96)

    thread = threading.Thread(target=render)
    thread.start()
    started.wait()
    time.sleep(0.05)
    renderer.set_scene(plane)
    thread.join()
    assert np.array_equal(results["image"]["rgba"], sol.render_cpu(lattice, 96, 96)["rgba"])
    assert np.array_equal(renderer.render(24, 16)["rgba"], sol.render_cpu(plane, 24, 16)["rgba"])


def test_bad_arguments_raise_value_errors():
    with pytest.raises(ValueError, match="direction"):
        sol.flow((0, 0, 0), (0, 0, 0), 1.0)
    # A NaN or infinite number in a scene names its field (JSON has neither: it was "malformed JSON").
    with pytest.raises(sol.InvalidArgumentError, match=r"objects\[0\]\.radius must be a finite number, got nan"):
        sol.scene([sol.ball((0, 0, 0), float("nan"))])
    with pytest.raises(sol.InvalidArgumentError, match=r"camera\.position\[2\] must be a finite number, got inf"):
        sol.scene([sol.plane_z(-1)], camera={"position": (0, 0, float("inf"))})
    with pytest.raises(ValueError, match="unknown preset 'tube'"):
        sol.preset_scene("tube")
    with pytest.raises(ValueError, match="shape"):
        sol.distances((0, 0, 0), np.zeros((4, 2)))
    with pytest.raises(ValueError):
        sol.render_cpu(sol.preset_scene("plane"), 0, 10)
    with pytest.raises(ValueError):
        sol.parse_scene('{"objects": [{"type": "ball", "radius": -1}]}')


def test_camera_rays_follow_the_camera_convention():
    # The plane scene looks straight down (forward (0, 0, -1), up (0, 1, 0)) with a 90 degree vertical field of
    # view: the middle pixel of an odd image looks straight down, and the top and bottom rows' middle rays are
    # 45 degrees off it (to within half a pixel), up the image being +y.
    scene = sol.preset_scene("plane")
    d = sol.camera_rays(scene, 5, 101)
    assert d.shape == (101, 5, 3)
    assert np.allclose(np.linalg.norm(d, axis=2), 1.0)
    assert np.allclose(d[50, 2], (0, 0, -1), atol=1e-15)
    top = math.degrees(math.acos(-d[0, 2, 2]))
    assert top == pytest.approx(45.0 * 100 / 101, abs=0.5) and d[0, 2, 1] > 0
    # A ray the renderer says hits the plane does, at the arc length it reports.
    r = sol.render_cpu(scene, 5, 101)
    end = sol.flow(tuple(scene.camera_position), d[50, 2], float(r["distance"][50, 2]))[0]
    assert abs(end[2]) < 1e-4
    with pytest.raises(ValueError, match="width and height"):
        sol.camera_rays(scene, 0, 4)


def test_messages_are_text_and_values_shown_as_written():
    # Bytes that are not UTF-8 are named in the message, not lost with it.
    with pytest.raises(ValueError, match=r"malformed JSON.*\\xFF"):
        sol.parse_scene(b"\xff\xfe")
    # A string where a number belongs is shown quoted.
    with pytest.raises(ValueError, match=r"'camera.fov' must be a number, got \"4\""):
        sol.parse_scene('{"camera": {"fov": "4"}, "objects": [{"type": "plane_z"}]}')


def test_unbounded_work_is_refused_up_front():
    # Arguments whose cost has no useful bound are refused at once with the figure (each would run for
    # minutes, or forever).
    with pytest.raises(ValueError, match="integration steps"):
        sol.sphere_area_density((1, 0, 0), 1e9)
    with pytest.raises(ValueError, match="integration steps"):
        sol.sphere_area_density((1, 0, 0), 1e308)
    with pytest.raises(ValueError, match=r"1000000 directions x 100001 points = 1e\+11 points; at most 1e\+07"):
        sol.geodesic_polylines((0, 0, 0), np.tile((1.0, 0.0, 0.0), (1000000, 1)), 3.0, 100000)
    with pytest.raises(ValueError, match=r"100000 radii x 4 arcs x 64 samples = 2.56e\+07 points"):
        sol.cut_locus_curves((0, 0, 0), [5.0] * 100000, 64)
    # An exact light's reach in the quotient that would need images beyond those enumerated.
    scene = json.loads(sol.preset_scene("lattice-balls").to_json())
    scene["lights"] = [{"type": "point", "position": [0.3, 0.2, 0.4], "exact": True, "reach": 10}]
    with pytest.raises(ValueError, match=r"lights\[0\].reach: reach 10 in the quotient .* at most 1\.\d\d"):
        sol.CpuRenderer(sol.parse_scene(json.dumps(scene)))


@pytest.mark.parametrize("call", ["render", "polylines", "distances"])
def test_long_calls_hear_ctrl_c(call):
    # Ctrl-C (here _thread.interrupt_main, which raises SIGINT's KeyboardInterrupt in the main thread) stops a
    # long call within a fraction of a second, where it used to run to its end (61 s for a render).
    import _thread
    import threading
    import time

    work = {
        "render": lambda: sol.render_cpu(sol.preset_scene("spheres"), 2048, 2048, 16),  # minutes here
        "polylines": lambda: sol.geodesic_polylines((0, 0, 0), np.tile((1.0, 0.2, 0.3), (10000, 1)), 3.0, 999),
        "distances": lambda: sol.distances((0, 0, 0), np.tile((3.0, 1.0, 0.5), (2000000, 1))),
    }[call]
    timer = threading.Timer(0.5, _thread.interrupt_main)
    started = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        work()
        time.sleep(30)  # finished before the timer: the interrupt arrives here and the test fails on time
    elapsed = time.monotonic() - started
    timer.cancel()
    assert elapsed < 5.0, f"{call} stopped {elapsed:.1f} s after it started (interrupted at 0.5 s)"


def test_scenes_built_from_python_are_the_scene_files():
    # A preset rebuilt from its own fields through sol.scene is the same scene (the same JSON), and the builders
    # give the file's keys: the scene file's reader is the one source of names, defaults and checks.
    for name in sol.preset_names():
        fields = sol.preset_scene(name).to_dict()
        objects = fields.pop("objects")
        assert sol.scene(objects, **fields).to_json() == sol.preset_scene(name).to_json(), name
    built = sol.scene([sol.plane_z(-1, pattern="checker"), sol.ball((1, 0, 0), 0.3, color=(0.9, 0.3, 0.2))],
                      camera=sol.camera(position=(0, 0, 0.5), forward=(1, 0, -0.3), fov=70),
                      lights=[sol.point_light((0, 0, 1), intensity=3)])
    text = ('{"objects": [{"type": "plane_z", "c": -1, "pattern": "checker"},'
            ' {"type": "ball", "center": [1, 0, 0], "radius": 0.3, "color": [0.9, 0.3, 0.2]}],'
            ' "camera": {"position": [0, 0, 0.5], "forward": [1, 0, -0.3], "fov": 70},'
            ' "lights": [{"type": "point", "position": [0, 0, 1], "intensity": 3}]}')
    assert built.to_json() == sol.parse_scene(text).to_json()
    # Errors name the field, as the file's would, and are ValueErrors.
    with pytest.raises(sol.InvalidArgumentError, match=r"objects\[0\].radius must be finite and > 0"):
        sol.scene([sol.ball((0, 0, 0), -1)])
    with pytest.raises(ValueError, match=r"unknown key 'colour' in objects\[0\]"):
        sol.scene([sol.ball((0, 0, 0), 1, colour=(1, 0, 0))])
    with pytest.raises(ValueError, match=r"camera.fov must be in \(0, 180\)"):
        sol.camera(fov=200)
    # ... and no place in the JSON that sol.scene wrote for them.
    for build in (lambda: sol.scene([sol.ball((0, 0, 0), -1)]), lambda: sol.camera(fov=200),
                  lambda: sol.scene([sol.plane_z()], max_steps=-3), lambda: sol.preset_scene("plane").replace(ambient=2)):
        with pytest.raises(sol.InvalidArgumentError) as raised:
            build()
        assert "line 1" not in str(raised.value) and "column" not in str(raised.value), raised.value


def test_composites_are_the_scene_files():
    # sol.union, sol.intersection and sol.difference write the file's composites; a part's appearance key is
    # refused naming it, and the composite renders the same on the CPU as its scene file does.
    hollow = sol.difference(sol.box((0, 0, 0), (0.3, 0.3, 0.3)), sol.ball((0, -0.3, 0.2), 0.25), color=(0.9, 0.5, 0.3))
    built = sol.scene([sol.plane_z(-0.6), hollow, sol.intersection(sol.ball((1, 0, 0), 0.3), sol.box((1, 0, 0), (0.2, 0.2, 0.2)))],
                      camera=sol.camera(position=(0, -0.9, 0.9), forward=(0, 0.5, -0.85), up=(0, 0.85, 0.5)))
    text = ('{"objects": [{"type": "plane_z", "c": -0.6}, {"type": "difference", "color": [0.9, 0.5, 0.3],'
            ' "a": {"type": "box", "center": [0, 0, 0], "half_size": [0.3, 0.3, 0.3]},'
            ' "b": {"type": "ball", "center": [0, -0.3, 0.2], "radius": 0.25}},'
            ' {"type": "intersection", "a": {"type": "ball", "center": [1, 0, 0], "radius": 0.3},'
            ' "b": {"type": "box", "center": [1, 0, 0], "half_size": [0.2, 0.2, 0.2]}}],'
            ' "camera": {"position": [0, -0.9, 0.9], "forward": [0, 0.5, -0.85], "up": [0, 0.85, 0.5]}}')
    assert built.to_json() == sol.parse_scene(text).to_json()
    assert built.to_dict()["objects"][1]["type"] == "difference"
    image = sol.render_cpu(built, 24, 16)
    assert np.array_equal(image["rgba"], sol.render_cpu(sol.parse_scene(text), 24, 16)["rgba"])
    assert np.any(image["object"] == 2)
    with pytest.raises(sol.InvalidArgumentError, match=r"'color' in objects\[0\].a: a part takes its kind's keys alone"):
        sol.scene([sol.union(sol.ball((0, 0, 0), 0.2, color=(1, 0, 0)), sol.box((0, 0, 0), (0.1, 0.1, 0.1)))])


def test_replace_changes_only_what_it_names():
    scene = sol.preset_scene("spheres")
    moved = scene.replace(camera={"position": (0.2, 0.1, 0.3)})
    before, after = scene.to_dict(), moved.to_dict()
    assert after["camera"]["position"] == [0.2, 0.1, 0.3]
    assert after["camera"]["forward"] == before["camera"]["forward"] and after["objects"] == before["objects"]
    assert np.allclose(moved.camera.position, (0.2, 0.1, 0.3)) and np.allclose(moved.camera.forward, scene.camera.forward)
    # A renderer of the first scene, from the moved scene's camera, renders the moved scene.
    from_camera = sol.CpuRenderer(scene).render(24, 16, camera=moved.camera)
    assert np.array_equal(from_camera["rgba"], sol.render_cpu(moved, 24, 16)["rgba"])
    assert sol.scene(**{"objects": before["objects"]}).object_count == len(before["objects"])


def test_defaults_are_the_programs():
    # solrender renders 512 x 512 at the scene's "samples"; solshape meshes spheres at 32 subdivisions
    # (8 * 32^2 triangles below sqrt(2) pi).
    plane = sol.scene([sol.plane_z(-1, pattern="checker")], samples=2, camera=sol.camera(fov=120))
    assert sol.render_cpu(plane)["rgba"].shape == (512, 512, 4)
    once = sol.render_cpu(plane, 8, 6)
    assert np.array_equal(once["rgba"], sol.render_cpu(plane, 8, 6, samples=2)["rgba"])
    assert not np.array_equal(once["rgba"], sol.render_cpu(plane, 8, 6, samples=1)["rgba"])
    vertices, triangles = sol.geodesic_sphere((0, 0, 0), 1.0)
    assert len(triangles) == 8 * 32 ** 2


@pytest.mark.skipif("SOLRENDER" not in os.environ, reason="solrender not built")
def test_a_scene_built_in_python_saves_the_png_solrender_writes():
    import matplotlib.image
    scene = sol.scene([sol.plane_z(-1, pattern="checker"), sol.ball((1, 0.2, -0.4), 0.3, color=(0.9, 0.3, 0.2))],
                      camera=sol.camera(position=(0, 0, 0.2), forward=(1, 0, -0.3), fov=70),
                      lights=[sol.point_light((0.3, 0, 0.8), intensity=3)])
    with tempfile.TemporaryDirectory() as tmp:
        ours, theirs, scene_file = (os.path.join(tmp, n) for n in ("python.png", "solrender.png", "scene.json"))
        image = sol.render_cpu(scene, 40, 30)
        assert sol.save(ours, image["rgba"]) == 0
        with open(scene_file, "w") as f:
            f.write(scene.to_json())
        subprocess.run([os.environ["SOLRENDER"], "--device", "cpu", "--scene", scene_file, "--width", "40", "--height",
                        "30", "-o", theirs], check=True, capture_output=True)
        a, b = matplotlib.image.imread(ours), matplotlib.image.imread(theirs)
        # The same CPU render, the same writer: the same bytes per pixel.
        assert a.shape == b.shape == (30, 40, 4) and np.array_equal(a, b)
        # And srgb8 is those bytes (independently of the writer: the sRGB formula, within rounding).
        bytes8 = sol.srgb8(image["rgba"])
        assert np.array_equal(bytes8, np.round(a * 255).astype(np.uint8))
        assert np.abs(bytes8[:, :, :3] / 255.0 - srgb(np.clip(image["rgba"][:, :, :3], 0, 1))).max() < 0.6 / 255
    with pytest.raises(ValueError, match="shape"):
        sol.save(os.path.join(tmp, "bad.png"), np.zeros((4, 4)))


@pytest.mark.skipif("SOLRENDER" not in os.environ, reason="solrender not built")
def test_exposure_and_tone_are_solrenders():
    import matplotlib.image
    scene = sol.preset_scene("plane").replace(exposure=2.5, tone="aces")
    with tempfile.TemporaryDirectory() as tmp:
        ours, theirs, scene_file = (os.path.join(tmp, n) for n in ("python.png", "solrender.png", "scene.json"))
        image = sol.render_cpu(scene, 24, 16)
        assert sol.save(ours, image["rgba"], exposure=2.5, tone="aces") == 0
        with open(scene_file, "w") as f:
            f.write(scene.to_json())
        subprocess.run([os.environ["SOLRENDER"], "--device", "cpu", "--scene", scene_file, "--width", "24", "--height",
                        "16", "-o", theirs], check=True, capture_output=True)
        a, b = matplotlib.image.imread(ours), matplotlib.image.imread(theirs)
        assert np.array_equal(a, b)  # the scene's keys reach solrender's PNG as Python's keywords reach sol.save
        bytes8 = sol.srgb8(image["rgba"], exposure=2.5, tone="aces")
        assert np.array_equal(bytes8, np.round(a * 255).astype(np.uint8))
        # Narkowicz's ACES fit, from its definition, after the exposure's 2^2.5.
        x = np.maximum(image["rgba"][:, :, :3].astype(np.float64), 0) * 2 ** 2.5
        shown = np.minimum(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 1.0)
        assert np.abs(bytes8[:, :, :3] / 255.0 - srgb(shown)).max() < 0.6 / 255
        assert not np.array_equal(bytes8, sol.srgb8(image["rgba"]))
    with pytest.raises(ValueError, match="tone must be one of clamp, aces"):
        sol.srgb8(image["rgba"], tone="filmic")
    with pytest.raises(ValueError, match="exposure"):
        sol.srgb8(image["rgba"], exposure=float("nan"))


def test_a_lens_focuses_every_ray_on_its_pixel_rays_focus_point():
    # Depth of field from Python: the camera's keys, the lens ray through
    # each lens sample reaching the pixel ray's focus point F = exp(f u)
    # (sol.flow from the lens point), and look_at focusing on the point.
    cam = sol.camera(position=[0, 0, 0], forward=[1, 0.2, 0.1], aperture=0.1, focus_distance=2.0)
    assert cam.aperture == 0.1 and cam.focus_distance == 2.0
    u = np.array([1.0, 0.2, 0.1]) / np.linalg.norm([1.0, 0.2, 0.1])
    assert tuple(sol.lens_sample(0)) == (0.0, 0.0)
    focus = np.asarray(sol.flow([0, 0, 0], u, 2.0)[0])
    for k in range(1, 6):
        disk = sol.lens_sample(k)
        assert np.hypot(*disk) <= 1.0
        ray = sol.lens_ray(cam, u, disk)
        assert ray["focused"]
        assert np.linalg.norm(ray["start"]) > 1e-3
        end = np.asarray(sol.flow(ray["start"], ray["direction"], ray["focus_length"])[0])
        assert np.linalg.norm(end - focus) < 1e-9
    aimed = sol.camera(position=[0.1, 0.2, 0.3], look_at=[1.7, -0.4, 0.9], aperture=0.1)
    assert abs(aimed.focus_distance - sol.aim([0.1, 0.2, 0.3], [1.7, -0.4, 0.9])["distance"]) < 1e-9
    with pytest.raises(sol.InvalidArgumentError, match="camera.aperture"):
        sol.camera(aperture=2.0)


def test_glossy_objects_from_python():
    # The glossy material's keyword and its check; a white glossy furnace
    # (a box about the camera, emitting 0.5, albedo 0.6) holds 0.5 / 0.4.
    wall = sol.box([0.1, -0.1, 0.05], [0.6, 0.5, 0.4], color=[0.6, 0.6, 0.6], emission=[0.5, 0.5, 0.5],
                   material="glossy", roughness=0.5)
    scene = sol.scene([wall], camera={"position": [0, 0, 0], "forward": [1, 0.2, 0.1]}, lights=[])
    image = sol.Renderer(scene, device="cpu", transport="path").render(6, 6, samples=16, seed=3)["rgba"]
    assert abs(float(np.mean(image[..., 0])) - 1.25) < 0.1
    with pytest.raises(sol.InvalidArgumentError, match="roughness"):
        sol.scene([sol.ball([1, 0, 0], 0.3, material="mirror", roughness=0.5)])


def test_glass_of_index_one_is_unseen_from_python():
    # The glass material's keywords: a clear ball of index 1 in front of a
    # coloured one leaves the image as it was; index 1.5 bends it; a glass
    # plane is refused by name.
    behind = sol.ball([2.5, 0.2, 0.3], 0.3, color=[0.9, 0.3, 0.2], pattern="circles")
    floor = sol.plane_z(0.0, color=[0.8, 0.8, 0.8], pattern="checker")
    camera = {"position": [0, 0, 0.4], "look_at": [2, 0, 0.3], "up": [0, 0, 1]}
    plain = sol.scene([floor, behind], camera=camera, lights=[], ambient=1.0)
    def image(ior):
        glass = sol.ball([1.5, 0, 0.35], 0.3, color=[1, 1, 1], material="glass", ior=ior)
        return sol.Renderer(sol.scene([floor, behind, glass], camera=camera, lights=[], ambient=1.0),
                            device="cpu").render(24, 18)["rgba"]
    reference = sol.Renderer(plain, device="cpu").render(24, 18)["rgba"]
    assert np.max(np.abs(image(1.0) - reference)) < 1e-5
    assert np.max(np.abs(image(1.5) - reference)) > 0.05
    with pytest.raises(sol.InvalidArgumentError, match="glass is for solids"):
        sol.scene([sol.plane_z(0.0, material="glass")])


@pytest.mark.skipif(not hasattr(sol, "save"), reason="this sol writes no images")
def test_a_texture_from_python_colours_the_albedo(tmp_path):
    # A one-texel texture of linear (0.5, 0.25, 1.0), saved as an 8-bit sRGB PNG and read back through the scene's
    # "texture" key (relative to the working directory for sol.scene): every hit's albedo is the object's colour times
    # it (within the 8-bit file's rounding, 0.5/255 encoded: under 0.004 linear).
    texel = np.array([[[0.5, 0.25, 1.0]]], dtype=np.float32)
    path = tmp_path / "one.png"
    assert sol.save(str(path), texel) == 0
    scene = sol.scene([sol.plane_z(-1.0, color=[0.8, 0.6, 1.0], texture=str(path), texture_cells=[2, 2])])
    image = sol.render_cpu(scene, width=16, height=12)
    hit = image["object"] == 1
    assert hit.sum() > 20
    assert np.allclose(image["albedo"][hit], np.array([0.4, 0.15, 1.0]), atol=0.004)
    assert "texture_cells" in scene.to_json() and "one.png" in scene.to_json()
    # Named by its absolute path once read, so the scene rebuilt from its JSON finds it from anywhere.
    here = os.getcwd()
    try:
        os.chdir("/")
        again = scene.replace(max_steps=300)
    finally:
        os.chdir(here)
    assert np.allclose(sol.render_cpu(again, width=16, height=12)["albedo"][hit], np.array([0.4, 0.15, 1.0]), atol=0.004)
    with pytest.raises(ValueError, match="texture_cells"):
        sol.scene([sol.plane_z(-1.0, texture=str(path), texture_cells=[3, 1])])
