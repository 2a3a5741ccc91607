#!/usr/bin/env python3
"""A frame's time against the number of objects (render_bench --only objects).

usage: plot_objects.py render_objects.csv render-objects.png
One line per device and camera (outside the crowd, inside it), log-log:
a march whose cost per step grows with the logarithm of the number of
objects climbs slowly, one that visits every object as fast as the count.
Rows without a time (a device that does not take the world) are skipped.
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
        rows = [r for r in csv.DictReader(f) if r["ms"]]
    if not rows:
        print(f"{source}: no rows with a time", file=sys.stderr)
        return 1
    fig, ax = plt.subplots(figsize=(6, 4), dpi=80)
    series = list(dict.fromkeys((r["device"], r["camera"]) for r in rows))
    for device, camera in series:
        points = [(int(r["objects"]), float(r["ms"])) for r in rows if (r["device"], r["camera"]) == (device, camera)]
        points.sort()
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", label=f"{device}, camera {camera}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("objects (small balls in a fixed region)")
    ax.set_ylabel("frame time (ms)")
    ax.set_title(f"Frame time against objects ({rows[0]['width']}x{rows[0]['height']})")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(target)
    return 0


if __name__ == "__main__":
    sys.exit(main())
