"""The package as users install it: `pip install .` into a fresh venv (offline, Debian's setuptools and NumPy
through --system-site-packages), and clear errors when the interpreter cannot load the module (no NumPy, another
Python version). ctest names the source tree in SOL_SOURCE_DIR and the CMake build folder to build in (the CI
build's, configured for Debian's python3) in SOL_CMAKE_BUILD_DIR."""
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import sol

SOURCE = os.environ.get("SOL_SOURCE_DIR")
BUILD = os.environ.get("SOL_CMAKE_BUILD_DIR")


def run(*args, **kwargs):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)


def copy_sources(work):
    """What the build reads of the tree (pip builds in the source folder: a copy keeps the repository clean)."""
    src = work / "src"
    for name in ("pyproject.toml", "setup.py", "CMakeLists.txt", "docs/python.md", "python/sol/__init__.py",
                 "python/sol/scenes.py", "python/sol/renderer.py", "python/sol/_build.py.in"):
        (src / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(Path(SOURCE) / name, src / name)
    return src


@pytest.mark.skipif(not SOURCE or not BUILD, reason="needs SOL_SOURCE_DIR and SOL_CMAKE_BUILD_DIR (ctest sets them)")
def test_pip_installs_the_package_into_a_fresh_venv():
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        src = copy_sources(work)
        venv = work / "venv"
        made = run(sys.executable, "-m", "venv", "--system-site-packages", venv)
        assert made.returncode == 0, made.stderr
        python = venv / "bin" / "python"
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        env["SOL_CMAKE_BUILD_DIR"] = BUILD
        pip = run(python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-deps", src, env=env)
        assert pip.returncode == 0, pip.stdout + pip.stderr
        # The venv's sol, not the build folder's: a render and the version.
        probe = ("import sol; print(sol.__file__); print(sol.__version__); "
                 "r = sol.render_cpu(sol.preset_scene('plane'), 8, 6); print(r['rgba'].shape)")
        used = run(python, "-c", probe, env=env)
        assert used.returncode == 0, used.stderr
        lines = used.stdout.split()
        assert lines[0].startswith(str(venv)), lines[0]
        assert lines[1] == sol.__version__
        assert lines[2:] == ["(6,", "8,", "4)"]
        # The kernel from the venv: sol.Renderer(device="vulkan") writes the image solrender --device vulkan
        # writes for the same scene, options and seed (both float EXR, idiff without tolerance).
        if sol.has_vulkan() and os.environ.get("SOLRENDER") and os.environ.get("IDIFF"):
            ours, theirs = work / "venv-kernel.exr", work / "solrender-kernel.exr"
            kernel = ("import sol, sys; r = sol.Renderer(sol.preset_scene('sandwich'), device='vulkan', "
                      "transport='path'); assert r.device == 'vulkan'; "
                      "sol.save(sys.argv[1], r.render(20, 14, samples=2, transport='path', seed=5)['rgba'])")
            made = run(python, "-c", kernel, ours, env=env)
            assert made.returncode == 0, made.stderr
            rendered = run(os.environ["SOLRENDER"], "--scene", "sandwich", "--device", "vulkan", "--width", 20,
                           "--height", 14, "--spp", 2, "--transport", "path", "--seed", 5, "-o", theirs)
            assert rendered.returncode == 0, rendered.stderr
            same = run(os.environ["IDIFF"], "-fail", "0", "-warn", "0", ours, theirs)
            assert same.returncode == 0, same.stdout + same.stderr
        # The notebook from the venv, as docs/python.md says: a kernel installed into the venv, which Jupyter
        # run from it finds; its cells import the venv's sol (the first prints where from), and the tour runs.
        if importlib.util.find_spec("ipykernel") is None or importlib.util.find_spec("nbclient") is None:
            return
        kernel = run(python, "-m", "ipykernel", "install", "--prefix", venv, "--name", "sol-venv", env=env)
        assert kernel.returncode == 0, kernel.stderr
        tour = Path(SOURCE) / "docs" / "notebooks" / "tour.ipynb"
        execute = ("import sys, nbformat, nbclient\n"
                   "probe = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell('import sol; print(sol.__file__)')])\n"
                   "nbclient.NotebookClient(probe, timeout=120, kernel_name='sol-venv').execute()\n"
                   "print(probe.cells[0].outputs[0]['text'].strip())\n"
                   "tour = nbformat.read(sys.argv[1], as_version=4)\n"
                   "nbclient.NotebookClient(tour, timeout=300, kernel_name='sol-venv').execute()\n"
                   "print(sum(o.output_type == 'error' for c in tour.cells if c.cell_type == 'code' for o in c.outputs))\n")
        env["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
        env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"
        ran = run(python, "-c", execute, tour, env=env, cwd=work)
        assert ran.returncode == 0, ran.stdout + ran.stderr
        where, errors = ran.stdout.split()[-2:]
        assert where.startswith(str(venv)), where
        assert errors == "0"


@pytest.mark.skipif(not SOURCE, reason="needs SOL_SOURCE_DIR (ctest sets it)")
def test_a_build_without_its_prerequisites_names_them_and_the_interpreter():
    # A venv of its own (no system packages): pip and setuptools, but neither wheel nor NumPy. pip's own
    # error would be "invalid command 'bdist_wheel'"; setup.py names both and the interpreter, before any build.
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        src = copy_sources(work)
        venv = work / "bare"
        made = run(sys.executable, "-m", "venv", venv)
        assert made.returncode == 0, made.stderr
        python = venv / "bin" / "python"
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SOL_CMAKE_BUILD_DIR")}
        pip = run(python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-deps", src, env=env)
        out = pip.stdout + pip.stderr
        assert pip.returncode != 0, out
        assert f"building sol under {python}" in out, out
        assert "the Python package wheel" in out, out
        assert "the Python package numpy" in out, out
        assert "invalid command" not in out, out


def test_another_python_version_is_named():
    # The compiled module renamed as if built for another Python: the import names both interpreters.
    with tempfile.TemporaryDirectory() as work:
        package = Path(work) / "sol"
        shutil.copytree(Path(sol.__file__).parent, package)
        for module in package.glob("_sol*.so"):
            module.rename(package / "_sol.cpython-399-x86_64-linux-gnu.so")
        env = dict(os.environ, PYTHONPATH=work)
        got = run(sys.executable, "-c", "import sol", env=env)
        assert got.returncode != 0
        running = f"{sys.version_info[0]}.{sys.version_info[1]}"
        assert "sol's compiled module was built for Python" in got.stderr, got.stderr
        assert f"this one (Python {running}" in got.stderr, got.stderr
        assert "pip install --no-build-isolation ." in got.stderr, got.stderr


def test_an_interpreter_without_numpy_is_told():
    with tempfile.TemporaryDirectory() as work:
        venv = Path(work) / "bare"
        made = run(sys.executable, "-m", "venv", "--without-pip", venv)
        assert made.returncode == 0, made.stderr
        env = dict(os.environ, PYTHONPATH=str(Path(sol.__file__).parent.parent))
        got = run(venv / "bin" / "python", "-c", "import sol", env=env)
        assert got.returncode != 0
        assert "sol needs NumPy in this interpreter" in got.stderr, got.stderr


def test_errors_are_sol_errors_and_shadow_no_builtin():
    import builtins

    assert not {n for n in dir(sol) if not n.startswith("_")} & set(dir(builtins))
    with pytest.raises(sol.InvalidArgumentError) as bad:
        sol.flow((0, 0, 0), (0, 0, 0), 1.0)
    assert isinstance(bad.value, sol.SolError) and isinstance(bad.value, ValueError)
    with pytest.raises(sol.OutOfRangeError):
        sol.sphere_area_density((1, 0, 0), 1e9)
    assert issubclass(sol.UnsupportedError, NotImplementedError) and issubclass(sol.UnsupportedError, sol.SolError)
