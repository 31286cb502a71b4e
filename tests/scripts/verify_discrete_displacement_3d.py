#!/usr/bin/env python3
"""Displacement conditions in the discrete layer in 3D (Mechanical boundary
conditions/Condition N/Type = displacement: every node of the faces with
its ids reaches X + u(X, t)).

1. Dynamic (tests/data/discrete/cube_pull-3d.prm, a weak cube fixed at
   x = 0 and pulled at x = L until joints break): Displacement x = t gives
   the run of Velocity x = 1 (each step's velocity (X + u(t + dt) - x) / dt,
   the last, shortened step included): every energy of summary.json within
   1e-9 relative (the balance error, their residual, within 1e-9 of the work
   put in), the same broken joints, the held face at u_x = t at the
   end to 1e-9 m (vtu float32).
2. Quasi-static (tests/data/discrete/cube_heated-3d.prm, the restrained
   cube heated 100 C with its face x = L pulled: the case 10 of
   verify_discrete_heat_3d.py): Displacement x = c t^2 / 2 in thermal time
   reaches its target at the end of each relaxation's ramp and holds it:
   the face at c t^2 / 2 at every output to 1e-6 of the pull, and the mean
   stresses of the run with Velocity x = c t within 1e-3 of their size
   (both relaxed to the tolerance), none at the relaxation cap.

usage: verify_discrete_displacement_3d.py TMFDEM OUT
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
from common import run, summary, check  # noqa: E402
import vtu_pieces  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
data = os.path.join(os.path.dirname(__file__), "..", "data", "discrete")
ok = True


def face_u(folder, L, index=-1):
    """(t, u_x of the nodes of the tetrahedra that own a face on x = L)."""
    t, arrays = vtu_pieces.read_series(folder)[index]
    u = arrays[("PointData", "displacement")].reshape(-1, 3)
    X = arrays[("Points", None)].reshape(-1, 3) - u
    on_face = (np.abs(X[:, 0] - L) < 1e-6).reshape(-1, 4)
    face = (on_face & (on_face.sum(axis=1) == 3)[:, None]).reshape(-1)
    return t, u[face, 0], arrays


# 1. dynamic
runs = {}
for kind in ("velocity", "displacement"):
    folder = os.path.join(out, f"pull_{kind}")
    run(binary, os.path.join(data, "cube_pull-3d.prm"), folder,
        f"Mechanical boundary conditions/Condition 2/Type={kind}",
        "Mechanical boundary conditions/Condition 2/Displacement x=t",
        "Output/Write vtu=true", "Output/Times=6e-4")
    runs[kind] = summary(folder)
# the energies relative to themselves; the balance error, a residual of
# them 2e4 times smaller, relative to the work put in
work = runs["velocity"]["energy"]["external_work"]
worst = max(abs(runs["displacement"]["energy"][k] - v) /
            (work if k == "balance_error" else max(abs(v), 1e-300))
            for k, v in runs["velocity"]["energy"].items() if abs(v) > 1e-12)
ok &= check(worst < 1e-9 and runs["velocity"]["broken_joints"] ==
            runs["displacement"]["broken_joints"] > 0,
            f"dynamic: Displacement x = t against Velocity x = 1: energies within "
            f"{worst:.2e} relative (< 1e-9), {runs['displacement']['broken_joints']} "
            f"broken joints in both")
t, u, _ = face_u(os.path.join(out, "pull_displacement"), 0.1)
error = np.max(np.abs(u - t))
ok &= check(error < 1e-9, f"dynamic: the held face at u_x = t = {t:g} m to {error:.2e} m "
            f"(< 1e-9 m) over {len(u)} nodes")

# 2. quasi-static
c_pull, L = 2000.0, 0.1
base = ["Mechanical boundary conditions/Condition 1/Boundary ids=0",
        "Mechanical boundary conditions/Condition 2/Boundary ids=2, 3",
        "Mechanical boundary conditions/Condition 3/Boundary ids=4, 5",
        "Mechanical boundary conditions/Condition 4/Boundary ids=1",
        "Discrete heat/Coupling=quasi-static", "Time stepping/Time step=1e-4",
        "Time stepping/End time=3e-4", "Output/Times=1e-4, 2e-4, 3e-4",
        "Discrete heat/Mechanical steps per thermal step=20000"]
pulls = {"velocity": ["Mechanical boundary conditions/Condition 4/Type=velocity",
                      f"Mechanical boundary conditions/Condition 4/Velocity x={c_pull:g}*t"],
         "displacement": ["Mechanical boundary conditions/Condition 4/Type=displacement",
                          f"Mechanical boundary conditions/Condition 4/Displacement x="
                          f"{c_pull / 2:g}*t^2"]}
for kind, settings in pulls.items():
    run(binary, os.path.join(data, "cube_heated-3d.prm"),
        os.path.join(out, f"quasi_static_{kind}"), *base, *settings)
folder = os.path.join(out, "quasi_static_displacement")
s = summary(folder)
pull = 0.5 * c_pull * 3e-4 ** 2
error = 0.0
for index in range(1, len(vtu_pieces.read_series(folder))):
    t, u, _ = face_u(folder, L, index)
    error = max(error, np.max(np.abs(u - 0.5 * c_pull * t * t)))
ok &= check(error <= 1e-6 * pull and s["relaxations_at_cap"] == 0,
            f"quasi-static: the face at c t^2 / 2 to {error:.3g} m at every output "
            f"(<= 1e-6 of the pull {pull:.3g} m), {s['relaxations_at_cap']} relaxations "
            "at the cap")
_, _, a = face_u(folder, L)
_, _, b = face_u(os.path.join(out, "quasi_static_velocity"), L)
for c in ("sxx", "syy", "szz"):
    mean_d, mean_v = np.mean(a[("CellData", c)]), np.mean(b[("CellData", c)])
    difference = abs(mean_d - mean_v) / abs(mean_v)
    ok &= check(difference < 1e-3, f"quasi-static: mean {c} {mean_d:.6g} Pa against "
                f"{mean_v:.6g} Pa of the velocity run, {difference:.2e} relative (< 1e-3)")
sys.exit(0 if ok else 1)
