#!/usr/bin/env python3
"""Paper 5.4 in the discrete layer (prm/thick_cylinder.prm, discrete
thermo-mechanics, quasi-static, plane strain, h = 4 mm): T along 'radial'
within 0.5 C; recovered sigma_r, sigma_theta within 3 % of max |sigma_theta|
of the plane-strain Eq. 49 (tension positive) from two element sizes off
the inner wall (r >= a + 2 h), and within 10 % at the wall itself, where
the patch recovery of the constant-stress triangles is first order (see
doc/cases/thick_cylinder.md); heat balance 1e-6."""
import os
import sys

import numpy as np

from analytic import read_csv, cylinder_stress, cylinder_temperature
from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "thick_cylinder.prm")
ok = True
run(binary, prm, out, "Output/Write vtu=false")
lines = read_csv(os.path.join(out, "lines.csv"))["radial"]
t = max(lines)
x, y, f = lines[t]
r = np.hypot(np.array(x), np.array(y))
T_error = np.abs(np.array(f["T"]) - cylinder_temperature(r)).max()
ok &= check(T_error <= 0.5, f"T along radial: max error {T_error:.4f} C (<= 0.5 C)")
sr, st = cylinder_stress(r)
scale = np.abs(st).max()
er = np.abs(np.array(f["sxx"]) - sr) / scale   # on y = 0: sxx = sigma_r
et = np.abs(np.array(f["syy"]) - st) / scale   # syy = sigma_theta
interior = r >= 0.03 + 2 * 0.004
ok &= check(er[interior].max() < 0.03 and et[interior].max() < 0.03,
            f"r >= a + 2h: sigma_r error {100 * er[interior].max():.2f} %, sigma_theta "
            f"{100 * et[interior].max():.2f} % of max |sigma_theta| (< 3 %)")
ok &= check(er.max() < 0.10 and et.max() < 0.10,
            f"whole line incl. the wall: sigma_r {100 * er.max():.2f} %, sigma_theta "
            f"{100 * et.max():.2f} % (< 10 %)")
s = summary(out)
rel = s["heat_balance"]["relative_imbalance"]
ok &= check(rel < 1e-6, f"heat balance {rel:.1e} (< 1e-6)")
ok &= check(s["last_kinetic_to_strain_energy"] < 1e-6,
            f"relaxed: kinetic / strain energy {s['last_kinetic_to_strain_energy']:.1e}")
sys.exit(0 if ok else 1)
