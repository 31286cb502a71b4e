#!/usr/bin/env python3
"""The discrete layer in 3D (tetrahedra, cohesive joints on their faces).

1. One face joint between two tetrahedra (prm/joint_pull-3d.prm, face area
   0.5 m^2) pulled apart (Mode I, along x) and slid (Mode II, along y and
   along z), Munjiza and linear softening: the work done on the joint until
   it breaks equals G times the face area within 1 % (the bound of the 2D
   joint_pull test), and the joint breaks in that mode.
2. A 0.1 m cube of tetrahedra pulled apart (face x = 0 fixed, face x = 0.1
   driven at 1 m/s along x) for 0.6 ms, joints breaking: the energy balance (external
   work = kinetic + strain + joint work + damping) closes to 1 % of the
   external work (central differences: an O(dt^2) error), momentum-free
   rigid motions aside; and the run on two threads gives bitwise the
   summary of the run on one (the chunks do not depend on the thread
   count), with the two threads shown to have run (common.check_parallel);
   and the vector batches (Vector instructions = auto) give bitwise the
   history and summary of the one-at-a-time loop (none) and of SSE2.
3. The jointed cube under uniaxial strain (rollers on the five other
   faces, one face pulled slowly along its normal, 25 wave transits; every
   boundary condition agrees with the closed form: the driven face's
   velocity condition holds its tangential motion, as the rollers do): the
   effective modulus (reaction / area) / (u / L) against the P-wave modulus
   M = lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu)), pulled along x
   and along z: within 3 % with Joint compliance compensation (anisotropic,
   the default), and more than 3 % off without it.

usage: verify_discrete_3d.py TMFDEM OUT
"""
import csv
import os
import sys

from common import run, summary, check, check_parallel, SKIP

binary, out = sys.argv[1], sys.argv[2]
prm_dir = os.path.join(os.path.dirname(__file__), "..", "..", "prm")
ok = True

# 1. joint pull
prm = os.path.join(prm_dir, "joint_pull-3d.prm")
area = 0.5
G = {"I": 1000.0, "II": 5000.0}
for law in ("Munjiza", "linear"):
    for mode, axis in (("I", "x"), ("II", "y"), ("II", "z")):
        folder = os.path.join(out, f"pull_{law}_{mode}_{axis}")
        velocity = {a: ("0.01" if a == axis else "0") for a in "xyz"}
        run(binary, prm, folder,
            f"Discrete mechanics/Softening law={law}",
            *[f"Discrete bodies/Body 2/Velocity {a}={velocity[a]}" for a in "xyz"],
            f"Time stepping/End time={'0.3' if mode == 'I' else '0.7'}")
        s = summary(folder)
        work = s["energy"]["joint_work"]
        error = abs(work / (G[mode] * area) - 1.0)
        ok &= check(s["broken_joints"] == 1 and s[f"broken_mode_{mode}"] == 1,
                    f"{law}, Mode {mode} along {axis}: the joint broke in "
                    f"Mode {mode}")
        ok &= check(error < 0.01,
                    f"{law}, Mode {mode} along {axis}: work to break "
                    f"{work:.3f} J vs G A = {G[mode] * area:.0f} J, error "
                    f"{100 * error:.4f} % (< 1 %)")

# 2. a cube pulled apart: energy balance, 1 vs 2 threads
cube_prm = os.path.join(os.path.dirname(__file__), "..", "data", "discrete",
                        "cube_pull-3d.prm")
load_before = os.getloadavg()[0]
runs = {}
for threads in (1, 2):
    folder = os.path.join(out, f"cube_{threads}_threads")
    run(binary, cube_prm, folder, f"Discrete mechanics/Threads={threads}")
    runs[threads] = summary(folder)
s = runs[1]
e = s["energy"]
ok &= check(s["elements"] > 2 * 512 and s["broken_joints"] > 0,
            f"the cube: {s['elements']} tetrahedra (more than two chunks of "
            f"512), {s['broken_joints']} joints broke")
ok &= check(abs(e["balance_error"]) < 0.01 * e["external_work"],
            f"energy balance: external work {e['external_work']:.6g} J = "
            f"kinetic {e['kinetic']:.6g} + strain {e['strain']:.6g} + joints "
            f"{e['joint_work']:.6g} + damping {e['damping']:.6g} J, error "
            f"{e['balance_error']:.3g} J "
            f"({100 * abs(e['balance_error']) / e['external_work']:.4f} %, "
            "< 1 %)")
keys = ["broken_joints", "damaged_joints", "cracks", "crack_area", "steps"]
same = all(runs[1][k] == runs[2][k] for k in keys) and \
    runs[1]["energy"] == runs[2]["energy"]
ok &= check(same, "1 and 2 threads: the same broken joints, cracks and "
            "energies, bit for bit")
