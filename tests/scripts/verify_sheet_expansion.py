#!/usr/bin/python3
"""Paper 5.3 (continuum, small strain): a 2 m square sheet heated and cooled
by dT = +-100 C, plane stress and plane strain.
Free sheet (rollers on the left and bottom edges only): strain beta dT within
0.1 % (beta = alpha in plane stress, (1 + nu) alpha in plane strain) and
stress below 1e-3 E alpha |dT|. Restrained sheet (rollers on all edges):
sigma_xx = sigma_yy = -E alpha dT/(1 - nu) (plane stress), -E alpha dT/(1 - 2 nu)
(plane strain) within 0.1 %."""
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv, restrained_sheet_stress

binary, prm_dir, out = sys.argv[1:4]
E, nu, alpha = 75.1e9, 0.311, 3e-6
ok = True
for idealisation in ("plane stress", "plane strain"):
    beta = alpha * (1 + nu if idealisation == "plane strain" else 1)
    tag = idealisation.replace(" ", "_")
    for dT in (100.0, -100.0):
        settings = [f"Mechanics/Temperature={dT:g}", f"Mechanics/Idealisation={idealisation}"]
        # free expansion
        folder = f"{out}/free_{tag}_{dT:+g}"
        run(binary, f"{prm_dir}/sheet_free_expansion-continuum.prm", folder, *settings)
        probes = read_csv(f"{folder}/probes.csv")
        lines = read_csv(f"{folder}/lines.csv")["diagonal"]
        x, y, f = lines[max(lines)]
        strain_x = f["ux"][x > 0] / x[x > 0]
        strain_y = f["uy"][y > 0] / y[y > 0]
        strain_error = max(abs(strain_x / (beta * dT) - 1).max(), abs(strain_y / (beta * dT) - 1).max())
        ok &= check(strain_error < 1e-3,
                    f"free, {idealisation}, dT = {dT:+g} C: strain u/x = {strain_x.mean():.6e} vs "
                    f"beta dT = {beta * dT:.6e}, max relative error {strain_error:.2e} < 1e-3")
        stress = summary(folder)["stress"]
        largest = max(stress["max_abs_sxx"], stress["max_abs_syy"], stress["max_abs_sxy"])
        sampled = max(abs(f[c]).max() for c in ("sxx", "syy", "sxy"))
        for name, by_time in probes.items():
            sampled = max(sampled, max(abs(by_time[max(by_time)][2][c]).max() for c in ("sxx", "syy", "sxy")))
        bound = 1e-3 * E * alpha * abs(dT)
        ok &= check(max(largest, sampled) < bound,
                    f"free, {idealisation}, dT = {dT:+g} C: max |stress| = {max(largest, sampled):.3e} Pa "
                    f"< 1e-3 E alpha |dT| = {bound:.3e} Pa")
        # restrained
        folder = f"{out}/restrained_{tag}_{dT:+g}"
        run(binary, f"{prm_dir}/sheet_restrained_expansion-continuum.prm", folder, *settings)
        exact = restrained_sheet_stress(E, nu, alpha, dT, idealisation, finite=False)
        formula = -E * alpha * dT / (1 - nu) if idealisation == "plane stress" else -E * alpha * dT / (1 - 2 * nu)
        assert abs(exact / formula - 1) < 1e-12
        worst = 0.0
        for name, by_time in list(read_csv(f"{folder}/probes.csv").items()) + \
                [("diagonal", read_csv(f"{folder}/lines.csv")["diagonal"])]:
            _, _, g = by_time[max(by_time)]
            worst = max(worst, abs(g["sxx"] / exact - 1).max(), abs(g["syy"] / exact - 1).max(),
                        abs(g["sxy"]).max() / abs(exact))
        ok &= check(worst < 1e-3,
                    f"restrained, {idealisation}, dT = {dT:+g} C: sigma_xx = sigma_yy vs "
                    f"{formula / 1e6:.4f} MPa, max relative error {worst:.2e} < 1e-3")
sys.exit(0 if ok else 1)
