"""sol.Renderer: a scene rendered on the Vulkan kernel or the CPU, as solrender renders it.

    r = sol.Renderer(sol.preset_scene("lattice-balls"), device="auto")   # the kernel where it can, else the CPU
    image = r.render(320, 240, samples=4)["rgba"]                       # (240, 320, 4) float32, linear
    r.device, r.description                                             # "vulkan", "vulkan 'llvmpipe ...'"

The world is prepared once (the kernel built, a quotient's images found); every render() reuses it. The
options are solrender's (--device, --transport, --spp, --seed, --stereo with --ipd, --integrator rk4), with the
same defaults, and the same seed gives the same image as solrender's on the same device.
"""
import sys as _sys
import time as _time

from . import _sol

__all__ = ["Renderer"]


class _ProgressBar:
    """A one-line text bar on stderr (a notebook's cell output too) for renders longer than half a second:
    percent, elapsed and time left; the line is ended when the render ends."""

    def __init__(self, who, stream=None):
        self._who = who
        self._stream = stream or _sys.stderr
        self._start = _time.monotonic()
        self._shown = False

    def __call__(self, fraction):
        elapsed = _time.monotonic() - self._start
        if elapsed < 0.5 and not self._shown:
            return
        self._shown = True
        filled = int(round(30 * fraction))
        left = f", about {elapsed * (1 - fraction) / fraction:.1f} s left" if 0 < fraction < 1 else ""
        self._stream.write(f"\r{self._who}: {100 * fraction:5.1f}% [{'#' * filled}{'.' * (30 - filled)}] "
                           f"{elapsed:.1f} s{left}   ")
        self._stream.flush()

    def close(self):
        if self._shown:
            self._stream.write("\n")
            self._stream.flush()


def _wants_bar():
    """A bar by default in a notebook (IPython's kernel) and on a terminal."""
    if "ipykernel" in _sys.modules:
        return True
    try:
        return _sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


class Renderer:
    """A renderer for a scene's world, on `device`: "auto" (the Vulkan kernel, on a GPU or else lavapipe, where
    this sol has it, a device opens and the kernel draws the world; otherwise the CPU, and ``notes`` says why),
    "vulkan" (the kernel, or sol.UnsupportedError saying why not) or "cpu" (the double-precision reference).
    `transport` ("direct" or "path") is the one the renders will use, so that "auto" can choose a device that
    draws it; `rk4` with `rk4_step` is the kernel's RK4 integrator (solrender's --integrator rk4 --rk-step)."""

    def __init__(self, scene, device="auto", *, transport="direct", rk4=False, rk4_step=0.01):
        self._transport = transport
        self._r = _sol._Renderer(scene, device, transport, rk4, rk4_step)

    @property
    def device(self):
        """Where it renders: "vulkan" or "cpu"."""
        return self._r.device

    @property
    def description(self):
        """The device for people: "cpu (8 threads)", "vulkan 'NVIDIA H100 ...'"."""
        return self._r.description

    @property
    def notes(self):
        """Why device="auto" took the CPU (one line each), if it did."""
        return list(self._r.notes)

    def set_scene(self, scene):
        """Prepares another scene's world (and takes its camera and samples) on the same device choice."""
        self._r.set_scene(scene)

    def render(self, width=512, height=512, *, samples=0, camera=None, transport=None, seed=0, stereo=False,
               ipd=0.064, aovs=True, threads=0, progress=None, first_sample=0, time_limit=None, noise_target=None,
               denoise=False):
        """Renders the prepared world, width x height pixels per eye (1..16384), from `camera` (the scene's when
        None), `samples` per pixel (1..4096; 0 the scene's "samples"), by `transport` (the renderer's when None),
        the path tracer's random numbers from `seed` (0..2^31-1); `stereo` both eyes of `ipd` side by side
        (width 2 W), on `threads` CPU threads (0: all; the CPU only). `first_sample` (0..2^24) starts the samples
        there: renders of consecutive ranges weighted by their counts are the render of all of them (render more
        samples into an image later: (n1 * a + n2 * b) / (n1 + n2)); above 0 `aovs` must be False (the AOVs are
        sample 0's). `time_limit` (seconds) and `noise_target` (a relative error) render in batches until either
        is reached, as solrender's --time-limit and --noise-target (from `samples` to 4096 per pixel); the dict then
        also holds "samples", "noise" (the estimate reached) and "seconds". `denoise` filters the colour with
        the denoiser guided by the AOVs (solrender's --denoise; on the renderer's device; "rgba" is then the
        denoised colour, the AOVs are rendered whatever `aovs` says and handed out only where it is True).

        Returns a dict of NumPy float32 arrays as sol.render_cpu's (rgba, and with `aovs` object, distance, point,
        steps, out_of_steps) plus rays_out_of_steps and device_ms. `progress`: a callable given the finished
        fraction now and then (at most every 0.1 s), True for a text bar, False for none; None (the default) a
        bar in a notebook or on a terminal for renders over half a second. Ctrl-C (or an exception the callable
        raises) stops the render within about 0.1 s of device work and reaches the caller."""
        bar = None
        if progress is None:
            progress = _wants_bar()
        if progress is True:
            bar = _ProgressBar(f"sol.Renderer ({self.device})")
            callback = bar
        elif progress is False:
            callback = None
        else:
            callback = progress
        try:
            return self._r.render(width, height, samples, camera, transport or self._transport, seed,
                                  ipd if stereo else None, aovs, threads, callback, first_sample, time_limit,
                                  noise_target, denoise)
        finally:
            if bar is not None:
                bar.close()

    def __repr__(self):
        return f"sol.Renderer({self.description!r})"
