#!/usr/bin/python3
"""Plots T along the midline of prm/cut_plate.prm for the intact, cut and
pressed variants against their exact profiles.
usage: scripts/plot_cut_plate.py <folder of verify_discrete_cut.py> <png>"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "scripts"))
from analytic import read_csv  # noqa: E402

folder, png = sys.argv[1], sys.argv[2]
k, h_c, L = 10.0, 100.0, 1.0
x = np.linspace(0, 1, 401)
q = 100.0 / (L / k + 1.0 / h_c)
exact = {
    "intact": 100.0 * (1 - x),
    "cut_touching": np.where(x < 0.5, 100.0, 0.0),
    "cut_pressed": np.where(x < 0.5, 100.0 - q * x / k, q * (1 - x) / k),
}
labels = {"intact": "intact", "cut_touching": "cut, faces touching",
          "cut_pressed": "cut, pressed (1 MPa), h_c = 100 W/(m^2 K)"}
fig, ax = plt.subplots(figsize=(7, 4.2))
for (name, T), colour in zip(exact.items(), ("C0", "C1", "C2")):
    lines = read_csv(os.path.join(folder, name, "lines.csv"))["midline"]
    t = max(lines)
    ax.plot(x, T, "-", color=colour, lw=1, label=f"exact: {labels[name]}")
    ax.plot(lines[t][0], lines[t][2]["T"], "o", color=colour, ms=3, label=f"tmfdem: {labels[name]}")
ax.set_xlabel("x [m]")
ax.set_ylabel("T [C]")
ax.set_title("cut_plate: steady temperature along y = 0.125 m")
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(png, dpi=120)
