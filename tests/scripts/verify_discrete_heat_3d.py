#!/usr/bin/env python3
"""Heat in the discrete layer in 3D and its coupling to the tetrahedra.

1. Paper 5.1 extruded (prm/plate_transient-discrete-3d.prm: a 1 x 0.25 x
   0.25 m slab of 12 000 exploded tetrahedra, faces x = 0 / 1 m at 0 / 100
   C, the rest insulated): the largest error of T at any node against the
   1D series of the 2D case at t = 2, 10, 20 s at most 0.5 C (the design
   doc's bound for 5.1 at h = 0.05 m, discrete and continuum), heat balance
   to 1e-6 (the 2D case's bound).
2. The joints conduct with k_i = beta k / h: the discrete solution differs
   from the joint-free one by O(1/beta), so the change from beta = 100 to
   1000 is 10 times the change from 1000 to 10 000 (asserted 8 to 12; 2D
   measures 9.92 and 9.99).
3. A free cube (rollers on three faces) heated 100 C above its stress-free
   temperature: the thermal stretch alone, strain alpha dT and no stress
   once the damping has taken the vibration out. Asserted: displacement
   alpha dT X to 1e-3 of alpha dT L at every node, every stress component
   below 1e-3 of E alpha dT / (1 - 2 nu), energy balance (thermal work =
   kinetic + strain + joints + damping) to 1e-3 of the thermal work.
4. The fully restrained cube (rollers on all six faces): the mean stress
   -E alpha dT / (1 - 2 nu) in all three directions, within 3 % with joint
   compliance compensation (anisotropic, the default); without it the
   joints soften the cube by more than 3 %.
5. A restrained cube heated by a uniform source Q (explicit heat, multi-
   rate: a thermal step every 100 mechanical steps): T = T0 + Q t / (rho c)
   at every node to 1e-9, the heat balance, and the energy balance as in 3
   with the thermal work put in step by step; and the run on two threads gives bitwise
   the summary of the run on one, the two threads shown to have run.

6. Quasi-static coupling (thermal steps, relaxations without a clock) of
   the restrained cube: the strain energy of the damped dynamics of 4 to
   1e-4, no relaxation at its cap.
7. Quasi-static, the restrained cube under the steady linear temperature
   0 -> 200 C across x: T linear to 1 C; the uniaxial-strain closed form
   sigma_xx = -3K alpha m, sigma_yy = sigma_zz = nu / (1 - nu) 3K alpha
   (dT - m) - 3K alpha dT (3K = E / (1 - 2 nu), m the mean rise) by layers
   of tetrahedra within 3 % for all three.

8. Checkpoints: the run of 5 stopped at 0.3 ms (checkpoints every 1000
   steps) and continued with --resume to 0.5 ms ends bitwise in the
   uninterrupted run's state (summary.json, every vtu file).
9. A fracture event in 3D: the restrained cube cooled by 100 C at once
   (tension up to E alpha 100 / (1 - 2 nu) = 59.6 MPa against a tensile
   strength of 30 MPa), quasi-static with kinetic damping and Fracture event
   duration = 0.1 ms: joints break, the velocity resets pause for a
   fracture event of at least 0.1 ms of mechanical steps, and the
   relaxations converge (none at the cap).
10. Imposed velocities in quasi-static coupling: the restrained cube heated
   100 C, its face x = L pulled with v = c t in thermal time (three thermal
   steps of 0.1 ms, each relaxation ramping the motion in): the face at
   u_x = c t^2 / 2 at every output (the step's velocity taken at its middle
   integrates a linear v exactly; to 1e-6 of the final pull, the vtu files
   hold float32); the uniaxial
   strain closed form sigma_xx = M eps - 3K alpha dT, sigma_yy = sigma_zz =
   lambda eps - 3K alpha dT (M = lambda + 2 mu) for the mean stresses, each
   within 3 % of the sum of its two terms' magnitudes (the 3 % of 3 and 4
   on each part); the reaction of the face x = 0 balances the mean
   sigma_xx over the section to 1 %; no relaxation at the cap.
11. The relaxation predictor on the run of 10: the strain energy of 10 to
   1e-3, the energy balance with the jumps' work to 1e-4 of the energy put
   in, no relaxation at the cap.

usage: verify_discrete_heat_3d.py TMFDEM OUT
"""
import csv
import json
import os
import shutil
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
from common import run, summary, check, check_parallel, SKIP  # noqa: E402
import analytic  # noqa: E402
import vtu_pieces  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
here = os.path.dirname(__file__)
plate = os.path.join(here, "..", "..", "prm", "plate_transient-discrete-3d.prm")
cube = os.path.join(here, "..", "data", "discrete", "cube_heated-3d.prm")
ok = True


