"""sol.Renderer, either device behind one class: against solrender with the same device, options and seed (both
as float EXR, compared by idiff without tolerance), the CPU device against sol.render_cpu, the choice of device and its
errors, progress and Ctrl-C. ctest names solrender in SOLRENDER and idiff in IDIFF."""
import json
import os
import subprocess
import tempfile

import numpy as np
import pytest

import sol

SOLRENDER = os.environ.get("SOLRENDER")
IDIFF = os.environ.get("IDIFF")
needs_vulkan = pytest.mark.skipif(not sol.has_vulkan(), reason="this sol has no Vulkan kernel")
needs_solrender = pytest.mark.skipif(not SOLRENDER or not IDIFF, reason="solrender or idiff not there")


def same_as_solrender(scene, image, *args):
    """Whether solrender with `args` writes the float image `image` is: both as EXR (float32, lossless), compared
    by OpenImageIO's idiff with no tolerance (a failure shows idiff's report)."""
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.json")
        with open(path, "w") as f:
            f.write(scene.to_json())
        theirs, ours = os.path.join(tmp, "solrender.exr"), os.path.join(tmp, "python.exr")
        subprocess.run([SOLRENDER, "--scene", path, *[str(a) for a in args], "-o", theirs], check=True,
                       capture_output=True)
        assert sol.save(ours, image) == 0
        compared = subprocess.run([IDIFF, "-fail", "0", "-warn", "0", ours, theirs], capture_output=True, text=True)
        assert compared.returncode == 0, compared.stdout + compared.stderr
        return True


@needs_vulkan
@needs_solrender
@pytest.mark.parametrize("preset, options", [
    ("lattice-balls", {"samples": 2}),
    ("sandwich", {"samples": 3, "transport": "path", "seed": 7}),
    ("plane", {"samples": 1, "stereo": True, "ipd": 0.2}),
])
def test_the_kernel_from_python_is_solrenders(preset, options):
    # The same kernel on the same device with the same options and seed: the same float image, bit for bit (the
    # renderer's tiling of long renders into dispatches changes no pixel).
    scene = sol.preset_scene(preset)
    r = sol.Renderer(scene, device="vulkan", transport=options.get("transport", "direct"))
    assert r.device == "vulkan" and r.description.startswith("vulkan")
    got = r.render(24, 16, progress=False, **options)
    args = ["--device", "vulkan", "--width", 24, "--height", 16, "--spp", options["samples"]]
    if options.get("transport") == "path":
        args += ["--transport", "path", "--seed", options["seed"]]
    if options.get("stereo"):
        args += ["--stereo", "--ipd", options["ipd"]]
    assert got["rgba"].shape == (16, 48 if options.get("stereo") else 24, 4)
    assert same_as_solrender(scene, got["rgba"], *args)
    assert got["device_ms"] > 0


@needs_vulkan
@needs_solrender
def test_denoised_from_python_is_solrenders():
    # denoise=True is solrender's --denoise: the same filter on the same device over the same render, float for
    # float; without aovs the dict holds the colour alone, with them the guides too.
    scene = sol.preset_scene("sandwich")
    r = sol.Renderer(scene, device="vulkan", transport="path")
    raw = r.render(24, 16, samples=2, seed=3, progress=False)
    got = r.render(24, 16, samples=2, seed=3, progress=False, denoise=True, aovs=False)
    assert set(got) >= {"rgba"} and "albedo" not in got and "object" not in got
    assert np.abs(got["rgba"] - raw["rgba"]).max() > 0.01  # the filter changed the colour
    assert raw["albedo"].shape == (16, 24, 3) and raw["normal"].shape == (16, 24, 3)
    assert raw["emission"].shape == (16, 24, 3) and "emission" not in got
    assert same_as_solrender(scene, got["rgba"], "--device", "vulkan", "--width", 24, "--height", 16, "--spp", 2,
                             "--transport", "path", "--seed", 3, "--denoise")
    with pytest.raises(ValueError, match="first_sample"):
        r.render(24, 16, samples=2, first_sample=2, aovs=False, denoise=True, progress=False)


