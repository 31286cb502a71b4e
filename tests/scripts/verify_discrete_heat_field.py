#!/usr/bin/env python3
"""The continuum thermoelastic model with the discrete layer's heat as its
temperature (Mechanics/Temperature source = discrete heat) on paper 5.4's
thick cylinder (prm/thick_cylinder.prm's mesh and heat settings, one
backward Euler step of 1e6 s to the steady state, plane strain, P2
displacements): T along 'radial' within the discrete target 0.5 C, and
sigma_r, sigma_theta within the discrete target 2 % of max |sigma_theta|
(design doc, 5.4) of the plane-strain Eq. 49 on the whole line. Two cases:
the shipped radii and temperatures (h = 4 mm) and other ones (a = 0.05 m,
b = 0.12 m, 200 C / 50 C, h = 6 mm). The same run with Temperature source
= heat solver is set beside it (differences reported)."""
import os
import sys

import numpy as np

from analytic import read_csv, cylinder_stress, cylinder_temperature
from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "thick_cylinder.prm")


def radial(folder):
    lines = read_csv(os.path.join(folder, "lines.csv"))["radial"]
    x, y, f = lines[max(lines)]
    return np.hypot(np.array(x), np.array(y)), {k: np.array(v) for k, v in f.items()}


def case(name, a, b, t_a, t_b, settings):
    common = ["Model=continuum thermoelastic", "Output/Write vtu=false",
              "Mechanics/Polynomial degree=2",
              f"Mechanics/Pinned points={b}, 0: y; {-b}, 0: y; 0, {b}: x", *settings]
    folder = os.path.join(out, name)
    run(binary, prm, folder, *common, "Mechanics/Temperature source=discrete heat")
    side = os.path.join(out, name + "-heat_solver")
    run(binary, prm, side, *common, "Mechanics/Temperature source=heat solver")
    ok = check(summary(folder)["temperature_source"] == "discrete heat",
               f"{name}: summary temperature_source = discrete heat")
    r, f = radial(folder)
    T_error = np.abs(f["T"] - cylinder_temperature(r, a, b, t_a, t_b)).max()
    ok &= check(T_error <= 0.5, f"{name}: T along radial: max error {T_error:.4f} C (<= 0.5 C)")
    sr, st = cylinder_stress(r, a=a, b=b, t_a=t_a, t_b=t_b)
    scale = np.abs(st).max()
    er = np.abs(f["sxx"] - sr).max() / scale  # on y ~ 0: sxx = sigma_r
    et = np.abs(f["syy"] - st).max() / scale
    ok &= check(er < 0.02 and et < 0.02,
                f"{name}: sigma_r error {100 * er:.3f} %, sigma_theta {100 * et:.3f} % of "
                f"max |sigma_theta| on the whole line (< 2 %)")
    r2, g = radial(side)
    print(f"{name}: beside Temperature source = heat solver: max |dT| "
          f"{np.abs(f['T'] - g['T']).max():.4f} C, max |d sigma_r| "
          f"{100 * np.abs(f['sxx'] - g['sxx']).max() / scale:.3f} %, max |d sigma_theta| "
          f"{100 * np.abs(f['syy'] - g['syy']).max() / scale:.3f} % of max |sigma_theta|")
    return ok


ok = case("shipped", 0.03, 0.15, 100.0, 0.0, [])
a, b, h = 0.05, 0.12, 0.006
ok &= case("other", a, b, 200.0, 50.0, [
    f"Mesh/Inner radius={a}", f"Mesh/Outer radius={b}", f"Mesh/Element size={h}",
    "Thermal boundary conditions/Condition 1/Temperature=200",
    "Thermal boundary conditions/Condition 2/Temperature=50",
    f"Monitors/Probes=inner: {a + 1e-4}, 0; outer: {b - 1e-4}, 0",
    f"Monitors/Lines=radial: {a + 1e-4}, 0.0001, {b - 1e-4}, 0.0001, 121"])
sys.exit(0 if ok else 1)
