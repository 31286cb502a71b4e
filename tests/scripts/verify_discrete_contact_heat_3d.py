#!/usr/bin/env python3
"""Heat across contacts between tetrahedra (prm/contact_conduction-3d.prm),
the 3D counterpart of verify_discrete_contact_heat.py with the same bounds:
  steady:      two blocks pressed together (overlap 10 um) between a hot
               and a cold face carry q = dT / (L1/k1 + 1/h_c + L2/k2)
               within 1 %, with the temperature jump q / h_c at the contact
               within 1 % (linear fits of T(z) in each block away from the
               contact, extrapolated to it); the same on a finer mesh
               (h = 0.01 m instead of 0.0125) with h_c = 500 instead of 50
               (the jump 10 times smaller, the contact resistance then
               a third of the total);
  equilibrate: the same blocks, insulated, highly conducting (nearly
               isothermal), start at 100 C and 0 C: the difference of their
               mean temperatures decays as 100 C exp(-t / tau) (to 1.5 tau),
               tau = C1 C2 / ((C1 + C2) h_c A), within 2 %, the fitted
               amplitude within 1 % of 100 C (Biot number h_c L / k =
               0.005); over its first 0.05 s, explicit (forward Euler
               below the stable step, which includes the contact) and
               implicit, the heat across the contact h_c A 100 C t to 1e-3;
  thermo-mechanics: the blocks as fixed bodies, contact on, quasi-static:
               the pairs from the mechanics' search give bitwise the
               temperatures of the heat alone; the upper block free,
               starting just touching and settled under gravity (the
               weight's overlap, about 1e-10 m, conducts over the whole
               face): the steady heat flow within 1 %, no relaxation at
               the cap;
  paper literal: the isothermal blocks exchange nothing (the difference
               stays 100 C to 1e-9), as the 2D model;
  threads:     the steady run on two threads gives bitwise the summary and
               temperatures of one thread, two threads shown to have run;
  the heat balance closes to 1e-6 relative in every run."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
from common import run, summary, check, check_parallel, SKIP  # noqa: E402
import vtu_pieces  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "prm",
                                   "contact_conduction-3d.prm"))
geo = prm.replace(".prm", ".geo")
ok = True
section, delta = 0.05 * 0.05, 1e-5
k1, k2, L1, L2 = 2.0, 5.0, 0.1, 0.1 - delta
rho_c = 2500.0 * 800.0


def nodal(folder, index=-1):
    """(z, material, T) of every node at output `index`."""
    t, arrays = vtu_pieces.read_series(folder)[index]
    z = arrays[("Points", None)].reshape(-1, 3)[:, 2]
    material = np.repeat(arrays[("CellData", "material_id")], 4)
    return t, z, material, arrays[("PointData", "T")]


def steady(folder, h_c, label, *settings):
    global ok
    run(binary, prm, folder, f"Discrete heat/Contact conductance={h_c}", *settings)
    s = summary(folder)
    q = 100.0 / (L1 / k1 + 1.0 / h_c + L2 / k2)
    Q = s["heat_balance"]["boundary_heat_rate_last_step"]["1"]
    error = abs(Q / (q * section) - 1.0)
    ok &= check(error < 0.01, f"{label}: steady heat flow {Q:.5f} W vs q A = "
                f"{q * section:.5f} W, error {100 * error:.3f} % (< 1 %)")
    _, z, material, T = nodal(folder)
    below = (material == 1) & (z > 0.02) & (z < 0.09)
    above = (material == 2) & (z > 0.11) & (z < 0.18)
    contact = 0.1 - delta / 2
    T_below = np.polyval(np.polyfit(z[below], T[below], 1), contact)
    T_above = np.polyval(np.polyfit(z[above], T[above], 1), contact)
    jump, expected = T_below - T_above, q / h_c
    error = abs(jump / expected - 1.0)
    ok &= check(error < 0.01, f"{label}: temperature jump at the contact "
                f"{jump:.4f} C vs q / h_c = {expected:.4f} C, error "
                f"{100 * error:.3f} % (< 1 %)")
    rel = s["heat_balance"]["relative_imbalance"]
    ok &= check(rel < 1e-6, f"{label}: heat balance closes to {rel:.1e} (< 1e-6)")
    return s


s1 = steady(os.path.join(out, "steady"), 50.0, "steady, h_c = 50",
            "Discrete mechanics/Threads=1")
fine_geo = os.path.join(out, "contact_conduction-3d-fine.geo")
os.makedirs(out, exist_ok=True)
with open(fine_geo, "w") as f:
    f.write(f'h = 0.01;\nInclude "{geo}";\n')
steady(os.path.join(out, "steady_fine"), 500.0, "steady, h = 0.01 m, h_c = 500",
       f"Mesh/File name={fine_geo}")

# two threads: bitwise the one-thread run
folder = os.path.join(out, "steady_2_threads")
load_before = os.getloadavg()[0]
run(binary, prm, folder, "Discrete heat/Contact conductance=50",
    "Discrete mechanics/Threads=2")
s2 = summary(folder)
same = (s2["heat_balance"] == s1["heat_balance"]
        and np.array_equal(nodal(folder)[3], nodal(os.path.join(out, "steady"))[3]))
ok &= check(same, "two threads: heat balance and every nodal temperature "
            "bitwise those of one thread")
parallel = check_parallel(s2, threads=2, load_before=load_before)
ok &= parallel != "fail"


# the blocks insulated, nearly isothermal, at 100 C and 0 C at t = 0
INSULATED = ["Thermal boundary conditions/Condition 1/Boundary ids=",
             "Thermal boundary conditions/Condition 2/Boundary ids=",
             "Materials/Material 1/Thermal conductivity=1000",
             "Materials/Material 2/Thermal conductivity=1000",
             "Materials/Material 1/Initial temperature=100",
             "Materials/Material 2/Initial temperature=0"]


def equilibrate(folder, label, *settings, literal=False):
    global ok
    run(binary, prm, folder, *INSULATED,
        "Time stepping/End time=3000", "Output/Times=" +
        ", ".join(str(250 * i) for i in range(1, 13)), *settings)
    series = vtu_pieces.read_series(folder)
    times, difference = [], []
    for index in range(1, len(series)):
        t, z, material, T = nodal(folder, index)
        times.append(t)
        difference.append(T[material == 1].mean() - T[material == 2].mean())
    difference = np.array(difference)
    if literal:
        error = np.max(np.abs(difference - 100.0))
        ok &= check(error < 1e-9, f"{label}: isothermal blocks keep their "
                    f"difference 100 C to {error:.1e} C (< 1e-9 C)")
    else:
        slope, intercept = np.polyfit(times, np.log(difference), 1)
        tau_fit, amplitude = -1.0 / slope, np.exp(intercept)
        C1, C2 = rho_c * section * L1, rho_c * section * L2
        tau = C1 * C2 / ((C1 + C2) * 50.0 * section)
        error = abs(tau_fit / tau - 1.0)
        ok &= check(error < 0.02, f"{label}: equilibration time constant "
                    f"{tau_fit:.2f} s vs C1 C2 / ((C1 + C2) h_c A) = {tau:.2f} s, "
                    f"error {100 * error:.3f} % (< 2 %)")
        error = abs(amplitude / 100.0 - 1.0)
        ok &= check(error < 0.01, f"{label}: fitted amplitude {amplitude:.3f} C "
                    f"vs 100 C, error {100 * error:.3f} % (< 1 %)")
    rel = summary(folder)["heat_balance"]["relative_imbalance"]
    ok &= check(rel < 1e-6, f"{label}: heat balance closes to {rel:.1e} (< 1e-6)")


# (joint conductance factor 100: the blocks, k = 1000 W/(m K), stay nearly
# isothermal either way, and the conjugate gradients need far fewer
# iterations than with 1e4)
equilibrate(os.path.join(out, "equilibrate"), "equilibrate, implicit",
            "Discrete heat/Contact conductance=50", "Time stepping/Time step=5",
            "Discrete heat/Joint conductance factor=100")
# explicit heat: forward Euler below the stable step, which includes the
# contact (the joints, beta = 1e4, make it about 1 us), over the first
# 0.05 s of the equilibration: the heat that crossed the contact is
# h_c A 100 C t to 1e-3 (the contact nodes cool by about 4e-4 of the
# difference in that time, sqrt(t) q / effusivity); the implicit run with
# short steps gives the same
for label, settings in (("explicit", ("Discrete heat/Time integration=explicit",
                                      "Time stepping/Time step=5e-7")),
                        ("implicit", ("Time stepping/Time step=5e-4",))):
    folder = os.path.join(out, f"short_{label}")
    run(binary, prm, folder, *INSULATED, "Discrete heat/Contact conductance=50",
        "Time stepping/End time=0.05", "Output/Times=0.05", *settings)
    s = summary(folder)
    exchange, expected = s["heat_balance"]["contact_exchange"], 50.0 * section * 100.0 * 0.05
    error = abs(exchange / expected - 1.0)
    ok &= check(error < 1e-3, f"{label}, first 0.05 s: heat across the contact "
                f"{exchange:.6f} J vs h_c A 100 C t = {expected:.6f} J, error "
                f"{error:.2e} (< 1e-3); stable explicit step "
                f"{s['stable_explicit_thermal_step']:.3g} s")
    rel = s["heat_balance"]["relative_imbalance"]
    ok &= check(rel < 1e-6, f"{label}, first 0.05 s: heat balance closes to "
                f"{rel:.1e} (< 1e-6)")
equilibrate(os.path.join(out, "equilibrate_literal"), "paper literal",
            "Discrete heat/Contact conductance=50",
            "Discrete heat/Contact heat model=paper literal",
            "Time stepping/Time step=5", literal=True)
# thermo-mechanics: the same blocks as fixed bodies with contact on, quasi-
# static coupling (no thermal expansion: nothing moves); the contact heat
# takes its pairs from the mechanics' search (boxes within the buffer),
# keeps those that overlap, and gives bitwise the heat-alone temperatures
mechanics = ["Model=discrete thermo-mechanics", "Mechanics/Idealisation=3D",
             "Discrete mechanics/Contact=true",
             "Discrete heat/Coupling=quasi-static",
             "Discrete bodies/Body 1/Material ids=1", "Discrete bodies/Body 1/Motion=fixed",
             "Discrete bodies/Body 2/Material ids=2", "Discrete bodies/Body 2/Motion=fixed"]
for material in (1, 2):
    mechanics += [f"Materials/Material {material}/Young's modulus=50e9",
                  f"Materials/Material {material}/Poisson's ratio=0.25",
                  f"Materials/Material {material}/Thermal expansion coefficient=0"]
for label, extra in (("heat alone", []), ("thermo-mechanics", mechanics)):
    folder = os.path.join(out, "coupled" if extra else "alone")
    run(binary, prm, folder, "Discrete heat/Contact conductance=50",
        "Time stepping/End time=2e6", "Output/Times=2e6", *extra)
alone, coupled = (summary(os.path.join(out, f)) for f in ("alone", "coupled"))
same = (alone["heat_balance"] == coupled["heat_balance"]
        and np.array_equal(nodal(os.path.join(out, "alone"))[3],
                           nodal(os.path.join(out, "coupled"))[3]))
ok &= check(same and coupled["contact_heat_pairs"] == alone["contact_heat_pairs"] > 0,
            f"thermo-mechanics, fixed bodies in contact: {coupled['contact_heat_pairs']} "
            f"pairs exchange heat ({alone['contact_heat_pairs']} alone; the mechanics' "
            f"search holds {coupled.get('contact_pairs')}), heat balance and every "
            "nodal temperature bitwise those of the heat alone")
# thermo-mechanics with a moving contact: the upper block a free body that
# starts touching the lower, fixed one (delta = 0, h = 0.025 m) and settles
# on it under gravity, quasi-static with kinetic damping: the weight
# presses the faces together by about 1e-10 m, and any overlap conducts
# over the whole face: steady heat flow dT / (L1/k1 + 1/h_c + L2/k2) within
# 1 % (L2 = 0.1 m), every relaxation converged, heat balance 1e-6
touching_geo = os.path.join(out, "contact_conduction-3d-touching.geo")
with open(touching_geo, "w") as f:
    f.write(f'h = 0.025;\ndelta = 0;\nInclude "{geo}";\n')
folder = os.path.join(out, "settled")
run(binary, prm, folder, *[m for m in mechanics if "Body 2/Motion" not in m],
    f"Mesh/File name={touching_geo}", "Discrete heat/Contact conductance=50",
    "Discrete mechanics/Gravity=0, 0, -9.81", "Discrete heat/Relaxation damping=kinetic",
    "Time stepping/End time=3e6", "Output/Times=3e6")
s = summary(folder)
q = 100.0 / (L1 / k1 + 1.0 / 50.0 + 0.1 / k2)
Q = s["heat_balance"]["boundary_heat_rate_last_step"]["1"]
error = abs(Q / (q * section) - 1.0)
ok &= check(error < 0.01 and s["contact_heat_pairs"] > 0,
            f"free block settled under gravity: steady heat flow {Q:.5f} W vs q A = "
            f"{q * section:.5f} W, error {100 * error:.3f} % (< 1 %), "
            f"{s['contact_heat_pairs']} pairs in contact")
ok &= check(s["relaxations_at_cap"] == 0,
            f"free block settled under gravity: {s['relaxations_at_cap']} relaxations at "
            f"the cap (0), {s['steps']} mechanical steps in {s['thermal_steps']} thermal steps")
rel = s["heat_balance"]["relative_imbalance"]
ok &= check(rel < 1e-6, f"free block settled under gravity: heat balance closes to "
            f"{rel:.1e} (< 1e-6)")
if ok and parallel == "skip":
    sys.exit(SKIP)
sys.exit(0 if ok else 1)
