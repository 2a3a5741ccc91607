"""The Python package sol, built by the project's CMake build.

pyproject.toml names setuptools as the backend; this file gives it the one
thing it cannot do alone: the compiled module sol._sol comes from CMake
(python/CMakeLists.txt), configured for the interpreter running the build
(its Python3_EXECUTABLE) with only libsol and the module, built, and copied
into the wheel beside python/sol/__init__.py. SOL_CMAKE_BUILD_DIR names a
build folder already configured for this interpreter to build in instead
(the tests use the CI build's); CMAKE_BUILD_PARALLEL_LEVEL sets the jobs.
"""
import os
import re
import shutil
import subprocess
import sys
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


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("SOL_CMAKE_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "cmake"
        if not given:
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            self.spawn(["cmake", "-S", str(ROOT), "-B", str(build), *generator,
                        "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
                        "-DSOL_BUILD_PYTHON=ON", "-DSOL_BUILD_TESTS=OFF", "-DSOL_BUILD_BENCH=OFF",
                        "-DSOL_BUILD_VULKAN=OFF", "-DSOL_BUILD_VIEWER=OFF", "-DSOL_BUILD_XR=OFF"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        self.spawn(["cmake", "--build", str(build), "--target", "sol_python", "--parallel", jobs])
        package = build / "python" / "package" / "sol"
        built = sorted(package.glob("_sol*.so"))
        if not built:
            raise RuntimeError(f"setup.py: the CMake build made no module in {package}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)
        shutil.copyfile(package / "_build.py", target.parent / "_build.py")


setup(
    version=project_version(),
    ext_modules=[Extension("sol._sol", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
)