outputs = vtu_pieces.read_series  # [(time, {(section, name): values})]


def reference_points(arrays):
    return (arrays[("Points", None)].reshape(-1, 3)
            - arrays[("PointData", "displacement")].reshape(-1, 3))


# 1. the extruded plate
folder = os.path.join(out, "plate")
run(binary, plate, folder)
s = summary(folder)
for t, arrays in outputs(folder):
    if t == 0:
        continue
    x = reference_points(arrays)[:, 0]
    error = np.max(np.abs(arrays[("PointData", "T")]
                          - analytic.plate_transient(x, t)))
    ok &= check(error <= 0.5, f"plate, t = {t:g} s: largest error at the "
                f"{len(x)} nodes {error:.4f} C (<= 0.5 C)")
imbalance = s["heat_balance"]["relative_imbalance"]
ok &= check(imbalance < 1e-6, f"plate: heat balance {imbalance:.3g} (< 1e-6)")

# 2. the joints' conductance: the O(1/beta) difference
# (beta = 1000 is the shipped run of 1, its output at t = 10 s)
T = {1000: next(a for t, a in outputs(os.path.join(out, "plate"))
                if t == 10.0)[("PointData", "T")]}
for beta in (100, 10000):
    folder = os.path.join(out, f"plate_beta_{beta}")
    run(binary, plate, folder, f"Discrete heat/Joint conductance factor={beta}",
        "Time stepping/End time=10", "Output/Times=10")
    T[beta] = outputs(folder)[-1][1][("PointData", "T")]
coarse = np.max(np.abs(T[100] - T[1000]))
fine = np.max(np.abs(T[1000] - T[10000]))
ok &= check(8 < coarse / fine < 12,
            f"plate, t = 10 s: beta 100 -> 1000 changes T by {coarse:.4f} C, "
            f"1000 -> 10000 by {fine:.5f} C: ratio {coarse / fine:.3f} "
            "(first order in 1/beta: 8 to 12)")

# 3. the free cube
E, nu, alpha, dT, L = 75.1e9, 0.311, 3e-6, 100.0, 0.1
sigma_restrained = -E * alpha * dT / (1 - 2 * nu)
folder = os.path.join(out, "cube_free")
run(binary, cube, folder)
s = summary(folder)
arrays = outputs(folder)[-1][1]
X = reference_points(arrays)
u = arrays[("PointData", "displacement")].reshape(-1, 3)
u_error = np.max(np.abs(u - alpha * dT * X)) / (alpha * dT * L)
stress = max(np.max(np.abs(arrays[("CellData", c)]))
             for c in ("sxx", "syy", "szz", "sxy", "syz", "sxz"))
e = s["energy"]
ok &= check(u_error < 1e-3, f"free cube: displacement alpha dT X to "
            f"{u_error:.3g} of alpha dT L (< 1e-3)")
ok &= check(stress < 1e-3 * abs(sigma_restrained),
            f"free cube: largest stress {stress:.4g} Pa (< 1e-3 of "
            f"{abs(sigma_restrained):.4g} Pa)")
ok &= check(abs(e["balance_error"]) < 1e-3 * e["thermal_work"],
            f"free cube: thermal work {e['thermal_work']:.6g} J = kinetic "
            f"{e['kinetic']:.3g} + strain {e['strain']:.3g} + joints "
            f"{e['joint_work']:.4g} + damping {e['damping']:.6g} J, error "
            f"{e['balance_error']:.3g} J (< 1e-3)")

