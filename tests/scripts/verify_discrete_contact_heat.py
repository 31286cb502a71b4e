#!/usr/bin/env python3
"""Heat across contacts in the discrete layer (prm/contact_conduction.prm):
  steady:      two blocks pressed together between a hot and a cold face
               carry q = dT / (L1/k1 + 1/h_c + L2/k2) within 1 %, with the
               temperature jump q / h_c at the contact within 1 %;
  equilibrate: the same blocks, insulated, highly conducting (nearly
               isothermal), start at 100 C and 0 C (Materials/Material <id>/
               Initial temperature): their difference decays as
               100 C exp(-t / tau), tau = C1 C2 / ((C1 + C2) h_c L), within
               2 %, the fitted amplitude within 1 % of 100 C (Biot number
               h_c L / k = 0.005: each block evens out internally in
               L^2 / kappa = 20 s << tau);
  the heat balance closes to 1e-6 relative in both."""
import math
import os
import sys

import numpy as np

from analytic import read_csv
from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "contact_conduction.prm")
ok = True
width, delta, h_c = 0.05, 1e-5, 50.0

folder = os.path.join(out, "steady")
run(binary, prm, folder)
s = summary(folder)
k1, k2, L1, L2 = 2.0, 5.0, 0.1, 0.1 - delta
q = 100.0 / (L1 / k1 + 1.0 / h_c + L2 / k2)
Q = s["heat_balance"]["boundary_heat_rate_last_step"]["1"]
error = abs(Q / (q * width) - 1.0)
ok &= check(error < 0.01, f"steady heat flow {Q:.5f} W/m vs q w = {q * width:.5f} W/m, "
            f"error {100 * error:.3f} % (< 1 %)")
lines = read_csv(os.path.join(folder, "lines.csv"))["axis"]
t_end = max(lines)
y, T = np.array(lines[t_end][1]), np.array(lines[t_end][2]["T"])
below, above = (y > 0.02) & (y < 0.09), (y > 0.11) & (y < 0.18)
T_below = np.polyval(np.polyfit(y[below], T[below], 1), 0.1 - delta / 2)
T_above = np.polyval(np.polyfit(y[above], T[above], 1), 0.1 - delta / 2)
jump, expected = T_below - T_above, q / h_c
ok &= check(abs(jump / expected - 1.0) < 0.01,
            f"temperature jump at the contact {jump:.4f} C vs q / h_c = {expected:.4f} C")
rel = s["heat_balance"]["relative_imbalance"]
ok &= check(rel < 1e-6, f"steady run: heat balance closes to {rel:.1e} (< 1e-6)")

folder = os.path.join(out, "equilibrate")
run(binary, prm, folder,
    "Thermal boundary conditions/Condition 1/Boundary ids=",
    "Thermal boundary conditions/Condition 2/Boundary ids=",
    "Materials/Material 1/Thermal conductivity=1000",
    "Materials/Material 2/Thermal conductivity=1000",
    "Materials/Material 1/Initial temperature=100",
    "Materials/Material 2/Initial temperature=0",
    "Time stepping/End time=6000", "Time stepping/Time step=5",
    "Output/Interval=500", "Output/Write vtu=false",
    "Monitors/Lines=", "Monitors/Probes=lower: 0.025, 0.05; upper: 0.025, 0.15")
probes = read_csv(os.path.join(folder, "probes.csv"))
times = sorted(t for t in probes["lower"] if t > 0)
difference = np.array([probes["lower"][t][2]["T"][0] - probes["upper"][t][2]["T"][0]
                       for t in times])
slope, intercept = np.polyfit(times, np.log(difference), 1)
tau_fit, amplitude = -1.0 / slope, np.exp(intercept)
C = 2500.0 * 800.0 * width * 0.1        # each block, J/(m K) (block 2 is delta shorter)
C2 = 2500.0 * 800.0 * width * (0.1 - delta)
tau = C * C2 / ((C + C2) * h_c * width)
error = abs(tau_fit / tau - 1.0)
ok &= check(error < 0.02, f"equilibration time constant {tau_fit:.2f} s vs lumped "
            f"C1 C2 / ((C1 + C2) h_c L) = {tau:.2f} s, error {100 * error:.3f} % (< 2 %)")
error = abs(amplitude / 100.0 - 1.0)
ok &= check(error < 0.01, f"equilibration: fitted amplitude {amplitude:.3f} C vs the initial "
            f"difference 100 C, error {100 * error:.3f} % (< 1 %)")
rel = summary(folder)["heat_balance"]["relative_imbalance"]
ok &= check(rel < 1e-6, f"equilibration: heat balance closes to {rel:.1e} (< 1e-6)")
sys.exit(0 if ok else 1)
