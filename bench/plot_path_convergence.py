#!/usr/bin/env python3
"""Log-log plot of the path tracer's relative error against samples per pixel and seconds.

usage: plot_path_convergence.py path_convergence.csv path-convergence.png
One line per scene and device in the file (the CPU renderer, the kernel).
Left: error against samples per pixel, raw (solid) and denoised (dotted),
with the 1/sqrt(spp) line through the first point; right: the raw error
against the wall time of each render.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    source, target = sys.argv[1], sys.argv[2]
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        print(f"{source}: no rows", file=sys.stderr)
        return 1
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), dpi=80)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))  # in the file's order
    devices = list(dict.fromkeys(r["device"] for r in rows))
    for scene in scenes:
        for device in devices:
            mine = [r for r in rows if r["device"] == device and r["scene"] == scene]
            spp = [int(r["spp"]) for r in mine]
            seconds = [float(r["seconds"]) for r in mine]
            error = [float(r["relative_rms_error"]) for r in mine]
            label = f"{scene}, " + ("CPU" if device == "cpu" else device.split(" (")[0])
            line, = left.loglog(spp, error, "o-", label=label)
            right.loglog(seconds, error, "o-", label=label, color=line.get_color())
            if mine and "denoised_relative_rms_error" in mine[0]:
                denoised = [float(r["denoised_relative_rms_error"]) for r in mine]
                left.loglog(spp, denoised, "s:", label=label + ", denoised", color=line.get_color())
    first = [r for r in rows if r["device"] == devices[0] and r["scene"] == scenes[0]]
    spp = [int(r["spp"]) for r in first]
    e0 = float(first[0]["relative_rms_error"])
    left.loglog(spp, [e0 / (s / spp[0]) ** 0.5 for s in spp], "k--", label="1/sqrt(spp)")
    left.set_title("path tracing, raw and denoised")
    left.set_xlabel("samples per pixel")
    left.set_ylabel(f"relative RMS error (reference: {rows[0]['reference_spp']} spp)")
    left.legend(fontsize=6)
    right.set_xlabel(f"seconds ({rows[0]['width']}x{rows[0]['height']})")
    right.set_ylabel("relative RMS error")
    right.legend(fontsize=6)
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
