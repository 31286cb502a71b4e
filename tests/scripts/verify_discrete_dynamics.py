#!/usr/bin/env python3
"""Discrete dynamics checks.
  incline:   a block on a 30-degree incline slides with a = g (sin - mu cos)
             within 1 % (mu = 0.3); at 22, 30, 35 and 40 degrees with mu
             above tan(theta) it sticks and stays stuck (Damping ratio 1,
             the default, and 0.2; gravity ramped in).
  collision: two blocks collide and fracture: momentum and angular
             momentum conserved to round-off (joint, contact and friction
             forces are internal and torque-free), energy balance error
             below 1 %.
  threads:   the collision with 1 and 2 threads gives identical outputs,
             and the 2-thread run really ran 2 threads in parallel.
  traction:  a jointed plate on rollers pulled by a traction carries the
             applied stress uniformly; the rollers react with the load.
  brazilian: a disc between arc-seated jaws splits along the loaded
             diameter; peak load within 15 % of pi D f_t / 2.
  mass_scaling: the incline with Mass scaling factor f = 100: the stable
             step is sqrt(f) = 10 times that of f = 1 (relative 2e-4, the
             bisection's resolution twice), the block slides with
             g (sin - mu cos) / f within 1 % (the physical weight drives
             f times the inertia) and sticks for mu >= tan(theta)."""
import filecmp
import math
import os
import sys

import numpy as np

from common import run, summary, check, check_parallel, SKIP

binary, out, which = sys.argv[1], sys.argv[2], sys.argv[3]
prm_dir = os.path.join(os.path.dirname(__file__), "..", "..", "prm")
ok = True
skipped = False

if which == "incline":
    # the shipped prm: 30 degrees, Damping ratio 1 (the default), gravity
    # ramped in over its Gravity ramp time (the block is set down at rest,
    # not dropped onto its contact springs), regularised friction (the
    # defaults of Friction memory slip and Friction rate effect)
    g = 9.81
    cases = [(30.0, 0.3, None)]  # slides: a = g (sin - mu cos) within 1 %
    # sticks for mu >= tan(theta), at the default damping and at 0.2: max
    # |u_x| below 10 um (the tangential penalty's elastic slip and the slip
    # of a new contact over a few memory slips / margin), and stopped: less
    # than 0.1 um in the last 50 ms; margins 4 to 7 % above tan
    for damping in (None, 0.2):
        cases += [(22.0, 0.42, damping), (30.0, 0.6, damping),
                  (35.0, 0.73, damping), (40.0, 0.9, damping)]
    for degrees, mu, damping in cases:
        theta = math.radians(degrees)
        name = f"theta_{degrees:g}_mu_{mu}"
        extra = []
        if damping is not None:
            name += f"_damping_{damping}"
            extra = [f"Discrete mechanics/Damping ratio={damping}"]
        folder = os.path.join(out, name)
        run(binary, os.path.join(prm_dir, "block_on_incline.prm"), folder,
            f"Discrete mechanics/Friction coefficient={mu}",
            f"Discrete mechanics/Gravity={g * math.sin(theta)!r}, "
            f"{-g * math.cos(theta)!r}", *extra)
        d = np.genfromtxt(os.path.join(folder, "probes.csv"), delimiter=",",
                          names=True, dtype=None, encoding=None)
        t, ux = d["time"], d["ux"]
        label = f"{degrees:g} deg, mu = {mu}"
        if damping is not None:
            label += f", Damping ratio = {damping}"
        if mu < math.tan(theta):
            late = t >= 0.02
            a = 2.0 * np.polyfit(t[late], ux[late], 2)[0]
            exact = g * (math.sin(theta) - mu * math.cos(theta))
            error = abs(a / exact - 1.0)
            ok &= check(error < 0.01, f"{label}: a = {a:.6f} m/s^2 vs "
                        f"g (sin - mu cos) = {exact:.6f}, error {100 * error:.4f} % (< 1 %)")
        else:
            drift = np.max(np.abs(ux))
            half = t >= t[-1] - 0.05
            creep = abs(ux[-1] - ux[half][0])
            ok &= check(drift < 1e-5 and creep < 1e-7,
                        f"{label} >= tan = {math.tan(theta):.3f}: block sticks, "
                        f"max |ux| = {drift:.3e} m (< 1e-5 m), {creep:.1e} m in the "
                        "last 50 ms (< 1e-7 m)")

