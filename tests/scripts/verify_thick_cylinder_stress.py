#!/usr/bin/python3
"""Paper 5.4, thermal stress at steady state (continuum, heat solver ->
thermoelastic, small strain): sigma_r and sigma_theta along 'radial' within
1 % of max |sigma_theta| of the analytic solution of the run's own
idealisation: plane strain = -Eq. 49 (tension positive), plane stress the
same bracket with E alpha dT / 2. A third run takes the temperature as the
exact function T(r) and adapts the mesh on the displacement (Kelly,
refine and coarsen with p4est) instead of on the temperature."""
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv, cylinder_stress, cylinder_temperature

binary, prm, out = sys.argv[1:4]
ok = True
runs = [("plane strain", "plane_strain", []), ("plane stress", "plane_stress", []),
        ("plane strain", "function_amr",
         ["Mechanics/Temperature source=function",
          "Mechanics/Temperature=100*log(0.15/sqrt(x^2+y^2))/log(5)",
          "Adaptive refinement/Coarsen fraction=0.02"])]
for idealisation, tag, extra in runs:
    folder = f"{out}/{tag}"
    run(binary, prm, folder, f"Mechanics/Idealisation={idealisation}", *extra)
    data = read_csv(f"{folder}/lines.csv")["radial"]
    x, y, f = data[max(data)]
    r = np.hypot(x, y)
    s_r, s_t = cylinder_stress(r, idealisation=idealisation)
    scale = abs(s_t).max()
    err_r = abs(f["srr"] - s_r).max() / scale
    err_t = abs(f["stt"] - s_t).max() / scale
    err_T = abs(f["T"] - cylinder_temperature(r)).max()
    idealisation_run = idealisation
    idealisation = f"{idealisation} ({tag}, {summary(folder)['dofs']} DoFs)"
    print(f"  {idealisation}: sigma_theta(a) = {f['stt'][0] / 1e6:.4f} MPa (exact {s_t[0] / 1e6:.4f}), "
          f"sigma_theta(b) = {f['stt'][-1] / 1e6:.4f} MPa (exact {s_t[-1] / 1e6:.4f})")
    ok &= check(err_r < 0.01, f"{idealisation}: max |sigma_r - exact| / max |sigma_theta| = {err_r:.2e} < 1 %")
    ok &= check(err_t < 0.01, f"{idealisation}: max |sigma_theta - exact| / max |sigma_theta| = {err_t:.2e} < 1 %")
    ok &= check(err_T < 0.5, f"{idealisation}: max |T - T_exact| = {err_T:.3f} C < 0.5 C")
    ok &= check(summary(folder)["model"] == "continuum thermoelastic" and
                summary(folder)["idealisation"] == idealisation_run, f"{idealisation}: summary names the model")
sys.exit(0 if ok else 1)