@needs_vulkan
def test_kernel_and_cpu_agree_on_hits():
    # The kernel (float) and the CPU reference (double) through one interface: the same objects hit at the same
    # points, to the kernel's float tolerance, in a world of the quotient.
    scene = sol.preset_scene("lattice-balls")
    kernel = sol.Renderer(scene, device="vulkan").render(20, 14, progress=False)
    cpu = sol.Renderer(scene, device="cpu").render(20, 14, progress=False)
    same = kernel["object"] == cpu["object"]
    assert same.mean() > 0.95  # pixels at an object's silhouette may differ
    hit = same & (cpu["object"] > 0)
    assert hit.any()
    # (float arithmetic along geodesics of length up to 12 here: 1.2e-4 relative measured, 5e-4 allowed)
    assert (np.abs(kernel["distance"][hit] - cpu["distance"][hit]) / np.maximum(1.0, cpu["distance"][hit])).max() < 5e-4


def test_the_cpu_device_is_render_cpu():
    scene = sol.preset_scene("sandwich")
    r = sol.Renderer(scene, device="cpu")
    assert r.device == "cpu" and r.notes == []
    got = r.render(16, 12, samples=2, progress=False)
    want = sol.render_cpu(scene, 16, 12, samples=2)
    for key in ("rgba", "object", "distance", "point", "steps"):
        assert np.array_equal(got[key], want[key]), key
    colour_only = r.render(16, 12, samples=2, aovs=False, progress=False)
    assert set(colour_only) == {"rgba", "rays_out_of_steps", "device_ms"}
    assert np.array_equal(colour_only["rgba"], want["rgba"])


@pytest.mark.parametrize("device", ["cpu", "vulkan"])
def test_ranges_of_samples_make_the_whole_render(device):
    # More samples later: renders of consecutive ranges (first_sample) weighted by their counts are one render of
    # them all (the same pixel points and paths), to float rounding.
    if device == "vulkan" and not sol.has_vulkan():
        pytest.skip("this sol has no Vulkan kernel")
    scene = sol.preset_scene("plane")
    r = sol.Renderer(scene, device=device, transport="path")
    whole = r.render(16, 12, samples=5, seed=4, aovs=False, progress=False)["rgba"]
    a = r.render(16, 12, samples=2, seed=4, aovs=False, progress=False)["rgba"]
    b = r.render(16, 12, samples=3, seed=4, first_sample=2, aovs=False, progress=False)["rgba"]
    assert np.abs((2 * a.astype(np.float64) + 3 * b) / 5 - whole).max() < 1e-5
    assert not np.array_equal(a, whole)
    with pytest.raises(ValueError, match="AOVs"):
        r.render(16, 12, samples=3, first_sample=2, progress=False)


def test_a_noise_target_or_a_time_limit_stops_the_render():
    # solrender's --noise-target and --time-limit: batches until the estimate is reached (path-traced plane, 16 x 12:
    # about 500 paths for 0.2 on the CPU), or before the time is up.
    r = sol.Renderer(sol.preset_scene("plane"), device="cpu", transport="path")
    out = r.render(16, 12, seed=5, noise_target=0.2, aovs=False, progress=False)
    assert out["noise"] <= 0.2 and 2 <= out["samples"] <= 4096 and out["rgba"].shape == (12, 16, 4)
    timed = r.render(16, 12, seed=5, time_limit=0.3, aovs=False, progress=False)
    assert timed["seconds"] < 0.3 * 1.2 and timed["samples"] >= 2
    with pytest.raises(ValueError, match="time_limit must be in"):
        r.render(16, 12, time_limit=-1, progress=False)


