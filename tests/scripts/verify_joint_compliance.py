#!/usr/bin/env python3
"""Joints that do not soften the body (Discrete mechanics/Joint compliance
compensation, doc/theory.md 5.4). Bounds fixed before the runs.

  verify_joint_compliance.py TMFDEM OUT sheet
      prm/sheet_restrained_expansion.prm (dT = 100 C, rollers on all edges):
      the area-weighted mean of (sxx + syy) / 2 over the triangles within
      0.1 % of -E alpha dT / (1 - nu) (plane stress) and -E alpha dT /
      (1 - 2 nu) (plane strain), with compensation, at the shipped
      h = 0.1 m, p = 1000 E and at h = 0.05 m, p = 20 E and p = 10 E (plane
      stress). Without compensation at p = 20 E the error is the joints'
      (more than 5 %): the test can fail.
  verify_joint_compliance.py TMFDEM OUT disc
      prm/thermal_shock_disc.prm at h = 1e4 W/(m^2 K), T0 = 400 C (the case
      of issue 12), before any joint is damaged: the mean over the triangles
      with an edge on the rim of their hoop stress over the analytic
      quenched-disc hoop stress at their (reference) centroid radius within
      2 % of 1; at the shipped h = 0.4 mm, p = 100 E at 30 and 60 ms
      (sigma / f_t = 0.69 and 0.92) and at h = 0.25 mm at 30 ms.
      Not asserted (measured when this test was written, doc/cases/
      thermal_shock_disc.md): at p = 20 E the ratio is 0.965 and 0.953, at
      10 E lower still -- not the joints' linear compliance, which the
      compensation removes (20 E without it: 0.913, 0.902), but the
      curvature of Munjiza's pre-peak law in tension (doc/theory.md 5.4),
      which falls like 1 / p.
"""
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts"))
from plot_vtu import read_vtu  # noqa: E402
from common import run, summary, check  # noqa: E402
import analytic  # noqa: E402

PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "prm")


def last_vtu(folder, name="solution"):
    pvd = os.path.join(folder, name + ".pvd")
    files = [(float(d.get("timestep")), os.path.join(folder, d.get("file")))
             for d in ET.parse(pvd).getroot().iter("DataSet")]
    return files


def cell_stress(vtu):
    pts, cells, sxx, _ = read_vtu(vtu, "sxx")
    _, _, syy, _ = read_vtu(vtu, "syy")
    _, _, sxy, _ = read_vtu(vtu, "sxy")
    cells = np.array(cells)
    p = pts[cells]  # (n, 3, 2)
    area = 0.5 * np.abs((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) -
                        (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    return pts, cells, area, sxx, syy, sxy


def sheet(binary, out):
    ok = True
    E, nu, alpha, dT = 75.1e9, 0.311, 3e-6, 100.0
    runs = [("plane stress", 0.1, 1000, "true"), ("plane strain", 0.1, 1000, "true"),
            ("plane stress", 0.05, 20, "true"), ("plane stress", 0.05, 10, "true"),
            ("plane stress", 0.05, 20, "false")]
    for ideal, h, p, comp in runs:
        modulus = E / (1 - nu) if ideal == "plane stress" else E / (1 - 2 * nu)
        exact = -modulus * alpha * dT
        folder = os.path.join(out, f"{ideal.replace(' ', '_')}_h{h}_p{p}_{comp}")
        run(binary, os.path.join(PRM, "sheet_restrained_expansion.prm"), folder,
            f"Mechanics/Idealisation={ideal}", f"Mesh/Element size={h}",
            f"Discrete mechanics/Joint normal penalty factor={p}",
            f"Discrete mechanics/Joint tangential penalty factor={p}",
            f"Discrete mechanics/Joint compliance compensation={comp}",
            "Output/Times=0.004", "Output/Interval=0")
        _, _, area, sxx, syy, _ = cell_stress(last_vtu(folder)[-1][1])
        mean = np.sum(area * 0.5 * (sxx + syy)) / np.sum(area)
        err = mean / exact - 1
        s = summary(folder)
        label = (f"{ideal}, h = {h} m, p = {p} E, compensation {comp}: mean sigma "
                 f"{mean / 1e6:.4f} MPa vs {exact / 1e6:.4f} MPa: {100 * err:+.4f} % "
                 f"(stable step {s['stable_time_step']:.3e} s, joints' largest share "
                 f"{100 * s['compensation_max_share']:.1f} %)")
        if comp == "true":
            ok &= check(abs(err) <= 1e-3, label + " (within 0.1 %)")
        else:
            ok &= check(err < -0.05, label + " (the joints soften it by more than 5 %)")
    return ok


def disc(binary, out):
    ok = True
    R = 6.5e-3
    E, alpha = 370e9, 7.5e-6
    kw = dict(radius=R, conductivity=35., diffusivity=35. / (3980 * 850.), h=1e4,
              t_ambient=15., t_initial=400.)
    for h_mesh, end in ((0.4e-3, 0.06), (0.25e-3, 0.03)):
        p = 100
        folder = os.path.join(out, f"h{h_mesh * 1e3:.2f}mm_p{p}")
        run(binary, os.path.join(PRM, "thermal_shock_disc.prm"), folder,
            "Initial conditions/Temperature=400",
            "Thermal boundary conditions/Condition 1/Heat transfer coefficient=1e4",
            f"Mesh/Element size={h_mesh}", f"Time stepping/End time={end}",
            "Output/Times=0.03,0.06", "Output/Interval=0")
        for t, vtu in last_vtu(folder):
            if t < 0.029:  # the output at t = 0 (and none other)
                continue
            pts, cells, area, sxx, syy, sxy = cell_stress(vtu)
            _, _, damage, _ = read_vtu(vtu, "joint_damage")
            # reference positions: the disc has shrunk by ~ alpha dT R
            _, _, u, _ = read_vtu(vtu, "displacement")
            pts = pts - u.reshape(len(pts), -1)[:, :2]
            on_rim = (np.hypot(pts[:, 0], pts[:, 1]) > R * (1 - 1e-6))[cells].sum(axis=1)
            ok &= check(summary(folder)["joint_compliance_compensation"],
                        "Joint compliance compensation on (the default)")
            rim = on_rim == 2
            c = pts[cells[rim]].mean(axis=1)
            r = np.hypot(c[:, 0], c[:, 1])
            cs, sn = c[:, 0] / r, c[:, 1] / r
            hoop = sxx[rim] * sn**2 - 2 * sxy[rim] * sn * cs + syy[rim] * cs**2
            exact = np.array([analytic.quenched_disc_hoop_stress(ri, t, E, alpha, **kw)
                              for ri in r])
            ratio = hoop / exact
            ok &= check(np.max(damage) == 0,
                        f"h = {h_mesh * 1e3} mm, p = {p} E, t = {t * 1e3:.0f} ms: no joint "
                        f"damaged yet")
            ok &= check(abs(ratio.mean() - 1) <= 0.02,
                        f"h = {h_mesh * 1e3} mm, p = {p} E, t = {t * 1e3:.0f} ms: rim "
                        f"triangles' hoop stress / analytic at their centroids, mean "
                        f"{ratio.mean():.4f} over {rim.sum()} triangles (min "
                        f"{ratio.min():.3f}, max {ratio.max():.3f}; analytic "
                        f"{exact.mean() / 1e6:.1f} MPa) (within 2 % of 1)")
    return ok


if __name__ == "__main__":
    binary, out, case = sys.argv[1:4]
    sys.exit(0 if {"sheet": sheet, "disc": disc}[case](binary, out) else 1)
