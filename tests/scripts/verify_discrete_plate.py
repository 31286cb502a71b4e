#!/usr/bin/env python3
"""Paper 5.1 in the discrete layer (prm/plate_transient.prm: exploded P1
triangles joined by conducting joints, backward Euler).
  - h = 0.05 m (the paper's): max |T - T_exact| along 'midline' <= 0.5 C at
    t = 10, 20, 50 s; at t = 2 s the P1 error of this mesh is ~1.06 C (the
    continuum P1 solver on the same mesh has 1.1-1.4 C; it is the steep
    initial layer at the hot end, width sqrt(kappa t) = 0.1 m = 2 h), so
    t = 2 s is held to 1.2 C and to 0.5 C at h = 0.025 m;
  - h = 0.025 m: <= 0.5 C at all four times (second order: ~7x smaller);
  - joint conductance factor beta: the difference to the continuum P1
    solver on the same mesh and steps falls like 1/beta;
  - explicit (lumped) integration at its stable step agrees with the series;
  - the heat balance closes to 1e-6 relative in every run."""
import os
import sys

import numpy as np

from analytic import plate_transient, read_csv
from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "plate_transient.prm")
ok = True


def errors(folder, times=(2.0, 10.0, 20.0, 50.0)):
    lines = read_csv(os.path.join(folder, "lines.csv"))["midline"]
    return {t: float(np.abs(np.array(lines[t][2]["T"]) - plate_transient(lines[t][0], t)).max())
            for t in times}


def balance(folder, label):
    s = summary(folder)
    rel = s["heat_balance"]["relative_imbalance"]
    return check(rel < 1e-6, f"{label}: heat balance closes to {rel:.1e} (< 1e-6)")


folder = os.path.join(out, "h0.05")
run(binary, prm, folder)
e = errors(folder)
for t in (10.0, 20.0, 50.0):
    ok &= check(e[t] <= 0.5, f"h = 0.05 m, t = {t:4.0f} s: max error {e[t]:.4f} C <= 0.5 C")
ok &= check(e[2.0] <= 1.2, f"h = 0.05 m, t =    2 s: max error {e[2.0]:.4f} C <= 1.2 C "
            "(P1 limit of this mesh, see doc/cases/plate_transient.md)")
ok &= balance(folder, "h = 0.05 m")

folder = os.path.join(out, "h0.025")
run(binary, prm, folder, "Mesh/Element size=0.025", "Output/Write vtu=false")
e2 = errors(folder)
for t, v in e2.items():
    ok &= check(v <= 0.5, f"h = 0.025 m, t = {t:4.0f} s: max error {v:.4f} C <= 0.5 C")
ok &= check(e[2.0] / e2[2.0] > 3.0, f"refinement h -> h/2 cuts the t = 2 s error by "
            f"{e[2.0] / e2[2.0]:.1f} (> 3, second order)")
ok &= balance(folder, "h = 0.025 m")

continuum = os.path.join(out, "continuum_P1")
run(binary, prm, continuum, "Model=continuum heat", "Heat solver/Polynomial degree=1",
    "Time stepping/Method=backward Euler", "Output/Write vtu=false")
reference = read_csv(os.path.join(continuum, "lines.csv"))["midline"]
differences = []
for beta in (100, 1000, 10000):
    folder = os.path.join(out, f"beta{beta}")
    run(binary, prm, folder, f"Discrete heat/Joint conductance factor={beta}",
        "Output/Write vtu=false")
    lines = read_csv(os.path.join(folder, "lines.csv"))["midline"]
    d = max(float(np.abs(np.array(lines[t][2]["T"]) - np.array(reference[t][2]["T"])).max())
            for t in (2.0, 10.0, 50.0))
    differences.append(d)
    print(f"beta = {beta:6d}: max |T_discrete - T_continuum| = {d:.3e} C")
    ok &= balance(folder, f"beta = {beta}")
for (b1, d1), (b2, d2) in zip(zip((100, 1000), differences), zip((1000, 10000), differences[1:])):
    ratio = d1 / d2
    ok &= check(8.0 < ratio < 12.0, f"beta {b1} -> {b2}: difference falls by {ratio:.2f} (~10, i.e. 1/beta)")

folder = os.path.join(out, "explicit")
run(binary, prm, folder, "Discrete heat/Time integration=explicit",
    "Discrete heat/Joint conductance factor=100", "Time stepping/End time=10",
    "Time stepping/Time step=4e-4", "Output/Times=2, 10", "Output/Write vtu=false")
s = summary(folder)
ee = errors(folder, (2.0, 10.0))
ok &= check(s["time_step"] <= s["stable_explicit_time_step"],
            f"explicit step {s['time_step']:.2e} s <= stable {s['stable_explicit_time_step']:.3e} s")
ok &= check(ee[10.0] <= 0.5 and ee[2.0] <= 1.2,
            f"explicit lumped, beta = 100: max error {ee[2.0]:.4f} C at 2 s, {ee[10.0]:.4f} C at 10 s")
ok &= balance(folder, "explicit")
sys.exit(0 if ok else 1)
