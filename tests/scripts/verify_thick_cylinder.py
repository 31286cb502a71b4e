#!/usr/bin/python3
"""Paper 5.4, temperature at steady state (continuum, quadrilaterals, Kelly
AMR): max abs error along 'radial' <= 0.2 C, and the adaptive run gets there
with fewer DoFs than uniform refinement does. The case file's model is the
thermoelastic one; this test runs its heat part alone (Model = continuum
heat); verify_thick_cylinder_stress.py checks the stresses."""
import sys
import numpy as np
from common import run, summary, check
from analytic import cylinder_temperature, read_csv

binary, prm, out = sys.argv[1:4]


def radial_error(folder):
    data = read_csv(f"{folder}/lines.csv")["radial"]
    x, y, f = data[max(data)]
    return abs(f["T"] - cylinder_temperature(np.hypot(x, y))).max()


ok = True
run(binary, prm, f"{out}/amr", "Model=continuum heat")
amr_error, amr_dofs = radial_error(f"{out}/amr"), summary(f"{out}/amr")["dofs"]
ok &= check(amr_error <= 0.2, f"AMR: max |T - T_exact| = {amr_error:.4f} C <= 0.2 C with {amr_dofs} DoFs")
balance = summary(f"{out}/amr")["heat"]
ok &= check(balance["relative_imbalance"] < 1e-6,
            f"steady heat balance: inner {balance['boundary_heat_in']['0']:.3f} W/m, "
            f"outer {balance['boundary_heat_in']['1']:.3f} W/m, relative imbalance {balance['relative_imbalance']:.1e}")
exact_rate = 2 * np.pi * 3.0 * 100.0 / np.log(0.15 / 0.03)
ok &= check(abs(balance["boundary_heat_in"]["0"] - exact_rate) / exact_rate < 0.01,
            f"heat rate through the inner wall {balance['boundary_heat_in']['0']:.3f} W/m "
            f"vs 2 pi k dT / ln(b/a) = {exact_rate:.3f} W/m within 1 %")

uniform_dofs = None
for k in range(0, 6):
    folder = f"{out}/uniform{k}"
    run(binary, prm, folder, "Model=continuum heat", "Adaptive refinement/Enable=false", f"Mesh/Global refinements={k}",
        "Output/Write vtu=false")
    error, dofs = radial_error(folder), summary(folder)["dofs"]
    print(f"  uniform, {k} refinements: {dofs} DoFs, max error {error:.4f} C")
    if error <= 0.2:
        uniform_dofs = dofs
        break
ok &= check(uniform_dofs is not None and amr_dofs < uniform_dofs,
            f"AMR reaches 0.2 C with {amr_dofs} DoFs, uniform refinement needs {uniform_dofs}")
sys.exit(0 if ok else 1)
