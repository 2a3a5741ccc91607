#!/usr/bin/env python3
"""Log-log plot of the path tracer's relative error against samples per pixel and seconds.

usage: plot_path_convergence.py path_convergence.csv path-convergence.png
Left: error against samples per pixel, with the 1/sqrt(spp) line through the
first point; right: error against the wall time of each render.
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
    spp = [int(r["spp"]) for r in rows]
    seconds = [float(r["seconds"]) for r in rows]
    error = [float(r["relative_rms_error"]) for r in rows]
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), dpi=80)
    left.loglog(spp, error, "o-", label=f"{rows[0]['scene']} on the {rows[0]['device']}")
    left.loglog(spp, [error[0] / (s / spp[0]) ** 0.5 for s in spp], "k--", label="1/sqrt(spp)")
    left.set_xlabel("samples per pixel")
    left.set_ylabel(f"relative RMS error (reference: {rows[0]['reference_spp']} spp)")
    left.legend()
    right.loglog(seconds, error, "o-")
    right.set_xlabel(f"seconds ({rows[0]['width']}x{rows[0]['height']})")
    right.set_ylabel("relative RMS error")
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
