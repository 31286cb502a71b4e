#!/usr/bin/python3
"""Finite-strain thermoelasticity (continuum, Eq. 44 on F_e):
1. restrained sheet with alpha dT = 0.05: sigma_xx = sigma_yy = Eq. 44 with
   F_e = I/(1 + alpha dT) to 1e-8 (both idealisations), and finite minus
   small strain equals the exact difference of doc/theory.md (to 1e-6 of
   that difference); its leading term is (lambda - mu) s^2;
2. a rigid rotation by 90 degrees of the left edge (the other edges free),
   in 10 load steps, turns the whole sheet without stress (below 1e-9 E)
   and moves the corner (2, 2) to (-2, 2); Newton (whose first, linearised
   step stretches the sheet) converges quadratically in every step;
3. the same rotation combined with free thermal expansion s = 0.05
   (u = (1 + s) R X - X on the left edge) gives no stress either."""
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv, restrained_sheet_stress, in_plane_constants

binary, prm, out = sys.argv[1:4]
E, nu, alpha, dT = 75.1e9, 0.311, 5e-4, 100.0
ok = True


def probe_values(folder):
    probes = read_csv(f"{folder}/probes.csv")
    return {name: {c: v[0] for c, v in by_time[max(by_time)][2].items()} for name, by_time in probes.items()}


for idealisation in ("plane stress", "plane strain"):
    tag = idealisation.replace(" ", "_")
    finite_dir, small_dir = f"{out}/restrained_finite_{tag}", f"{out}/restrained_small_{tag}"
    run(binary, prm, finite_dir, f"Mechanics/Idealisation={idealisation}")
    run(binary, prm, small_dir, f"Mechanics/Idealisation={idealisation}", "Mechanics/Strain measure=small")
    exact_finite = restrained_sheet_stress(E, nu, alpha, dT, idealisation, True)
    exact_small = restrained_sheet_stress(E, nu, alpha, dT, idealisation, False)
    lam, mu, factor = in_plane_constants(E, nu, idealisation)
    s = factor * alpha * dT
    finite, small = probe_values(finite_dir), probe_values(small_dir)
    err = max(abs(finite[p][c] / exact_finite - 1) for p in finite for c in ("sxx", "syy"))
    ok &= check(err < 1e-8, f"{idealisation}: restrained, s = beta dT = {s:.4f}: sigma = "
                f"{finite['centre']['sxx'] / 1e6:.6f} MPa vs Eq. 44 {exact_finite / 1e6:.6f} MPa, "
                f"relative error {err:.1e} < 1e-8")
    difference = finite["centre"]["sxx"] - small["centre"]["sxx"]
    exact_difference = exact_finite - exact_small
    leading = (lam - mu) * s**2
    err_d = abs(difference - exact_difference) / abs(exact_difference)
    ok &= check(err_d < 1e-6, f"{idealisation}: finite - small = {difference / 1e6:.6f} MPa vs theory "
                f"{exact_difference / 1e6:.6f} MPa (relative error {err_d:.1e}); leading term "
                f"(lambda - mu) s^2 = {leading / 1e6:.4f} MPa, next -2 lambda s^3 = {-2 * lam * s**3 / 1e6:.4f} MPa")

rotation = "(pi/2)*t"
for name, stretch in (("rotation", "1"), ("heated_rotation", "(1 + 0.05*t)")):
    folder = f"{out}/{name}"
    settings = ["Mechanics/Temperature=100*t" if name == "heated_rotation" else "Mechanics/Temperature=0",
                "Time stepping/Time step=0.1",
                "Mechanical boundary conditions/Condition 1/Boundary ids=0",
                "Mechanical boundary conditions/Condition 1/Type=displacement",
                f"Mechanical boundary conditions/Condition 1/Displacement x="
                f"{stretch}*(cos({rotation})*x - sin({rotation})*y) - x",
                f"Mechanical boundary conditions/Condition 1/Displacement y="
                f"{stretch}*(sin({rotation})*x + cos({rotation})*y) - y",
                "Mechanical boundary conditions/Condition 2/Boundary ids="]
    run(binary, prm, folder, *settings)
    stress = summary(folder)["stress"]
    largest = max(stress["max_abs_sxx"], stress["max_abs_syy"], stress["max_abs_sxy"])
    ok &= check(largest < 1e-9 * E, f"{name} by 90 degrees: max |sigma| = {largest:.2e} Pa < 1e-9 E = {1e-9 * E:.1f} Pa")
    corner = probe_values(folder)["corner"]
    k = 1.05 if name == "heated_rotation" else 1.0
    moved = np.array([2 + corner["ux"], 2 + corner["uy"]])
    history = summary(folder)["newton_history"]
    worst_iterations = 0
    for t in sorted(set(h["time"] for h in history)):
        residuals = [h["residual"] for h in history if h["time"] == t]
        worst_iterations = max(worst_iterations, len(residuals) - 1)
        if abs(t - 0.5) < 1e-12:
            print(f"  {name}: Newton residuals at t = 0.5 [N/m]:", ", ".join(f"{r:.2e}" for r in residuals))
    ok &= check(worst_iterations <= 8, f"{name}: Newton converges in at most {worst_iterations} iterations per load step (<= 8)")
    ok &= check(np.abs(moved - k * np.array([-2.0, 2.0])).max() < 1e-10,
                f"{name}: corner (2, 2) moves to ({moved[0]:.12f}, {moved[1]:.12f})")
sys.exit(0 if ok else 1)