elif which == "mass_scaling":
    g, f = 9.81, 100.0
    steps = {}
    for degrees, mu, scaling in ((30.0, 0.3, 1.0), (30.0, 0.3, f), (30.0, 0.6, f)):
        theta = math.radians(degrees)
        folder = os.path.join(out, f"theta_{degrees:g}_mu_{mu}_f_{scaling:g}")
        # the slide with f = 1 only for its stable step: 20 ms suffice
        end = ["Time stepping/End time=0.02"] if scaling == 1.0 else []
        run(binary, os.path.join(prm_dir, "block_on_incline.prm"), folder,
            f"Discrete mechanics/Friction coefficient={mu}",
            f"Discrete mechanics/Mass scaling factor={scaling:g}",
            f"Discrete mechanics/Gravity={g * math.sin(theta)!r}, "
            f"{-g * math.cos(theta)!r}", *end)
        s = summary(folder)
        steps[(mu, scaling)] = s["stable_time_step"]
        ok &= check(s["mass_scaling_factor"] == scaling,
                    f"summary.json: mass_scaling_factor = {s['mass_scaling_factor']}")
        if scaling == 1.0:
            continue
        d = np.genfromtxt(os.path.join(folder, "probes.csv"), delimiter=",",
                          names=True, dtype=None, encoding=None)
        t, ux = d["time"], d["ux"]
        label = f"{degrees:g} deg, mu = {mu}, f = {scaling:g}"
        if mu < math.tan(theta):
            late = t >= 0.02
            a = 2.0 * np.polyfit(t[late], ux[late], 2)[0]
            exact = g * (math.sin(theta) - mu * math.cos(theta)) / scaling
            error = abs(a / exact - 1.0)
            ok &= check(error < 0.01, f"{label}: a = {a:.6e} m/s^2 vs "
                        f"g (sin - mu cos) / f = {exact:.6e}, error {100 * error:.4f} % (< 1 %)")
        else:
            drift = np.max(np.abs(ux))
            ok &= check(drift < 1e-5, f"{label} >= tan = {math.tan(theta):.3f}: block "
                        f"sticks, max |ux| = {drift:.3e} m (< 1e-5 m)")
    ratio = steps[(0.3, f)] / steps[(0.3, 1.0)]
    ok &= check(abs(ratio / math.sqrt(f) - 1.0) < 2e-4,
                f"stable step {steps[(0.3, f)]:.6e} s (f = {f:g}) / {steps[(0.3, 1.0)]:.6e} s "
                f"(f = 1) = {ratio:.6f} vs sqrt(f) = {math.sqrt(f):g} (relative 2e-4)")

elif which == "collision":
    folder = os.path.join(out, "collision")
    run(binary, os.path.join(prm_dir, "two_blocks_collision.prm"), folder)
    s = summary(folder)
    # initial momentum: both bodies 0.01 m^2 x 2500 kg/m^3 = 25 kg/m
    p0x, p0y = 25.0 * 8.0 - 25.0 * 2.0, 25.0 * 0.5
    dp = math.hypot(s["momentum_x"] - p0x, s["momentum_y"] - p0y)
    ok &= check(dp < 1e-9 * math.hypot(p0x, p0y),
                f"momentum ({s['momentum_x']:.15g}, {s['momentum_y']:.15g}) vs "
                f"({p0x}, {p0y}): change {dp:.2e} (round-off)")
    # initial angular momentum about the origin, sum of M (x_c v_y - y_c v_x):
    # body 1 centred at (0.05, 0.05) with (8, 0) m/s, body 2 at (0.155, 0.07)
    # with (-2, 0.5) m/s
    L0 = 25.0 * (0.05 * 0.0 - 0.05 * 8.0) + 25.0 * (0.155 * 0.5 - 0.07 * -2.0)
    dL = abs(s["angular_momentum"] - L0)
    ok &= check(dL < 1e-9 * abs(L0),
                f"angular momentum {s['angular_momentum']:.15g} vs {L0} kg m^2/s per m: "
                f"change {dL:.2e} (round-off)")
    ok &= check(s["broken_joints"] > 10 and s["cracks"] >= 1,
                f"the impact fractures: {s['broken_joints']} broken joints, "
                f"{s['cracks']} cracks")
    rel = s["energy"]["relative_balance_error"]
    ok &= check(rel < 0.01, f"energy balance error {100 * rel:.5f} % (< 1 %)")