def test_the_device_is_chosen_and_errors_name_the_keyword():
    with pytest.raises(sol.InvalidArgumentError, match='device must be "auto", "vulkan" or "cpu", not "gpu"'):
        sol.Renderer(sol.preset_scene("plane"), device="gpu")
    with pytest.raises(sol.InvalidArgumentError, match="transport"):
        sol.Renderer(sol.preset_scene("plane"), transport="paths")
    with pytest.raises(sol.InvalidArgumentError, match="seed"):
        sol.Renderer(sol.preset_scene("plane"), device="cpu").render(4, 4, seed=-1)
    # Exact balls of a radius above 2 are rendered on the CPU only (the kernel's float solves): "auto"
    # takes it and says why; "vulkan" refuses, naming the keyword that would render it.
    scene = json.loads(sol.preset_scene("plane").to_json())
    scene["objects"] = [{"type": "ball", "center": [1, 0, 3], "radius": 2.5, "exact": True}]
    large = sol.parse_scene(json.dumps(scene))
    auto = sol.Renderer(large, transport="path")
    assert auto.device == "cpu"
    if sol.has_vulkan():
        assert any("radius above" in note and "CPU" in note for note in auto.notes), auto.notes
        with pytest.raises(sol.UnsupportedError, match='device="cpu" or "auto"'):
            sol.Renderer(large, device="vulkan", transport="path")
    else:
        with pytest.raises(sol.UnsupportedError, match="without the Vulkan kernel"):
            sol.Renderer(large, device="vulkan", transport="path")


def test_progress_is_reported_and_its_errors_stop_the_render():
    fractions = []
    sol.Renderer(sol.preset_scene("plane"), device="auto").render(32, 32, progress=fractions.append)
    assert fractions and fractions[-1] == 1.0 and fractions == sorted(fractions)

    class Stop(Exception):
        pass

    def stop(fraction):
        raise Stop(fraction)

    with pytest.raises(Stop):
        sol.Renderer(sol.preset_scene("plane"), device="cpu").render(64, 64, progress=stop)
    with pytest.raises(sol.InvalidArgumentError, match="progress must be a callable"):
        sol.Renderer(sol.preset_scene("plane"), device="cpu").render(4, 4, progress=3)


def test_the_text_bar_ends_its_line(capsys):
    # A bar shows for renders over half a second only; asked for, it goes to stderr and ends its line.
    import sol.renderer as module

    bar = module._ProgressBar("sol.Renderer (cpu)")
    bar._start -= 1.0
    bar(0.25)
    bar(1.0)
    bar.close()
    err = capsys.readouterr().err
    assert "25.0%" in err and "100.0%" in err and err.endswith("\n")
    assert "left" in err.split("\r")[1]


@pytest.mark.parametrize("device", ["cpu", "vulkan"])
def test_renders_hear_ctrl_c(device):
    # As sol.render_cpu: KeyboardInterrupt within a fraction of a second of device work (the kernel's dispatches
    # are tiled to about 50 ms).
    import _thread
    import threading
    import time

    if device == "vulkan" and not sol.has_vulkan():
        pytest.skip("this sol has no Vulkan kernel")
    r = sol.Renderer(sol.preset_scene("spheres"), device=device)
    r.render(4, 4, samples=16, progress=False)  # the kernel (the variant for these options) built before the clock starts
    # Twice: the first large render also makes its images and lists on the device (over a second on a loaded
    # 2-core machine, before any dispatch); the second, timed, is dispatches alone.
    for attempt in range(2):
        timer = threading.Timer(0.5, _thread.interrupt_main)
        started = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            r.render(1024, 4096, samples=16, progress=False)  # minutes on lavapipe or the CPU (rows of 16 samples: the CPU hears Ctrl-C between rows)
            time.sleep(30)
        elapsed = time.monotonic() - started
        timer.cancel()
    assert elapsed < 5.0, f"stopped {elapsed:.1f} s after it started (interrupted at 0.5 s)"


def test_set_scene_waits_for_a_render_under_way():
    # Another thread's set_scene while a render runs (both without the GIL) waits for that render, which finishes
    # with the world it started with: its image is the first scene's.
    import threading

    first, second = sol.preset_scene("sandwich"), sol.preset_scene("plane")
    r = sol.Renderer(first, device="cpu")
    want = sol.render_cpu(first, 96, 64, samples=4)["rgba"]
    got, under_way = {}, threading.Event()
    worker = threading.Thread(
        target=lambda: got.update(image=r.render(96, 64, samples=4, progress=lambda f: under_way.set())["rgba"]))
    worker.start()
    assert under_way.wait(30)  # (the render has begun: it reports from within)
    r.set_scene(second)
    worker.join()
    assert np.array_equal(got["image"], want)
    assert np.array_equal(r.render(16, 12, progress=False)["rgba"], sol.render_cpu(second, 16, 12)["rgba"])
