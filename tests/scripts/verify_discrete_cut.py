#!/usr/bin/env python3
"""A body cut in two by broken joints (prm/cut_plate.prm, model discrete
thermo-mechanics, quasi-static), 100 C / 0 C ends, k = 10 W/(m K), 1 x 0.25 m:
  intact (no crack):        heat flow k dT W / L = 250 W/m within 1 %;
  cut, faces only touching: no heat crosses (|q| < 1e-6 of 250 W/m);
  cut, pressed together:    conducts through contact again,
                            dT W / (L/k + 1/h_c) = 227.27 W/m within 1 %;
  the heat balance closes to 1e-6 relative."""
import os
import sys

from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "cut_plate.prm")
ok = True


def outflow(folder):
    s = summary(folder)
    hb = s["heat_balance"]
    rel = hb["relative_imbalance"]
    return -hb["boundary_heat_rate_last_step"]["1"], rel


folder = os.path.join(out, "intact")
run(binary, prm, folder, "Discrete mechanics/Initial cracks=", "Output/Write vtu=false")
q, rel = outflow(folder)
ok &= check(abs(q / 250.0 - 1.0) < 0.01, f"intact plate: heat flow {q:.3f} W/m vs k dT W / L = 250 W/m")
ok &= check(rel < 1e-6, f"intact plate: heat balance {rel:.1e} (< 1e-6)")

folder = os.path.join(out, "cut_touching")
run(binary, prm, folder, "Mechanical boundary conditions/Condition 3/Traction x=0",
    "Materials/Material 0/Thermal expansion coefficient=0", "Output/Write vtu=false")
q, rel = outflow(folder)
ok &= check(abs(q) < 1e-6 * 250.0, f"cut, faces touching: heat flow across {q:.3e} W/m (< 2.5e-4)")
s = summary(folder)
ok &= check(s["broken_joints"] == 5 and s["cracks"] == 1, "the crack is 5 broken joints, one crack")
# unloaded (no load, no expansion): the relaxations end at once instead of
# running to the step cap on round-off energies (theory 8, unloaded body)
ok &= check(s["relaxations_at_cap"] == 0,
            f"cut, faces touching: relaxations at the cap {s['relaxations_at_cap']} (0: "
            f"an unloaded body is relaxed), last relaxation {s['last_relaxation_steps']} steps")

folder = os.path.join(out, "cut_pressed")
run(binary, prm, folder)
q, rel = outflow(folder)
expected = 100.0 * 0.25 / (1.0 / 10.0 + 1.0 / 100.0)
ok &= check(abs(q / expected - 1.0) < 0.01, f"cut, pressed with 1 MPa: heat flow {q:.3f} W/m vs "
            f"dT W / (L/k + 1/h_c) = {expected:.3f} W/m, error {100 * abs(q / expected - 1):.2f} %")
ok &= check(rel < 1e-6, f"pressed: heat balance {rel:.1e} (< 1e-6)")
sys.exit(0 if ok else 1)
