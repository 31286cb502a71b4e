#!/usr/bin/python3
"""The continuum thermo-mechanical loop (coupling/continuum_thermomechanics):
paper 5.4's hollow cylinder, transient heat from T = 0 with the walls at
100 / 0 C, the stress solved at its own coupling times.

Run 1, Coupling interval = 200 s, outputs every 500 s to 1000 s: the
mechanics is solved exactly at 0, 200, 400, 500, 600, 800, 1000 s (Newton
history), both models write only at 0, 500, 1000 s, the temperature the
mechanics reports at its probes is the heat solver's at the same time
(the field handed over is the current one), and at 1000 s (about 80 thermal
time constants (b - a)^2 / (pi^2 kappa) = 12 s) the stress is the steady
analytic one of Eq. 49 within 1 % of max |sigma_theta| (the bound of the
steady case; Q3 displacement as in the case file, on the mesh of 4 initial
Kelly refinements on the temperature). Run 2, Coupling interval = 0 (the default): the mechanics is
solved at the output times only, as before the loop was written out."""
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv, cylinder_stress

binary, prm, out = sys.argv[1:4]
ok = True
common = ["Time stepping/Mode=transient", "Time stepping/End time=1000",
          "Time stepping/Time step=50", "Time stepping/Method=backward Euler",
          "Output/Interval=500", "Adaptive refinement/Initial refinements=4",
          "Adaptive refinement/Interval=1000"]


def pvd_times(path):
    with open(path) as f:
        return sorted({float(line.split('timestep="')[1].split('"')[0])
                       for line in f if 'timestep="' in line})


def probe_values(path, name, column):
    """{time: value} of one probe in probes.csv."""
    values = {}
    with open(path) as f:
        header = f.readline().strip().split(",")
        for line in f:
            row = line.strip().split(",")
            if row[header.index("name")] == name:
                values[float(row[header.index("time")])] = float(row[header.index(column)])
    return values


folder = f"{out}/interval"
run(binary, prm, folder, *common, "Mechanics/Coupling interval=200")
s = summary(folder)
solved = sorted({record["time"] for record in s["newton_history"]})
expected = [0., 200., 400., 500., 600., 800., 1000.]
ok &= check(solved == expected, f"mechanics solved at {solved} s (expected {expected})")
ok &= check(s["steps"] == len(expected), f"{s['steps']} solves (expected {len(expected)})")
for name in ("solution.pvd", "heat/solution.pvd"):
    times = pvd_times(f"{folder}/{name}")
    ok &= check(times == [0., 500., 1000.], f"{name} at {times} s (expected 0, 500, 1000)")
for probe in ("inner", "middle", "outer"):
    mech = probe_values(f"{folder}/probes.csv", probe, "T")
    heat = probe_values(f"{folder}/heat/probes.csv", probe, "T")
    diff = max(abs(mech[t] - heat[t]) for t in heat)
    ok &= check(sorted(mech) == sorted(heat) and diff <= 1e-12 * 100,
                f"probe {probe}: mechanics' T = heat solver's T at every output (max diff {diff:.1e} C)")
data = read_csv(f"{folder}/lines.csv")["radial"]
x, y, f = data[max(data)]
r = np.hypot(x, y)
s_r, s_t = cylinder_stress(r, idealisation="plane strain")
scale = abs(s_t).max()
err_r = abs(f["srr"] - s_r).max() / scale
err_t = abs(f["stt"] - s_t).max() / scale
ok &= check(max(data) == 1000., f"last line sample at t = {max(data)} s")
ok &= check(err_r < 0.01, f"t = 1000 s: max |sigma_r - steady exact| / max |sigma_theta| = {err_r:.2e} < 1 %")
ok &= check(err_t < 0.01, f"t = 1000 s: max |sigma_theta - steady exact| / max |sigma_theta| = {err_t:.2e} < 1 %")

folder = f"{out}/outputs_only"
run(binary, prm, folder, *common)
solved = sorted({record["time"] for record in summary(folder)["newton_history"]})
ok &= check(solved == [0., 500., 1000.], f"Coupling interval = 0: mechanics solved at {solved} s (the output times)")
sys.exit(0 if ok else 1)
