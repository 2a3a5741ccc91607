"""Sol: Thurston's Sol geometry from Python.

The group law, geodesics (closed form), exact distances and connections,
geodesic spheres, the lattice of the compact quotient, scenes and the CPU
renderer of the Sol renderer's library (libsol), as a compiled module
(``sol._sol``) with this package around it. Points and directions are
sequences of three numbers in, NumPy arrays out. docs/python.md has the
reference and examples.
"""
import sys as _sys

try:
    import numpy as _numpy  # noqa: F401  (every result is a NumPy array)
except ImportError as _error:  # pragma: no cover - depends on the interpreter
    raise ImportError(
        f"sol needs NumPy in this interpreter ({_sys.executable}): 'python3 -m pip install numpy', or Debian's "
        "python3-numpy with a venv made with --system-site-packages"
    ) from _error

try:
    from . import _sol
    from ._sol import *  # noqa: F401,F403
    from ._sol import __version__  # noqa: F401
except ImportError as _error:
    from ._build import PYTHON_EXECUTABLE as _built_executable, PYTHON_VERSION as _built_version

    _running = ".".join(str(v) for v in _sys.version_info[:2])
    raise ImportError(
        f"sol's compiled module was built for Python {_built_version} ({_built_executable}) and does not load in "
        f"this one (Python {_running}, {_sys.executable}): build it for this interpreter with "
        "'python3 -m pip install --no-build-isolation .' in the Sol repository (docs/python.md)"
    ) from _error

from . import scenes as _scenes  # noqa: E402
from .scenes import *  # noqa: E402,F401,F403

__all__ = [_name for _name in dir(_sol) if not _name.startswith("_")] + _scenes.__all__
if hasattr(_sol, "_Renderer"):  # (a module built with solrender's image and renderer code: every build but the bare library's)
    from .renderer import Renderer  # noqa: E402,F401

    __all__.append("Renderer")
