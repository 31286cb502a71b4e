#!/usr/bin/env python3
"""Contact between tetrahedra (doc/theory.md 5.13).

1. Two weak cubes collide off-centre and obliquely, and fracture
   (prm/two_blocks_collision-3d.prm: 0.1 m cubes of 2500 kg/m^3, 8 m/s
   against (-2, 0.5, 0.3) m/s, no damping, friction 0.5). The contact
   forces are the exact gradient of an energy that rigid motions leave
   unchanged, and friction acts at one point on both sides, so:
   - the total momentum sum m v stays (15, 1.25, 0.75) kg m/s to round-off
     (1e-9 relative, the 2D bound);
   - the angular momentum about the origin, sum m x cross v, stays its
     initial value to 1e-9 relative;
   - the energy balance (kinetic + strain + joint work + contact work +
     damping = initial kinetic) closes to 1 % of the initial kinetic energy
     (central differences: an O(dt^2) error; the 2D bound);
   - the cubes touch (stored contact energy above 1e-3 of the initial
     kinetic energy at some time), friction dissipates (> 0, never
     decreasing), the contact gains no energy (its work on the nodes at the
     end, stored + dissipated, is not below minus the largest balance error
     of the run, the O(dt^2) error of the works); more sharply, its normal
     part (work less friction) is not below what the overlaps hold less
     what the faces of joints broken in compression brought in
     (summary.json contact_handed_over) by more than that error; and the
     impact fractures (broken joints > 10).
2. The same collision with unbreakable joints and no friction: the normal
   contact is conservative, so after the impact the work the nodes did on
   it equals the energy its overlaps hold (summary.json contact_stored) to
   within the largest balance error of the run.
3. Collision 1 through the impact (to 1.2 ms) on two threads gives bitwise
   the history and the outputs of the run on one thread (pair forces summed
   per tetrahedron in pair order), with the two threads shown to have run
   (common.check_parallel).

incline: a block on a fixed base under gravity tilted by theta = 30 degrees
in the plane at phi = 30 degrees from x, out of the block's symmetry planes
(prm/block_on_incline-3d.prm; gravity ramped in over 10 ms). With
mu = 0.3 < tan(theta) the centre of mass slides along the steepest descent
(g_x, g_y) / |(g_x, g_y)| at a = |(g_x, g_y)| - mu |g_z| (Coulomb's law for
a rigid block): the acceleration fitted to the displacement after 20 ms is
within 1 % of it (the 2D bound), and the sideways displacement is below
1 % of the downhill one. With mu = 0.7 >= tan(theta) the block sticks: its
centre moves less than 1e-5 m (the 2D bound).

usage: verify_discrete_contact_3d.py TMFDEM OUT [collision|incline]
"""
import csv
import filecmp
import math
import os
import sys

from common import run, summary, check, check_parallel, SKIP

binary, out = sys.argv[1], sys.argv[2]
which = sys.argv[3] if len(sys.argv) > 3 else "collision"
prm_dir = os.path.join(os.path.dirname(__file__), "..", "..", "prm")
prm = os.path.join(prm_dir, "two_blocks_collision-3d.prm")
ok = True



def incline():
    import numpy as np
    ok = True
    prm_incline = os.path.join(prm_dir, "block_on_incline-3d.prm")
    g = (4.24786, 2.45250, -8.49571)  # the prm's Gravity
    g_t = math.hypot(g[0], g[1])
    d = (g[0] / g_t, g[1] / g_t)
    for mu in (0.3, 0.7):
        folder = os.path.join(out, f"incline_mu_{mu}")
        run(binary, prm_incline, folder, f"Discrete mechanics/Friction coefficient={mu}")
        s = summary(folder)
        with open(os.path.join(folder, "history.csv")) as f:
            rows = list(csv.DictReader(f))
        t = np.array([float(r["time"]) for r in rows])
        ux = np.array([float(r["body2_ux"]) for r in rows])
        uy = np.array([float(r["body2_uy"]) for r in rows])
        down = ux * d[0] + uy * d[1]
        side = -ux * d[1] + uy * d[0]
        rel = abs(s["energy"]["balance_error"]) / max(s["energy"]["external_work"], 1e-300)
        if mu < g_t / abs(g[2]):
            late = t >= 0.02
            a = 2.0 * np.polyfit(t[late], down[late], 2)[0]
            exact = g_t - mu * abs(g[2])
            error = abs(a / exact - 1.0)
            ok &= check(error < 0.01, f"mu = {mu}: a = {a:.6e} m/s^2 along the "
                        f"steepest descent vs |g_t| - mu |g_n| = {exact:.6e}, error "
                        f"{100 * error:.4f} % (< 1 %)")
            sideways = np.max(np.abs(side))
            ok &= check(sideways < 0.01 * abs(down[-1]),
                        f"mu = {mu}: sideways {sideways:.3e} m vs downhill "
                        f"{down[-1]:.4e} m (< 1 %)")
        else:
            drift = np.max(np.hypot(ux, uy))
            ok &= check(drift < 1e-5, f"mu = {mu} >= tan = {g_t / abs(g[2]):.3f}: "
                        f"block sticks, max |u| = {drift:.3e} m (< 1e-5 m)")
        print(f"  mu = {mu}: energy balance error {s['energy']['balance_error']:.3e} J, "
              f"{100 * rel:.4f} % of the work of gravity; {s['contact_pairs']} "
              f"contact pairs, {s['steps']} steps, {s['wall_time_s']:.1f} s", flush=True)
    return ok


