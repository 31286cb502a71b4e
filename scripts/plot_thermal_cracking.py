#!/usr/bin/python3
"""Crack pattern over the temperature field of a discrete thermo-mechanics run.

    plot_thermal_cracking.py OUTPUT_FOLDER out.png [--times t1,t2,...]
                             [--title "..."] [--zoom x0,x1,y0,y1]

Draws, for each requested output time (the nearest written one; default: the
last), the temperature on the exploded mesh (solution_*.vtu) with the broken
joints (cracks_*.vtu) as black lines over it, in the current configuration.
Needs only numpy and matplotlib.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import read_vtu  # noqa: E402


def datasets(folder, series):
    """[(time, path)] of a pvd series."""
    pvd = os.path.join(folder, series + ".pvd")
    if not os.path.exists(pvd):
        sys.exit(f"{pvd}: not found (is {folder} the output of a discrete run?)")
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file")))
            for d in ET.parse(pvd).getroot().iter("DataSet")]


def nearest(items, t):
    return min(items, key=lambda item: abs(item[0] - t))


def draw(ax, solution_vtu, crack_vtu, t_range, zoom=None):
    pts, cells, T, _ = read_vtu(solution_vtu, "T")
    tri = Triangulation(pts[:, 0] * 1e3, pts[:, 1] * 1e3, np.array(cells))
    im = ax.tripcolor(tri, T, shading="gouraud", cmap="coolwarm",
                      vmin=t_range[0], vmax=t_range[1])
    cpts, lines, _, _ = read_vtu(crack_vtu, "break_time")
    if lines:
        segments = [cpts[line] * 1e3 for line in lines]
        ax.add_collection(LineCollection(segments, colors="k", linewidths=1.0))
    ax.set_aspect("equal")
    if zoom:
        ax.set_xlim(zoom[0] * 1e3, zoom[1] * 1e3)
        ax.set_ylim(zoom[2] * 1e3, zoom[3] * 1e3)
    ax.set_xticks([])
    ax.set_yticks([])
    return im, len(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("output")
    ap.add_argument("--times", default=None,
                    help="comma-separated output times [s] (default: the last)")
    ap.add_argument("--time-unit", default="s", choices=["s", "ms", "h"])
    ap.add_argument("--title", default=None)
    ap.add_argument("--zoom", default=None, help="x0,x1,y0,y1 [m]")
    args = ap.parse_args()

    solutions = datasets(args.folder, "solution")
    cracks = datasets(args.folder, "cracks")
    if not solutions:
        sys.exit(f"{args.folder}/solution.pvd: no DataSet")
    wanted = ([float(t) for t in args.times.split(",")] if args.times
              else [solutions[-1][0]])
    picked = [(nearest(solutions, t), nearest(cracks, t)) for t in wanted]
    # one colour range for all panels: the initial and extreme temperatures
    lo, hi = np.inf, -np.inf
    for (_, s), _ in picked + [((0., solutions[0][1]), None)]:
        T = read_vtu(s, "T")[2]
        lo, hi = min(lo, T.min()), max(hi, T.max())
    zoom = [float(v) for v in args.zoom.split(",")] if args.zoom else None
    scale = {"s": 1., "ms": 1e3, "h": 1. / 3600.}[args.time_unit]
    n = len(picked)
    fig, axes = plt.subplots(1, n, figsize=(3.2 * n + 0.8, 3.6), dpi=150,
                             squeeze=False)
    for ax, ((t, s), (_, c)) in zip(axes[0], picked):
        im, n_broken = draw(ax, s, c, (lo, hi), zoom)
        ax.set_title(f"t = {t * scale:.4g} {args.time_unit}\n"
                     f"{n_broken} broken joints", fontsize=9)
    fig.colorbar(im, ax=axes[0].tolist(), label="T [C]", shrink=0.85)
    if args.title:
        fig.suptitle(args.title, fontsize=10)
    fig.savefig(args.output, bbox_inches="tight")
    print(f"wrote {args.output}: {n} panel(s), T in [{lo:.4g}, {hi:.4g}] C")


if __name__ == "__main__":
    main()
