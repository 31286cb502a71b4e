#!/usr/bin/env python3
"""Paper 5.4 in the discrete layer (prm/thick_cylinder.prm, discrete
thermo-mechanics, quasi-static, plane strain): T along 'radial' within
0.5 C; recovered sigma_r, sigma_theta within 3 % of max |sigma_theta| of the
plane-strain Eq. 49 (tension positive) along the whole line, both walls
included (boundary vertices take the stress from the walls' zero traction
and tangential stretch, doc/theory.md "Stress recovery at vertices"), and
also reported from two element sizes off the walls; heat balance 1e-6.
Three cases: the shipped one (a = 0.03 m, b = 0.15 m, 100 C / 0 C,
h = 4 mm), the same at h = 8 mm (a / h = 3.75: the first ring of
triangles spans the steepest part of sigma_theta, where the recovery's
quadratic patch polynomials matter) and one with other radii, wall
temperatures and element size (a = 0.05 m, b = 0.12 m, 200 C / 50 C,
h = 6 mm)."""
import os
import sys

import numpy as np

from analytic import read_csv, cylinder_stress, cylinder_temperature
from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "thick_cylinder.prm")


def case(name, a, b, t_a, t_b, h, settings):
    folder = os.path.join(out, name)
    run(binary, prm, folder, "Output/Write vtu=false", *settings)
    lines = read_csv(os.path.join(folder, "lines.csv"))["radial"]
    t = max(lines)
    x, y, f = lines[t]
    r = np.hypot(np.array(x), np.array(y))
    ok = True
    T_error = np.abs(np.array(f["T"]) - cylinder_temperature(r, a, b, t_a, t_b)).max()
    ok &= check(T_error <= 0.5, f"{name}: T along radial: max error {T_error:.4f} C (<= 0.5 C)")
    sr, st = cylinder_stress(r, a=a, b=b, t_a=t_a, t_b=t_b)
    scale = np.abs(st).max()
    er = np.abs(np.array(f["sxx"]) - sr) / scale   # on y = 0: sxx = sigma_r
    et = np.abs(np.array(f["syy"]) - st) / scale   # syy = sigma_theta
    interior = (r >= a + 2 * h) & (r <= b - 2 * h)
    print(f"{name}: a + 2h <= r <= b - 2h: sigma_r error {100 * er[interior].max():.2f} %, "
          f"sigma_theta {100 * et[interior].max():.2f} %; inner wall point: "
          f"{100 * er[0]:.2f} %, {100 * et[0]:.2f} %; outer wall point: "
          f"{100 * er[-1]:.2f} %, {100 * et[-1]:.2f} %")
    ok &= check(er.max() < 0.03 and et.max() < 0.03,
                f"{name}: whole line incl. the walls: sigma_r error {100 * er.max():.2f} %, "
                f"sigma_theta {100 * et.max():.2f} % of max |sigma_theta| (< 3 %)")
    s = summary(folder)
    rel = s["heat_balance"]["relative_imbalance"]
    ok &= check(rel < 1e-6, f"{name}: heat balance {rel:.1e} (< 1e-6)")
    ok &= check(s["last_kinetic_to_strain_energy"] < 1e-6,
                f"{name}: relaxed: kinetic / strain energy "
                f"{s['last_kinetic_to_strain_energy']:.1e}")
    return ok


ok = case("shipped", 0.03, 0.15, 100.0, 0.0, 0.004, [])
ok &= case("coarse", 0.03, 0.15, 100.0, 0.0, 0.008, ["Mesh/Element size=0.008"])
a, b, h = 0.05, 0.12, 0.006
ok &= case("other", a, b, 200.0, 50.0, h, [
    f"Mesh/Inner radius={a}", f"Mesh/Outer radius={b}", f"Mesh/Element size={h}",
    "Thermal boundary conditions/Condition 1/Temperature=200",
    "Thermal boundary conditions/Condition 2/Temperature=50",
    f"Monitors/Probes=inner: {a + 1e-4}, 0; outer: {b - 1e-4}, 0",
    f"Monitors/Lines=radial: {a + 1e-4}, 0.0001, {b - 1e-4}, 0.0001, 121"])
sys.exit(0 if ok else 1)