# 4. the restrained cube, with and without compensation
restrained = ["Mechanical boundary conditions/Condition 1/Boundary ids=0, 1",
              "Mechanical boundary conditions/Condition 2/Boundary ids=2, 3",
              "Mechanical boundary conditions/Condition 3/Boundary ids=4, 5"]
means = {}
for compensation in ("true", "false"):
    folder = os.path.join(out, f"cube_restrained_{compensation}")
    run(binary, cube, folder, *restrained,
        f"Discrete mechanics/Joint compliance compensation={compensation}")
    arrays = outputs(folder)[-1][1]
    # the 24 tetrahedra of a hexahedron have equal volumes: the plain mean
    # is the volume average
    means[compensation] = [np.mean(arrays[("CellData", c)]) / sigma_restrained
                           for c in ("sxx", "syy", "szz")]
    print(f"compensation {compensation}: mean stress / (-E alpha dT / "
          f"(1 - 2 nu)) = " + ", ".join(f"{m:.4f}" for m in means[compensation])
          + f" (x, y, z; reference {sigma_restrained:.6g} Pa)", flush=True)
ok &= check(max(abs(m - 1) for m in means["false"]) > 0.03,
            "restrained cube without compensation: the joints soften it by "
            "more than 3 %")
within = max(abs(m - 1) for m in means["true"])
ok &= check(within <= 0.03,
            f"restrained cube with compensation: every direction within "
            f"{100 * within:.2f} % of -E alpha dT / (1 - 2 nu) (3 %)")

# 5. a uniform source, explicit heat; 1 and 2 threads
Q, rho_c, t_end = 8e11, 2300 * 700.0, 5e-4
source = restrained + [f"Materials/Material 0/Volumetric heat source={Q:g}",
                       "Discrete heat/Time integration=explicit",
                       "Discrete heat/Mechanical steps per thermal step=100"]
load_before = os.getloadavg()[0]
runs = {}
for threads in (1, 2):
    folder = os.path.join(out, f"cube_source_{threads}_threads")
    run(binary, cube, folder, *source, f"Discrete mechanics/Threads={threads}")
    runs[threads] = summary(folder)
    if threads == 1:
        arrays = outputs(folder)[-1][1]
s = runs[1]
T_exact = dT + Q * t_end / rho_c
T_error = np.max(np.abs(arrays[("PointData", "T")] - T_exact)) / T_exact
ok &= check(T_error < 1e-9 and s["thermal_steps"] > 20,
            f"uniform source: T = {T_exact:.6g} C at every node to "
            f"{T_error:.3g} (< 1e-9), {s['thermal_steps']} explicit thermal "
            "steps (> 20)")
hb = s["heat_balance"]
ok &= check(hb["relative_imbalance"] < 1e-6,
            f"uniform source: source heat {hb['source_heat']:.6g} J, stored "
            f"{hb['stored_heat']:.6g} J, balance {hb['relative_imbalance']:.3g} "
            "(< 1e-6)")
e = s["energy"]
ok &= check(abs(e["balance_error"]) < 1e-3 * abs(e["thermal_work"]),
            f"uniform source: energy balance error {e['balance_error']:.3g} J of "
            f"thermal work {e['thermal_work']:.6g} J (< 1e-3)")

# 6. quasi-static coupling: the restrained cube relaxes to the equilibrium
# the damped dynamics reached (3 thermal steps of 0.1 ms)
folder = os.path.join(out, "cube_restrained_quasi_static")
run(binary, cube, folder, *restrained, "Discrete heat/Coupling=quasi-static",
    "Time stepping/Time step=1e-4", "Time stepping/End time=3e-4",
    "Output/Times=3e-4", "Discrete heat/Mechanical steps per thermal step=20000")