# the vector batches (tetrahedral_update.cc) against the one-at-a-time loop
# (none) and the narrowest set: the same history and summary, bit for bit
# (the run above takes the set of auto)
with open(os.path.join(out, "cube_1_threads", "history.csv"), "rb") as f:
    history_auto = f.read()
for instructions in ("none", "SSE2"):
    folder = os.path.join(out, f"cube_vector_{instructions}")
    run(binary, cube_prm, folder, "Discrete mechanics/Threads=1",
        f"Discrete mechanics/Vector instructions={instructions}")
    v = summary(folder)
    with open(os.path.join(folder, "history.csv"), "rb") as f:
        history = f.read()
    ok &= check(all(v[k] == s[k] for k in keys) and v["energy"] == e
                and history == history_auto,
                f"Vector instructions = {instructions} and auto: "
                "the same broken joints, cracks, energies and history.csv, "
                "bit for bit")

# 3. the jointed cube's stiffness: uniaxial strain (the face at the lower
# end of the axis on a roller, the face at the upper end driven along the
# axis with a smooth ramp to 0.01 m/s over 1 ms, then steadily, to 4 ms:
# 25 wave transits, nothing breaks; rollers on the four lateral faces);
# M_eff = (reaction / area) / (u / L) at the end against M
ramp = "(t < 1e-3 ? 0.01 * sin(pi * t / 2e-3)^2 : 0.01)"
u_end, L, area, E, nu = 0.01 * (4e-3 - 0.5e-3), 0.1, 0.01, 1e9, 0.25
M = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
material = [
    "Mesh/Element size=0.025",
    "Materials/Material 0/Tensile strength=1e8", "Materials/Material 0/Cohesion=2e8",
    "Materials/Material 0/Mode I fracture energy=1e6",
    "Materials/Material 0/Mode II fracture energy=5e6",
    "Time stepping/End time=4e-3",
]
# boundary ids of the box: 0/1 x = 0/L, 2/3 y, 4/5 z
axes = {"x": (0, 1, [("2, 3", "y"), ("4, 5", "z")]),
        "z": (4, 5, [("0, 1", "x"), ("2, 3", "y")])}
moduli = {}
for axis, (low, high, lateral) in axes.items():
    conditions = [
        f"Mechanical boundary conditions/Condition 1/Boundary ids={low}",
        f"Mechanical boundary conditions/Condition 1/Type=roller {axis}",
        f"Mechanical boundary conditions/Condition 2/Boundary ids={high}",
        f"Mechanical boundary conditions/Condition 2/Velocity {axis}={ramp}",
    ]
    if axis != "x":  # the cube's prm drives along x
        conditions.append("Mechanical boundary conditions/Condition 2/Velocity x=0")
    for n, (ids, roller) in enumerate(lateral):
        conditions += [
            f"Mechanical boundary conditions/Condition {n + 3}/Boundary ids={ids}",
            f"Mechanical boundary conditions/Condition {n + 3}/Type=roller {roller}"]
    for compensation in ("true", "false"):
        folder = os.path.join(out, f"uniaxial_strain_{axis}_compensation_{compensation}")
        run(binary, cube_prm, folder, *material, *conditions,
            f"Discrete mechanics/Joint compliance compensation={compensation}")
        with open(os.path.join(folder, "history.csv")) as f:
            last = list(csv.DictReader(f))[-1]
        sigma = float(last[f"condition2_f{axis}"]) / area
        moduli[(axis, compensation)] = sigma / (u_end / L) / M
        su = summary(folder)
        print(f"along {axis}, compensation {compensation}: {su['elements']} "
              f"tetrahedra, reaction {float(last[f'condition2_f{axis}']):.6g} N, "
              f"M_eff = {moduli[(axis, compensation)]:.4f} M, broken "
              f"{su['broken_joints']}, damaged {su['damaged_joints']}, capped "
              f"{su['compensation_capped_elements']}, largest share "
              f"{su['compensation_largest_share']:.3f}", flush=True)
    ok &= check(abs(moduli[(axis, "true")] - 1) <= 0.03,
                f"uniaxial strain along {axis} with joint compliance "
                f"compensation: M_eff / M = {moduli[(axis, 'true')]:.4f} "
                f"(within 3 %)")
    ok &= check(abs(moduli[(axis, "false")] - 1) > 0.03,
                f"uniaxial strain along {axis} without compensation: the joints "
                f"soften the cube, M_eff / M = {moduli[(axis, 'false')]:.4f} "
                f"(more than 3 % off)")

parallel = check_parallel(runs[2], threads=2, load_before=load_before)
if parallel == "fail":
    ok = False
if not ok:
    sys.exit(1)
if parallel == "skip":
    sys.exit(SKIP)
sys.exit(0)
