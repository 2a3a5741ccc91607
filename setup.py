"""The Python package sol, built by the project's CMake build.

pyproject.toml names setuptools as the backend; this file gives it the one
thing it cannot do alone: the compiled module sol._sol comes from CMake
(python/CMakeLists.txt), configured for the interpreter running the build
(its Python3_EXECUTABLE) with only libsol and the module, built, and copied
into the wheel beside python/sol/__init__.py, with the Vulkan kernel where
its dependencies are installed (SOL_BUILD_VULKAN=AUTO; the environment's
SOL_BUILD_VULKAN=OFF leaves it out, ON requires it; sol.has_vulkan() and
sol.vulkan_missing() tell which). SOL_CMAKE_BUILD_DIR names a
build folder already configured for this interpreter to build in instead
(the tests use the CI build's); CMAKE_BUILD_PARALLEL_LEVEL sets the jobs.
"""
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import sysconfig
import time
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    text = (ROOT / "CMakeLists.txt").read_text()
    match = re.search(r"project\(Sol VERSION ([0-9.]+)", text)
    if not match:
        raise RuntimeError("setup.py: no 'project(Sol VERSION x.y.z' in CMakeLists.txt")
    return match.group(1)


def missing_prerequisites(building_wheel):
    """What the build needs that this interpreter's environment lacks, each
    with where it comes from (pip, or Debian's package)."""
    missing = []
    if building_wheel and importlib.util.find_spec("wheel") is None:
        missing.append("the Python package wheel (python3 -m pip install wheel; Debian: python3-wheel)")
    if importlib.util.find_spec("numpy") is None:
        missing.append("the Python package numpy (python3 -m pip install numpy; Debian: python3-numpy)")
    if not shutil.which("cmake"):
        missing.append("CMake 3.25 or newer (Debian: cmake)")
    if not (os.environ.get("CXX") or any(shutil.which(c) for c in ("c++", "g++", "clang++"))):
        missing.append("a C++20 compiler (Debian: g++)")
    include = sysconfig.get_paths().get("include", "")
    if not include or not (Path(include) / "Python.h").exists():
        missing.append(f"this Python's headers, Python.h, in {include or '(no include path)'} "
                       "(Debian: python3-dev; pyenv builds have them)")
    pybind11_dirs = [Path(p) / "pybind11" for p in ("/usr/lib/cmake", "/usr/share/cmake", "/usr/local/lib/cmake",
                                                     "/usr/local/share/cmake")]
    if importlib.util.find_spec("pybind11") is None and not any((d / "pybind11Config.cmake").exists() for d in pybind11_dirs):
        missing.append("pybind11 2.10 or newer (Debian: pybind11-dev; or python3 -m pip install pybind11)")
    return missing


def check_prerequisites():
    """Stops a build whose prerequisites are missing with one message that
    names them all and the interpreter it ran under (pip's own error for a
    missing wheel, "invalid command 'bdist_wheel'", names neither)."""
    # (pip's metadata step runs dist_info, which takes setuptools' bdist_wheel
    # from the wheel package before setuptools 70.1.)
    wheel = any(a in sys.argv for a in ("bdist_wheel", "dist_info"))
    building = wheel or any(a in sys.argv for a in ("build_ext", "build", "install", "develop", "editable_wheel"))
    missing = missing_prerequisites(wheel) if building else []
    if missing:
        lines = "\n".join(f"  - {m}" for m in missing)
        sys.exit(f"setup.py: building sol under {sys.executable} (Python {sys.version.split()[0]}) needs:\n{lines}\n"
                 "(docs/python.md: Installing)")


class BuildProgress:
    """The CMake build's progress, one line a second at most: the share of its steps done (Ninja's [n/N], Make's
    [ p%]) and the time left at the rate so far. pip keeps a build's output to itself unless asked (-v), so the
    line also goes to the terminal (/dev/tty) where there is one."""

    STEP = re.compile(r"^\[\s*(\d+)/(\d+)\]|^\[\s*(\d+)%\]")

    def __init__(self):
        self.start = time.monotonic()
        self.shown = 0.0
        self.tty = None
        if not sys.stderr.isatty():  # (on a terminal already: the lines below reach it)
            try:
                self.tty = open("/dev/tty", "w")  # noqa: SIM115 (closed in close())
            except OSError:
                pass

    def line(self, text):
        match = self.STEP.match(text)
        if not match:
            return
        fraction = int(match[1]) / int(match[2]) if match[1] else int(match[3]) / 100
        now = time.monotonic()
        if now - self.shown < 1.0 and fraction < 1.0:
            return
        self.shown = now
        elapsed = now - self.start
        left = f", about {elapsed * (1 - fraction) / fraction:.0f} s left" if 0.02 < fraction < 1 else ""
        message = f"setup.py: building sol's compiled module: {100 * fraction:3.0f}% after {elapsed:.0f} s{left}"
        print(message, file=sys.stderr, flush=True)
        if self.tty:
            self.tty.write(f"\r{message}   ")
            self.tty.flush()

    def close(self):
        if self.tty:
            self.tty.write("\n")
            self.tty.close()


def build_with_progress(command):
    """Runs the build, its output passed on as it comes and its progress reported; fails as spawn would."""
    progress = BuildProgress()
    print(" ".join(command), flush=True)
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace") as build:
        for text in build.stdout:
            sys.stdout.write(text)
            progress.line(text)
    progress.close()
    if build.returncode != 0:
        raise RuntimeError(f"setup.py: the CMake build failed (exit {build.returncode}): {' '.join(command)}")


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("SOL_CMAKE_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            self.spawn(["cmake", "-S", str(ROOT), "-B", str(build), *generator,
                        "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                        "-DSOL_BUILD_PYTHON=ON", "-DSOL_BUILD_TESTS=OFF", "-DSOL_BUILD_BENCH=OFF",
                        f"-DSOL_BUILD_VULKAN={os.environ.get('SOL_BUILD_VULKAN', 'AUTO')}", "-DSOL_BUILD_VIEWER=OFF",
                        "-DSOL_BUILD_XR=OFF"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        build_with_progress(["cmake", "--build", str(build), "--target", "sol_python", "--parallel", jobs])
        package = build / "python" / "package" / "sol"
        built = sorted(package.glob("_sol*.so"))
        if not built:
            raise RuntimeError(f"setup.py: the CMake build made no module in {package}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)
        shutil.copyfile(package / "_build.py", target.parent / "_build.py")


check_prerequisites()
setup(
    version=project_version(),
    ext_modules=[Extension("sol._sol", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
