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
h = 6 mm). The third one reads the stresses in the polar frame
(Mechanics/Polar frame, centre 0, 0) along a line at 35 degrees: srr and
stt of lines.csv against Eq. 49 with the same bound, and srr, stt of the
solution vtu's cells against the rotation of their sxx, syy, sxy about the
centre to the deformed centroid (1e-9 of max |sigma_theta|; the vtu files
written with Output/Vtu precision = double for it)."""
import os
import sys

import numpy as np

from analytic import read_csv, cylinder_stress, cylinder_temperature
from common import run, summary, check

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts"))
from plot_discrete_case import read_vtu  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "thick_cylinder.prm")


def polar_cells(folder, scale):
    """srr, stt of the last solution vtu against the rotation of the cells'
    own sxx, syy, sxy about (0, 0) to their deformed centroids."""
    vtus = sorted(f for f in os.listdir(folder) if f.startswith("solution_") and
                  f.endswith(".vtu"))
    points, cells, arrays = read_vtu(os.path.join(folder, vtus[-1]))
    centroid = np.array([points[c, :2].mean(axis=0) for c in cells])
    angle = np.arctan2(centroid[:, 1], centroid[:, 0])
    c, s = np.cos(angle), np.sin(angle)
    sxx, syy, sxy = arrays["sxx"], arrays["syy"], arrays["sxy"]
    srr = sxx * c * c + syy * s * s + 2 * sxy * c * s
    stt = sxx * s * s + syy * c * c - 2 * sxy * c * s
    error = max(np.abs(arrays["srr"] - srr).max(), np.abs(arrays["stt"] - stt).max()) / scale
    return check(error < 1e-9, f"vtu cells' srr, stt against the rotated sxx, syy, sxy "
                               f"({len(cells)} cells): {error:.1e} of max |sigma_theta| (< 1e-9)")


def case(name, a, b, t_a, t_b, h, settings, polar=False):
    folder = os.path.join(out, name)
    # the polar check compares the vtu's doubles to round-off: Float64
    run(binary, prm, folder, *(["Output/Vtu precision=double"] if polar else
                               ["Output/Write vtu=false"]), *settings)
    lines = read_csv(os.path.join(folder, "lines.csv"))["radial"]
    t = max(lines)
    x, y, f = lines[t]
    r = np.hypot(np.array(x), np.array(y))
    ok = True
    T_error = np.abs(np.array(f["T"]) - cylinder_temperature(r, a, b, t_a, t_b)).max()
    ok &= check(T_error <= 0.5, f"{name}: T along radial: max error {T_error:.4f} C (<= 0.5 C)")
    sr, st = cylinder_stress(r, a=a, b=b, t_a=t_a, t_b=t_b)
    scale = np.abs(st).max()
    if polar:
        er = np.abs(np.array(f["srr"]) - sr) / scale
        et = np.abs(np.array(f["stt"]) - st) / scale
        ok &= polar_cells(folder, scale)
    else:
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
c, s = np.cos(np.radians(35)), np.sin(np.radians(35))
r0, r1 = a + 1e-4, b - 1e-4
ok &= case("other", a, b, 200.0, 50.0, h, [
    f"Mesh/Inner radius={a}", f"Mesh/Outer radius={b}", f"Mesh/Element size={h}",
    "Thermal boundary conditions/Condition 1/Temperature=200",
    "Thermal boundary conditions/Condition 2/Temperature=50",
    "Mechanics/Polar frame=true", "Mechanics/Polar centre=0, 0",
    f"Monitors/Probes=inner: {r0 * c}, {r0 * s}; outer: {r1 * c}, {r1 * s}",
    f"Monitors/Lines=radial: {r0 * c}, {r0 * s}, {r1 * c}, {r1 * s}, 121"], polar=True)
sys.exit(0 if ok else 1)
