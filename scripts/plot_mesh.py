#!/usr/bin/python3
"""Draws the cells of the last solution_*.vtu of a 2D run (quadrilaterals or
triangles, e.g. a mesh after adaptive refinement) with their edges.

    plot_mesh.py OUTPUT_FOLDER OUT.png [--title TEXT]

Reads the series solution.pvd of OUTPUT_FOLDER and draws the cells of its
last file in the x-y plane, axes in metres. Needs numpy and matplotlib.
"""
import argparse
import os
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import read_vtu  # noqa: E402
from count_radial_cracks import series_entry  # noqa: E402


def main():
    p = argparse.ArgumentParser()
    p.add_argument("folder")
    p.add_argument("png")
    p.add_argument("--title", default=None)
    args = p.parse_args()
    _, vtu = series_entry(args.folder, "solution")
    points, cells, _, _ = read_vtu(vtu, "T")
    points = np.asarray(points)[:, :2]
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.add_collection(PolyCollection([points[c] for c in cells], facecolors="none",
                                     edgecolors="k", linewidths=0.2))
    lo, hi = points.min(axis=0), points.max(axis=0)
    pad = 0.03 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(args.title or f"{len(cells)} cells")
    fig.savefig(args.png, dpi=110, bbox_inches="tight")
    print(f"wrote {args.png}: {len(cells)} cells")


if __name__ == "__main__":
    main()