q = summary(folder)
dynamic = summary(os.path.join(out, "cube_restrained_true"))
strain_difference = abs(q["energy"]["strain"] / dynamic["energy"]["strain"] - 1)
ok &= check(q["relaxations_at_cap"] == 0 and strain_difference < 1e-4,
            f"quasi-static restrained cube: {q['thermal_steps']} thermal steps, "
            f"none at the relaxation cap; strain energy {q['energy']['strain']:.8g} J "
            f"against the damped dynamics' {dynamic['energy']['strain']:.8g} J "
            f"({strain_difference:.2g}, < 1e-4)")

# 7. quasi-static, a steady linear temperature 0 -> 200 C across x (faces
# x = 0 and x = L held, one backward Euler step of 1e6 s), rollers on all
# six faces: the uniaxial-strain solution, sigma_xx = -3K alpha m with m
# the mean temperature rise, sigma_yy = sigma_zz = nu / (1 - nu) 3K alpha
# (dT - m) - 3K alpha dT (3K = E / (1 - 2 nu)), by layers of tetrahedra
folder = os.path.join(out, "cube_linear_quasi_static")
run(binary, cube, folder, *restrained, "Discrete heat/Coupling=quasi-static",
    "Time stepping/Time step=1e6", "Time stepping/End time=1e6",
    "Output/Times=1e6", "Discrete heat/Mechanical steps per thermal step=20000",
    "Initial conditions/Temperature=0",
    "Thermal boundary conditions/Condition 1/Boundary ids=0",
    "Thermal boundary conditions/Condition 1/Type=dirichlet",
    "Thermal boundary conditions/Condition 1/Temperature=0",
    "Thermal boundary conditions/Condition 2/Boundary ids=1",
    "Thermal boundary conditions/Condition 2/Type=dirichlet",
    "Thermal boundary conditions/Condition 2/Temperature=200")
q = summary(folder)
arrays = outputs(folder)[-1][1]
X = reference_points(arrays)
T_error = np.max(np.abs(arrays[("PointData", "T")] - 2000 * X[:, 0]))
ok &= check(T_error < 1.0 and q["relaxations_at_cap"] == 0,
            f"linear temperature: T = 2000 x to {T_error:.4f} C (< 1 C, 0.5 % of "
            "the range), the relaxation converged")
K3, m = E / (1 - 2 * nu), 100.0
centroid_x = X.reshape(-1, 4, 3).mean(axis=1)[:, 0]
worst = {"sxx": 0.0, "syy": 0.0, "szz": 0.0}
for layer in range(4):
    cells = (centroid_x >= 0.025 * layer) & (centroid_x < 0.025 * (layer + 1))
    dT_layer = 2000 * np.mean(centroid_x[cells])
    reference = {"sxx": -K3 * alpha * m,
                 "syy": nu / (1 - nu) * K3 * alpha * (dT_layer - m) - K3 * alpha * dT_layer}
    reference["szz"] = reference["syy"]
    row = []
    for c in ("sxx", "syy", "szz"):
        ratio = np.mean(arrays[("CellData", c)][cells]) / reference[c]
        worst[c] = max(worst[c], abs(ratio - 1))
        row.append(f"{c} {ratio:.4f}")
    print(f"layer {layer} (dT {dT_layer:.1f} C): " + ", ".join(row) +
          " of the closed form", flush=True)
ok &= check(max(worst.values()) <= 0.03,
            f"linear temperature: sigma_xx within {100 * worst['sxx']:.2f} %, "
            f"sigma_yy {100 * worst['syy']:.2f} %, sigma_zz "
            f"{100 * worst['szz']:.2f} % of the closed form in every layer (3 %)")

# 8. checkpoints: the run of 5 stopped at 0.3 ms with a checkpoint every
# 1000 steps, then resumed to 0.5 ms (--resume may extend End time), ends
# in the state of the uninterrupted run: every vtu file and summary.json
# (less its timings) bitwise the same
folder = os.path.join(out, "cube_source_resumed")
shutil.rmtree(folder, ignore_errors=True)  # no checkpoints of an earlier run
partial = source + ["Checkpoint/Interval (steps)=1000", "Discrete mechanics/Threads=1"]
run(binary, cube, folder, *partial, "Time stepping/End time=3e-4")
command = [binary, cube, "--resume", "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0"]
for setting in partial:
    command += ["--set", setting]