def collision():
    ok = True
    # initial state: both cubes 1e-3 m^3 x 2500 kg/m^3 = 2.5 kg
    M = 2.5
    v1, v2 = (8.0, 0.0, 0.0), (-2.0, 0.5, 0.3)
    c1, c2 = (0.05, 0.05, 0.05), (0.155, 0.07, 0.06)
    p0 = [M * (a + b) for a, b in zip(v1, v2)]


    def cross(a, b):
        return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0])


    L0 = [M * (a + b) for a, b in zip(cross(c1, v1), cross(c2, v2))]
    K0 = 0.5 * M * (sum(v * v for v in v1) + sum(v * v for v in v2))

    runs = {}
    load_before = os.getloadavg()[0]
    # the whole collision on two threads; 1 vs 2 threads through the impact
    # (to 1.2 ms: contact from 0.5 ms, friction, the first broken joints)
    run(binary, prm, os.path.join(out, "collision"),
        "Discrete mechanics/Threads=2")
    runs[1] = os.path.join(out, "collision")
    for threads in (1, 2):
        folder = os.path.join(out, f"impact_threads_{threads}")
        run(binary, prm, folder, f"Discrete mechanics/Threads={threads}",
            "Time stepping/End time=0.0012")
        runs[f"impact_{threads}"] = folder

    s = summary(runs[1])
    e = s["energy"]
    p = [s["momentum_x"], s["momentum_y"], s["momentum_z"]]
    dp = math.sqrt(sum((a - b) ** 2 for a, b in zip(p, p0)))
    ok &= check(dp < 1e-9 * math.sqrt(sum(a * a for a in p0)),
                f"momentum ({p[0]:.15g}, {p[1]:.15g}, {p[2]:.15g}) vs "
                f"({p0[0]}, {p0[1]}, {p0[2]}) kg m/s: change {dp:.2e} (round-off)")
    L = [s["angular_momentum_x"], s["angular_momentum_y"], s["angular_momentum_z"]]
    dL = math.sqrt(sum((a - b) ** 2 for a, b in zip(L, L0)))
    ok &= check(dL < 1e-9 * math.sqrt(sum(a * a for a in L0)),
                f"angular momentum ({L[0]:.12g}, {L[1]:.12g}, {L[2]:.12g}) vs "
                f"({L0[0]:.12g}, {L0[1]:.12g}, {L0[2]:.12g}) kg m^2/s: change "
                f"{dL:.2e} (round-off)")
    ok &= check(abs(e["initial_kinetic"] / K0 - 1.0) < 1e-12,
                f"initial kinetic energy {e['initial_kinetic']:.12g} J vs "
                f"{K0:.12g} J")
    rel = abs(e["balance_error"]) / K0
    ok &= check(rel < 0.01, f"energy balance error {e['balance_error']:.4e} J, "
                f"{100 * rel:.5f} % of the initial kinetic energy (< 1 %)")
    with open(os.path.join(runs[1], "history.csv")) as f:
        rows = list(csv.DictReader(f))
    contact_work = [float(r["contact_work"]) for r in rows]
    friction = [float(r["friction_dissipation"]) for r in rows]
    stored = [w - d for w, d in zip(contact_work, friction)]
    ok &= check(max(stored) > 1e-3 * K0,
                f"the cubes touch: largest work on the normal contact "
                f"{max(stored):.4e} J (> 1e-3 of {K0:.1f} J)")
    ok &= check(friction[-1] > 0 and all(b >= a for a, b in zip(friction, friction[1:])),
                f"friction dissipates {friction[-1]:.4e} J, never negative")
    largest_balance = max(abs(float(r["balance_error"])) for r in rows)
    ok &= check(contact_work[-1] >= -largest_balance,
                f"the contact gains no energy: its work at the end "
                f"{contact_work[-1]:.4e} J (stored {e['contact_stored']:.3e} J, "
                f"friction {friction[-1]:.4e} J) >= -{largest_balance:.3e} J, "
                f"the largest balance error of the run")
    # sharper: the normal contact's own books. Its work less friction is
    # what the overlaps hold now, less what the faces of joints broken in
    # compression brought in (the joints' work before), plus the elastic
    # energy of the friction springs (>= 0): never below that by more than
    # the O(dt^2) error of the works
    normal_work = contact_work[-1] - friction[-1]
    books = normal_work - (e["contact_stored"] - e["contact_handed_over"])
    ok &= check(books >= -largest_balance,
                f"the normal contact gains no energy: its work "
                f"{normal_work:.4e} J - (stored {e['contact_stored']:.4e} J - "
                f"handed over by broken joints {e['contact_handed_over']:.4e} J)"
                f" = {books:.3e} J >= -{largest_balance:.3e} J")
    ok &= check(s["broken_joints"] > 10,
                f"the impact fractures: {s['broken_joints']} broken joints, "
                f"{s['cracks']} cracks, {s['contact_pairs']} contact pairs, "
                f"{s['contact_searches']} searches")

    # 2. unbreakable, frictionless: the normal contact gives back what it took
    folder = os.path.join(out, "elastic_frictionless")
    strong = []
    for m in (1, 2):
        for entry in ("Tensile strength", "Cohesion", "Mode I fracture energy",
                      "Mode II fracture energy"):
            strong.append(f"Materials/Material {m}/{entry}=1e9")
    run(binary, prm, folder, *strong, "Discrete mechanics/Friction coefficient=0",
        "Time stepping/End time=0.0012")
    s_el = summary(folder)
    e_el = s_el["energy"]
    with open(os.path.join(folder, "history.csv")) as f:
        rows_el = list(csv.DictReader(f))
    largest_el = max(abs(float(r["balance_error"])) for r in rows_el)
    touched = max(float(r["contact_work"]) for r in rows_el)
    ok &= check(s_el["broken_joints"] == 0 and touched > 1e-3 * K0,
                f"elastic, frictionless: no joint broke, largest contact work "
                f"{touched:.4e} J")
    gap = abs(e_el["contact_work"] - e_el["contact_stored"])
    ok &= check(gap <= largest_el,
                f"elastic, frictionless: contact work at the end "
                f"{e_el['contact_work']:.4e} J vs the energy the overlaps hold "
                f"{e_el['contact_stored']:.4e} J: difference {gap:.3e} J <= "
                f"{largest_el:.3e} J, the largest balance error of the run")
    p_el = [s_el["momentum_x"], s_el["momentum_y"], s_el["momentum_z"]]
    dp_el = math.sqrt(sum((a - b) ** 2 for a, b in zip(p_el, p0)))
    ok &= check(dp_el < 1e-9 * math.sqrt(sum(a * a for a in p0)),
                f"elastic, frictionless: momentum change {dp_el:.2e} (round-off)")

    # 3. one vs two threads
    one, two = runs["impact_1"], runs["impact_2"]
    names = sorted(f for f in os.listdir(one)
                   if f.endswith(".vtu") or f == "history.csv")
    same = all(filecmp.cmp(os.path.join(one, f), os.path.join(two, f),
                           shallow=False) for f in names)
    s1, s2 = summary(one), summary(two)
    keys = ("momentum_x", "angular_momentum_z", "broken_joints", "contact_pairs")
    ok &= check(same and len(names) > 2 and all(s1[k] == s2[k] for k in keys)
                and s1["energy"]["friction_dissipation"] > 0,
                f"2 threads, through the impact to 1.2 ms ({s1['broken_joints']} "
                f"broken joints, friction {s1['energy']['friction_dissipation']:.3e} J): "
                f"{len(names)} outputs (history.csv, .vtu) bitwise equal to the "
                f"1-thread run's")
    parallel = check_parallel(s2, threads=2, load_before=load_before)
    ok &= parallel != "fail"
    if ok and parallel == "skip":
        sys.exit(SKIP)
    return ok


if which == "incline":
    sys.exit(0 if incline() else 1)
ok = collision()
if ok == "skip":
    sys.exit(SKIP)
sys.exit(0 if ok else 1)
