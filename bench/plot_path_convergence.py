#!/usr/bin/env python3
"""Log-log plot of the path tracer's relative error against samples per pixel and seconds.

usage: plot_path_convergence.py path_convergence.csv path-convergence.png
One line per device in the file (the CPU renderer, the kernel). Left: error
against samples per pixel, with the 1/sqrt(spp) line through the first
point; right: error against the wall time of each render.
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
    devices = list(dict.fromkeys(r["device"] for r in rows))  # in the file's order
    for device in devices:
        mine = [r for r in rows if r["device"] == device]
        spp = [int(r["spp"]) for r in mine]
        seconds = [float(r["seconds"]) for r in mine]
        error = [float(r["relative_rms_error"]) for r in mine]
        label = "CPU" if device == "cpu" else device
        left.loglog(spp, error, "o-", label=label)
        right.loglog(seconds, error, "o-", label=label)
    first = [r for r in rows if r["device"] == devices[0]]
    spp = [int(r["spp"]) for r in first]
    e0 = float(first[0]["relative_rms_error"])
    left.loglog(spp, [e0 / (s / spp[0]) ** 0.5 for s in spp], "k--", label="1/sqrt(spp)")
    left.set_title(rows[0]["scene"])
    left.set_xlabel("samples per pixel")
    left.set_ylabel(f"relative RMS error (reference: {rows[0]['reference_spp']} spp)")
    left.legend()
    right.set_xlabel(f"seconds ({rows[0]['width']}x{rows[0]['height']})")
    right.set_ylabel("relative RMS error")
    right.legend()
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