elif which == "threads":
    load_before = os.getloadavg()[0]
    folders = []
    for threads in (1, 2):
        folder = os.path.join(out, f"threads_{threads}")
        run(binary, os.path.join(prm_dir, "two_blocks_collision.prm"), folder,
            f"Discrete mechanics/Threads={threads}")
        folders.append(folder)
    names = sorted(f for f in os.listdir(folders[0])
                   if f.endswith(".vtu") or f == "history.csv")
    same = all(filecmp.cmp(os.path.join(folders[0], f),
                           os.path.join(folders[1], f), shallow=False) for f in names)
    s1, s2 = summary(folders[0]), summary(folders[1])
    ok &= check(same and len(names) > 2,
                f"{len(names)} output files identical with 1 and 2 threads")
    ok &= check(s1["energy"] == s2["energy"] and s1["broken_joints"] == s2["broken_joints"],
                "summary energies and broken joints identical")
    ok &= check(s1["threads_used"] == 1, f"1-thread run: threads_used = {s1['threads_used']}")
    parallel = check_parallel(s2, 2, load_before)
    ok &= parallel != "fail"
    skipped = parallel == "skip"
elif which == "brazilian":
    import glob
    folder = os.path.join(out, "brazilian")
    run(binary, os.path.join(prm_dir, "brazilian_disc.prm"), folder)
    d = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
    # load: mean of the two jaws' reactions (cancels the disc's inertia)
    load = 0.5 * (-d["body1_fy"] + d["body2_fy"])
    peak = load.max()
    D, f_t = 0.05, 5e6
    expected = math.pi * D * f_t / 2.0  # from f_t = 2 P / (pi D t), t = 1 m
    error = abs(peak / expected - 1.0)
    ok &= check(error < 0.15, f"peak load {peak / 1e3:.1f} kN/m vs pi D f_t / 2 = "
                f"{expected / 1e3:.1f} kN/m, error {100 * error:.1f} % (< 15 %, h = 1.5 mm)")
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "scripts"))
    from plot_vtu import grid_arrays, read_grid  # noqa: E402
    points, _, _, _, _, cell_arrays = grid_arrays(
        read_grid(sorted(glob.glob(os.path.join(folder, "cracks_*.vtu")))[-1]))

    def array(name):
        return cell_arrays[name].astype(float)
    mid = 0.5 * (points[0::2] + points[1::2])
    order = np.argsort(array("break_time"))
    first = mid[order[:10]]
    mode = array("failure_mode")[order[:10]]
    ok &= check(np.all(np.abs(first[:, 0]) < 0.1 * D) and np.all(np.abs(first[:, 1]) < 0.3 * D)
                and np.all(mode == 1),
                "the first 10 joints break in Mode I near the centre, on the loaded diameter")
    on_axis = mid[np.abs(mid[:, 0]) < 0.05 * D]
    span = on_axis[:, 1].max() - on_axis[:, 1].min() if len(on_axis) else 0.0
    ok &= check(span > 0.7 * D, f"the split runs along the loaded diameter over "
                f"{span / D:.2f} D (> 0.7 D)")
elif which == "traction":
    folder = os.path.join(out, "traction")
    run(binary, os.path.join(prm_dir, "plate_traction.prm"), folder)
    d = np.genfromtxt(os.path.join(folder, "lines.csv"), delimiter=",", names=True,
                      dtype=None, encoding=None)
    last = d["time"] == d["time"].max()
    sigma0 = 1e6
    sxx, syy, sxy = d["sxx"][last], d["syy"][last], d["sxy"][last]
    ok &= check(abs(sxx.mean() / sigma0 - 1) < 0.01 and np.abs(sxx / sigma0 - 1).max() < 0.02,
                f"sxx along the midline: mean {sxx.mean() / 1e6:.5f} MPa, worst "
                f"{np.abs(sxx / sigma0 - 1).max() * 100:.2f} % off the applied 1 MPa (< 1 %, < 2 %)")
    ok &= check(np.abs(syy).max() < 0.01 * sigma0 and np.abs(sxy).max() < 0.01 * sigma0,
                f"syy, sxy below 1 % of 1 MPa (max {np.abs(syy).max():.0f}, {np.abs(sxy).max():.0f} Pa)")
    h = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
    reaction = h["condition1_fx"][-1]
    ok &= check(abs(reaction / (-sigma0 * 0.1) - 1) < 0.01,
                f"left rollers react with {reaction / 1e3:.3f} kN/m vs -100 kN/m (< 1 %)")
sys.exit(1 if not ok else SKIP if skipped else 0)
