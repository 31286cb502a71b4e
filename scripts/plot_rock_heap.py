#!/usr/bin/python3
"""Figures of the rock heap case (paper Sec. 5.2) for doc/cases/rock_heap.md.

    plot_rock_heap.py SETTLE_OUTPUT HEAT_OUTPUT IMAGE_FOLDER

SETTLE_OUTPUT: output folder of prm/rock_heap.prm (solution.pvd);
HEAT_OUTPUT: output folder of prm/rock_heap-heat.prm (solution.pvd,
lines.csv, probes.csv). Writes rock_heap_settle.png (the generated and the
settled heap), rock_heap_T.png (temperature at the output times, as the
paper's Fig. 6) and rock_heap_monitor.png (the line `monitor` at the output
times and the probes against time, as the paper's Fig. 7).
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "scripts"))
from plot_vtu import read_vtu  # noqa: E402
from analytic import read_csv  # noqa: E402


# the times of the temperature fields and monitor-line curves [s]
FIELD_TIMES = [1800, 7200, 18000, 43200]


def datasets(pvd):
    folder = os.path.dirname(pvd)
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file")))
            for d in ET.parse(pvd).getroot().iter("DataSet")]


def draw_mesh(ax, vtu, title):
    pts, cells, material, _ = read_vtu(vtu, "material_id")
    polys = [pts[c] for c in cells]
    colors = ["#b08060" if m == 1 else "0.6" for m in material]
    ax.add_collection(PolyCollection(polys, facecolors=colors, edgecolors="k", linewidths=0.1))
    ax.set_xlim(-0.04, 0.54)
    ax.set_ylim(-0.04, 0.72)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x [m]")


def main():
    settle, heat, images = sys.argv[1:4]
    os.makedirs(images, exist_ok=True)

    # ---------------------------------------------------------------- settle
    sets = datasets(os.path.join(settle, "solution.pvd"))
    fig, axes = plt.subplots(1, 2, figsize=(7, 4.6))
    draw_mesh(axes[0], sets[0][1], f"generated (t = {sets[0][0]:g} s)")
    draw_mesh(axes[1], sets[-1][1], f"settled (t = {sets[-1][0]:g} s)")
    axes[0].set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(os.path.join(images, "rock_heap_settle.png"), dpi=130)
    plt.close(fig)

    # ------------------------------------------------------ temperature field
    sets = [s for s in datasets(os.path.join(heat, "solution.pvd"))
            if any(abs(s[0] - t) < 1 for t in FIELD_TIMES)]
    fig, axes = plt.subplots(1, len(sets), figsize=(2.6 * len(sets), 3.9))
    line = read_csv(os.path.join(heat, "lines.csv"))["monitor"]
    probes = read_csv(os.path.join(heat, "probes.csv"))
    for ax, (t, vtu) in zip(axes, sets):
        pts, cells, T, _ = read_vtu(vtu, "T")
        tri = Triangulation(pts[:, 0], pts[:, 1], np.array([c[:3] for c in cells]))
        im = ax.tripcolor(tri, T, shading="gouraud", cmap="inferno", vmin=0, vmax=100)
        ax.plot([0.195, 0.195], [0, max(line[t][1])], "c--", lw=0.8)
        for name in probes:
            p = probes[name][t]
            ax.plot(p[0], p[1], "co", ms=2.5)
        ax.set_xlim(-0.03, 0.53)
        ax.set_ylim(-0.03, 0.65)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t / 3600:g} h", fontsize=9)
        ax.set_xticks([0, 0.25, 0.5])
        if ax is not axes[0]:
            ax.set_yticks([])
    fig.colorbar(im, ax=axes, shrink=0.8, label="T [C]")
    fig.savefig(os.path.join(images, "rock_heap_T.png"), dpi=130, bbox_inches="tight")
    plt.close(fig)

    # -------------------------------------------------------------- monitors
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.8))
    for t in sorted(line):
        if any(abs(t - f) < 1 for f in FIELD_TIMES):
            a.plot(line[t][2]["T"], line[t][1], label=f"{t / 3600:g} h")
    a.set_xlabel("T [C]")
    a.set_ylabel("height y [m] (x = 0.195 m)")
    a.set_title("(a) line 'monitor'", fontsize=9)
    a.legend(fontsize=7)
    for name in sorted(probes, key=lambda n: int(n[1:])):
        times = np.array(sorted(probes[name]))
        T = [probes[name][t][2]["T"][0] for t in times]
        y = probes[name][times[0]][1][0]
        b.plot(times / 3600, T, label=f"{name} (y = {y:g} m)")
    b.set_xlabel("t [h]")
    b.set_ylabel("T [C]")
    b.set_title("(b) probes", fontsize=9)
    b.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(images, "rock_heap_monitor.png"), dpi=130)
    plt.close(fig)


if __name__ == "__main__":
    main()
