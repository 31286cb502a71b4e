#!/usr/bin/python3
"""Crack patterns of several discrete runs side by side.

    plot_crack_patterns.py out.png "LABEL=OUTPUT_FOLDER" ["LABEL=OUTPUT_FOLDER" ...]
                           [--radius R] [--time SECONDS]

One panel per run: the broken joints of its last cracks_*.vtu (or the one
written nearest --time [s]) in the reference configuration, over the
outline of a disc of radius --radius [m] centred at the origin (default
6.5e-3, prm/thermal_shock_disc.prm; 0: no outline). Each panel's title is
its label with the broken joints, the cracks (summary.json) and the summed
length of the broken joints [mm]. Needs only numpy and matplotlib.
"""
import argparse
import json
import os
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from count_radial_cracks import last_cracks  # noqa: E402
from plot_vtu import read_vtu  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("png")
    ap.add_argument("runs", nargs="+", help="LABEL=OUTPUT_FOLDER")
    ap.add_argument("--radius", type=float, default=6.5e-3)
    ap.add_argument("--time", type=float, default=None)
    args = ap.parse_args()
    runs = []
    for item in args.runs:
        if "=" not in item:
            sys.exit(f"{item}: expected LABEL=OUTPUT_FOLDER")
        label, folder = item.split("=", 1)
        if not os.path.exists(os.path.join(folder, "cracks.pvd")):
            sys.exit(f"{folder}: no cracks.pvd (is it the output of a discrete run?)")
        runs.append((label, folder))
    fig, axes = plt.subplots(1, len(runs), figsize=(3.2 * len(runs), 3.6), squeeze=False)
    for ax, (label, folder) in zip(axes[0], runs):
        t, vtu = last_cracks(folder, args.time)
        pts, lines, _, _ = read_vtu(vtu, "break_time")
        segments = [(pts[a][:2] * 1e3, pts[b][:2] * 1e3) for a, b in lines]
        length = sum(float(np.linalg.norm(pts[a] - pts[b])) for a, b in lines)
        with open(os.path.join(folder, "summary.json")) as f:
            s = json.load(f)
        if args.radius > 0:
            phi = np.linspace(0, 2 * np.pi, 361)
            ax.plot(1e3 * args.radius * np.cos(phi), 1e3 * args.radius * np.sin(phi),
                    color="0.6", lw=0.8)
        ax.add_collection(LineCollection(segments, colors="k", linewidths=1.2))
        ax.set_aspect("equal")
        lim = 1e3 * args.radius * 1.05 if args.radius > 0 else None
        if lim:
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
        else:
            ax.autoscale()
        ax.set_xlabel("x [mm]")
        ax.set_title(f"{label}\n{len(lines)} broken joints, {s.get('cracks', '-')} cracks,\n"
                     f"{1e3 * length:.2f} mm at t = {1e3 * t:g} ms", fontsize=8)
    axes[0][0].set_ylabel("y [mm]")
    fig.tight_layout()
    fig.savefig(args.png, dpi=130)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