print("$", " ".join(command), flush=True)
resume = subprocess.run(command, capture_output=True, text=True)
print(resume.stderr[-1500:], flush=True)
ok &= check(resume.returncode == 0 and "resumed from" in resume.stderr,
            "--resume continued from the checkpoint")
timing = ("wall_time_s", "cpu_time_s", "cpu_time_busiest_thread_s",
          "cpu_time_other_threads_s", "element_steps_per_second", "threads",
          "threads_requested", "threads_used")
same = all(runs[1][k] == runs[2][k] for k in runs[1] if k not in timing)
ok &= check(same, "1 and 2 threads: summary.json the same bit for bit "
            "(temperatures, heat balance, energies)")
resumed = summary(folder)
same_resumed = all(resumed[k] == runs[1][k] for k in runs[1] if k not in timing)
reference_folder = os.path.join(out, "cube_source_1_threads")
vtu_files = sorted(f for f in os.listdir(reference_folder) if f.endswith(".vtu"))
for name in vtu_files:
    with open(os.path.join(reference_folder, name), "rb") as a, \
            open(os.path.join(folder, name), "rb") as b:
        same_resumed &= a.read() == b.read()
ok &= check(same_resumed and resumed["steps"] == runs[1]["steps"],
            f"stopped at 0.3 ms and resumed from the checkpoint at step 1000: "
            f"summary.json and the {len(vtu_files)} vtu files bitwise those of "
            "the uninterrupted run")
# 9. a fracture event
folder = os.path.join(out, "cube_fracture_event")
run(binary, cube, folder, *restrained, "Initial conditions/Temperature=-100",
    "Materials/Material 0/Tensile strength=3e7", "Materials/Material 0/Cohesion=6e7",
    "Materials/Material 0/Mode I fracture energy=50",
    "Materials/Material 0/Mode II fracture energy=250",
    "Discrete heat/Coupling=quasi-static", "Discrete heat/Relaxation damping=kinetic",
    "Discrete heat/Fracture event duration=1e-4", "Time stepping/Time step=1e-4",
    "Time stepping/End time=3e-4", "Output/Times=3e-4",
    "Discrete heat/Mechanical steps per thermal step=20000")
f = summary(folder)
event_steps = 1e-4 / f["time_step"]
ok &= check(f["broken_joints"] > 0 and f["fracture_events"] >= 1 and
            f["fracture_event_steps"] >= event_steps and f["relaxations_at_cap"] == 0,
            f"fracture event: {f['broken_joints']} joints broke, {f['fracture_events']} "
            f"event(s) of {f['fracture_event_steps']} mechanical steps (>= "
            f"{event_steps:.0f}: 0.1 ms), {f['velocity_resets']} velocity resets, no "
            f"relaxation at the cap; energy balance error {f['energy']['balance_error']:.4g} J "
            f"of the thermal work {f['energy']['thermal_work']:.4g} J (printed: the resets "
            f"of a state released at once)")

# 10. imposed velocities in quasi-static coupling
c_pull = 2000.0
folder = os.path.join(out, "cube_pulled_quasi_static")
pulled = ["Mechanical boundary conditions/Condition 1/Boundary ids=0",
          "Mechanical boundary conditions/Condition 2/Boundary ids=2, 3",
          "Mechanical boundary conditions/Condition 3/Boundary ids=4, 5",
          "Mechanical boundary conditions/Condition 4/Boundary ids=1",
          "Mechanical boundary conditions/Condition 4/Type=velocity",
          f"Mechanical boundary conditions/Condition 4/Velocity x={c_pull:g}*t",
          "Discrete heat/Coupling=quasi-static", "Time stepping/Time step=1e-4",
          "Time stepping/End time=3e-4", "Output/Times=1e-4, 2e-4, 3e-4",
          "Discrete heat/Mechanical steps per thermal step=20000"]
