#!/usr/bin/python3
"""Plots T, sigma_r and sigma_theta along 'radial' of prm/thick_cylinder.prm
(discrete layer) against the plane-strain Eq. 49 (tension positive).
usage: scripts/plot_cylinder_discrete.py <output folder> <png>"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests", "scripts"))
from analytic import read_csv, cylinder_stress, cylinder_temperature  # noqa: E402

folder, png = sys.argv[1], sys.argv[2]
lines = read_csv(os.path.join(folder, "lines.csv"))["radial"]
t = max(lines)
x, y, f = lines[t]
r = np.hypot(np.array(x), np.array(y))
rr = np.linspace(0.03, 0.15, 400)
sr, st = cylinder_stress(rr)
fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
a1.plot(rr, cylinder_temperature(rr), "k-", lw=1, label="exact")
a1.plot(r, f["T"], "o", ms=3, label="tmfdem (discrete)")
a1.set_xlabel("r [m]")
a1.set_ylabel("T [C]")
a1.legend()
a2.plot(rr, sr / 1e6, "k-", lw=1, label="Eq. 49, plane strain")
a2.plot(rr, st / 1e6, "k--", lw=1)
a2.plot(r, np.array(f["sxx"]) / 1e6, "o", ms=3, label="sigma_r (discrete, recovered)")
a2.plot(r, np.array(f["syy"]) / 1e6, "s", ms=3, label="sigma_theta (discrete, recovered)")
a2.set_xlabel("r [m]")
a2.set_ylabel("stress [MPa], tension positive")
a2.legend(fontsize=8)
fig.suptitle("thick_cylinder (paper 5.4), discrete layer, h = 4 mm, plane strain;\n"
             "stresses recovered by quadratic patch fits, walls from their traction and stretch")
fig.tight_layout()
fig.savefig(png, dpi=120)
