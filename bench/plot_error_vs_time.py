#!/usr/bin/env python3
"""Log-log plot of error against time per evaluation from flow_bench's CSV.

usage: plot_error_vs_time.py error_vs_time.csv error_vs_time.png
One curve per method and arc length (RK4 over its step sizes, Dormand-Prince
over its tolerances); the closed forms are single points (precomputed and per
call). Errors of exactly 0 are drawn at 1e-17.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    source, target = sys.argv[1], sys.argv[2]
    series = defaultdict(list)
    with open(source, newline="") as f:
        for row in csv.DictReader(f):
            key = (row["method"], row["setting"] if row["method"].startswith("closed") else "", row["arc_length"])
            series[key].append((float(row["ns_per_eval"]), max(float(row["max_error"]), 1e-17)))
    if not series:
        print(f"{source}: no rows", file=sys.stderr)
        return 1
    colours = {"1": "tab:blue", "10": "tab:orange", "50": "tab:red"}
    markers = {"rk4": "o", "dopri5": "s", "closed-double": "*", "closed-float": "P"}
    fig, ax = plt.subplots(figsize=(10.5, 5.5), dpi=80)
    for (method, setting, arc), points in sorted(series.items()):
        points.sort()
        xs, ys = zip(*points)
        label = f"{method}{' ' + setting if setting else ''}, t={arc}"
        style = "-" if not method.startswith("closed") else "none"
        fill = "none" if setting == "per call" else colours.get(arc, "k")
        ax.plot(xs, ys, linestyle=style, marker=markers.get(method, "x"), color=colours.get(arc, "k"),
                markerfacecolor=fill, markersize=9 if method.startswith("closed") else 5, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per evaluation [ns]")
    ax.set_ylabel("max endpoint error / max(1, |coordinate|)")
    ax.set_title("Sol geodesic flow: error against run time")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(target + ".part.png")
    import os
    os.replace(target + ".part.png", target)
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