run(binary, cube, folder, *pulled)
p = summary(folder)
pull_error = 0.0
for t, arrays in outputs(folder):
    X = reference_points(arrays)
    u = arrays[("PointData", "displacement")].reshape(-1, 3)
    # the condition holds the nodes of the tetrahedra that own a face on
    # x = L (three nodes there); others touch it along an edge or at a
    # vertex and follow through their joints
    on_face = (np.abs(X[:, 0] - L) < 1e-6).reshape(-1, 4)
    face = (on_face & (on_face.sum(axis=1) == 3)[:, None]).reshape(-1)
    pull_error = max(pull_error, np.max(np.abs(u[face, 0] - 0.5 * c_pull * t * t)))
t_end = 3e-4
eps = 0.5 * c_pull * t_end ** 2 / L
# (the vtu files hold float32: 6e-8 of the pull)
ok &= check(pull_error <= 1e-6 * eps * L and p["relaxations_at_cap"] == 0,
            f"pulled cube: the face x = L at c t^2 / 2 to {pull_error:.3g} m at "
            f"every output (<= 1e-6 of the pull {eps * L:.3g} m: the vtu files hold float32); "
            f"{p['thermal_steps']} thermal steps, none at the relaxation cap")
arrays = outputs(folder)[-1][1]
lam = E * nu / ((1 + nu) * (1 - 2 * nu))
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
thermal = E * alpha * dT / (1 - 2 * nu)
for c, stiffness in (("sxx", M), ("syy", lam), ("szz", lam)):
    mean = np.mean(arrays[("CellData", c)])
    reference = stiffness * eps - thermal
    scale = stiffness * eps + thermal
    ok &= check(abs(mean - reference) <= 0.03 * scale,
                f"pulled cube: mean {c} {mean:.5g} Pa against {reference:.5g} Pa "
                f"= {stiffness / 1e9:.4g} GPa x {eps:.3g} - {thermal:.5g}: off by "
                f"{100 * abs(mean - reference) / scale:.2f} % of {scale:.5g} Pa (3 %)")
with open(os.path.join(folder, "history.csv")) as f:
    rows = list(csv.DictReader(f))
reaction = float(rows[-1]["condition1_fx"])
sxx = np.mean(arrays[("CellData", "sxx")])
ok &= check(abs(reaction + sxx * L * L) <= 0.01 * abs(sxx) * L * L,
            f"pulled cube: reaction at x = 0 {reaction:.6g} N against -mean sigma_xx "
            f"L^2 = {-sxx * L * L:.6g} N (1 %)")

# 11. the relaxation predictor (each relaxation starts from the last one's
# increment extrapolated) on the pulled cube: the same end state, the jumps'
# energy booked
folder = os.path.join(out, "cube_pulled_predictor")
run(binary, cube, folder, *pulled, "Discrete heat/Relaxation predictor=extrapolate")
q = summary(folder)
strain_difference = abs(q["energy"]["strain"] / p["energy"]["strain"] - 1)
put_in = q["energy"]["external_work"] + q["energy"]["thermal_work"] + q["energy"]["relaxation_work"]
ok &= check(q["predicted_relaxations"] > 0 and strain_difference < 1e-3 and
            abs(q["energy"]["balance_error"]) < 1e-4 * abs(put_in) and
            q["relaxations_at_cap"] == 0,
            f"relaxation predictor: {q['predicted_relaxations']} extrapolated starts, strain "
            f"energy {q['energy']['strain']:.8g} J against {p['energy']['strain']:.8g} J without "
            f"({strain_difference:.2g}, < 1e-3), energy balance {q['energy']['balance_error']:.3g} J "
            f"of {put_in:.6g} J put in (relaxation work {q['energy']['relaxation_work']:.4g} J; "
            f"< 1e-4), no relaxation at the cap")

parallel = check_parallel(runs[2], 2, load_before)
if parallel == "fail":
    ok = False
if not ok:
    sys.exit(1)
if parallel == "skip":
    sys.exit(SKIP)
print("all discrete 3D heat checks passed")
