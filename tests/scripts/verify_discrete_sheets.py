#!/usr/bin/env python3
"""Paper 5.3 in the discrete layer (model discrete thermo-mechanics), dT =
+100 and -100 C: the free sheet takes the strain alpha dT (plane stress)
within 0.5 % with stresses below 1e-2 E alpha |dT|; the sheet on rollers
carries -E alpha dT / (1 - nu) (plane stress) and -E alpha dT / (1 - 2 nu)
(plane strain) within 0.1 % (with the default Joint compliance
compensation; 1 % before it). (The paper reports 3.3 % and 2.75 %.)"""
import os
import sys

import numpy as np

from analytic import read_csv
from common import run, check

binary, out = sys.argv[1], sys.argv[2]
prm_dir = os.path.join(os.path.dirname(__file__), "..", "..", "prm")
E, nu, alpha = 75.1e9, 0.311, 3e-6
ok = True


def final_probes(folder):
    probes = read_csv(os.path.join(folder, "probes.csv"))
    result = {}
    for name, by_time in probes.items():
        t = max(by_time)
        x, y, fields = by_time[t]
        result[name] = (x[0], y[0], {k: v[0] for k, v in fields.items()})
    return result


for dT in (100.0, -100.0):
    folder = os.path.join(out, f"free_{dT:+.0f}")
    run(binary, os.path.join(prm_dir, "sheet_free_expansion.prm"), folder,
        f"Initial conditions/Temperature={dT}", "Output/Write vtu=false")
    p = final_probes(folder)
    worst_strain, worst_stress = 0.0, 0.0
    for name, (x, y, f) in p.items():
        for u, X in ((f["ux"], x), (f["uy"], y)):
            worst_strain = max(worst_strain, abs(u / X / (alpha * dT) - 1.0))
        worst_stress = max(worst_stress, abs(f["sxx"]), abs(f["syy"]), abs(f["sxy"]))
    ok &= check(worst_strain < 0.005, f"free sheet, dT = {dT:+.0f} C: strain u/x vs alpha dT, "
                f"worst error {100 * worst_strain:.4f} % (< 0.5 %)")
    ok &= check(worst_stress < 1e-2 * E * alpha * abs(dT),
                f"free sheet, dT = {dT:+.0f} C: max |stress| {worst_stress:.0f} Pa = "
                f"{worst_stress / (E * alpha * abs(dT)):.1e} E alpha |dT| (< 1e-2)")
    for idealisation, modulus in (("plane stress", E / (1 - nu)), ("plane strain", E / (1 - 2 * nu))):
        if idealisation == "plane strain" and dT < 0:
            continue
        folder = os.path.join(out, f"restrained_{idealisation.replace(' ', '_')}_{dT:+.0f}")
        run(binary, os.path.join(prm_dir, "sheet_restrained_expansion.prm"), folder,
            f"Initial conditions/Temperature={dT}", f"Mechanics/Idealisation={idealisation}",
            "Output/Write vtu=false")
        exact = -modulus * alpha * dT
        p = final_probes(folder)
        worst = max(max(abs(f["sxx"] / exact - 1.0), abs(f["syy"] / exact - 1.0))
                    for (x, y, f) in p.values())
        ok &= check(worst < 0.001, f"restrained sheet, {idealisation}, dT = {dT:+.0f} C: "
                    f"sigma vs {exact / 1e6:.4f} MPa, worst error {100 * worst:.4f} % (< 0.1 %)")
sys.exit(0 if ok else 1)
