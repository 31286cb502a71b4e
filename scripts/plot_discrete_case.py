#!/usr/bin/python3
"""Plot a discrete-mechanics case against its reference.

    plot_discrete_case.py CASE OUTPUT_FOLDER PNG

CASE is one of joint_pull, joint_pull-3d, block_on_incline, two_blocks_collision,
two_blocks_collision-3d, block_on_incline-3d,
brazilian_disc, plate_traction, plate_transient, plate_transient-discrete-3d,
contact_conduction, contact_conduction-3d,
sheet_free_expansion, sheet_restrained_expansion, thermal_shock_disc-3d,
sphere_drop-3d, brazilian_cylinder-3d, rock_heap-3d. OUTPUT_FOLDER holds tmfdem's outputs (history.csv,
probes.csv, summary.json, solution_*.vtu, cracks_*.vtu). Cases that compare
several runs read one sub-folder per run, the layout the verification
scripts write:

    joint_pull:        OUTPUT_FOLDER/{Munjiza,linear}_{I,II}/   (verify_discrete_joint.py)
    joint_pull-3d:     OUTPUT_FOLDER/pull_{Munjiza,linear}_{I_x,II_y,II_z}/
                       (verify_discrete_3d.py)
    block_on_incline:  OUTPUT_FOLDER/theta_<deg>_mu_<mu>[_damping_0.2]/ (verify_discrete_dynamics.py incline)
    plate_transient:   OUTPUT_FOLDER/{h0.05,continuum_P1,beta100,beta1000,beta10000}/
                       (verify_discrete_plate.py)
    plate_transient-discrete-3d: OUTPUT_FOLDER/{plate,plate_beta_{100,10000}}/
                       (verify_discrete_heat_3d.py)
    contact_conduction: OUTPUT_FOLDER/{steady,equilibrate}/  (verify_discrete_contact_heat.py)
    contact_conduction-3d: OUTPUT_FOLDER/{steady,equilibrate}/
                       (verify_discrete_contact_heat_3d.py)
    block_on_incline-3d: OUTPUT_FOLDER/incline_mu_{0.3,0.7}/
                       (verify_discrete_contact_3d.py incline)
    two_blocks_collision-3d: OUTPUT_FOLDER/collision/
                       (verify_discrete_contact_3d.py)
    sphere_drop-3d:    OUTPUT_FOLDER/drop/ (verify_discrete_sphere_drop_3d.py)
    brazilian_cylinder-3d: OUTPUT_FOLDER/cylinder/ (verify_discrete_brazilian_3d.py)
    rock_heap-3d:      OUTPUT_FOLDER/{settle,heat}/ (the two prm files; heat/ reads
                       settle/final_mesh.msh)
    thermal_shock_disc-3d: OUTPUT_FOLDER/{disc-3d,disc-2d}/
                       (verify_discrete_thermal_shock_3d.py)
    sheet_*_expansion: OUTPUT_FOLDER/free_{+100,-100}/,
                       OUTPUT_FOLDER/restrained_plane_{stress,strain}_{+100,-100}/
                       (verify_discrete_sheets.py)

A missing run is made with the binary in $TMFDEM (default
build-release/tmfdem), with the same --set overrides as those scripts.
The numbers compared are printed.
"""
import glob
import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import grid_arrays, read_grid  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BINARY = os.environ.get("TMFDEM", os.path.join(ROOT, "build-release", "tmfdem"))


# ------------------------------------------------------------------ reading
def read_csv(path):
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)


def read_summary(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def read_vtu(path):
    """Points (n x 3), connectivity per cell (list of arrays) and the
    DataArrays by name (point and cell data, connectivity, offsets, types),
    read by VTK (plot_vtu.read_grid: either Output/Vtu format)."""
    points, conn, offsets, types, point_data, cell_data = grid_arrays(read_grid(path))
    cells = [conn[s:e] for s, e in zip(offsets[:-1], offsets[1:])]
    arrays = dict(point_data, **cell_data, connectivity=conn, offsets=offsets[1:], types=types)
    return points, cells, arrays


def ensure_run(folder, prm, *settings):
    """Runs tmfdem into folder unless it already holds a summary."""
    if os.path.exists(os.path.join(folder, "summary.json")):
        return
    cmd = [BINARY, os.path.join(ROOT, "prm", prm), "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0"]
    for s in settings:
        cmd += ["--set", s]
    print("$", " ".join(f"'{c}'" if " " in c else c for c in cmd), flush=True)
    subprocess.run(cmd, check=True)


# --------------------------------------------------- joint_pull: the law
def munjiza_z(D):
    a, b, c = 0.63, 1.8, 6.0
    return (1 - (a + b - 1) / (a + b) * np.exp(D * (a + c * b) / ((a + b) * (1 - a - b)))) \
        * (a * (1 - D) + b * (1 - D) ** 6)


def cohesive_curve(f, G, k, law, n=4000):
    """Exact traction-separation curve of one pure mode: returns
    displacement, traction, work per unit area (the integral), and the
    softening width w = (G - 4 f^2 / (3 k)) / (f int z)."""
    z = munjiza_z if law == "Munjiza" else (lambda D: 1 - D)
    Ds = np.linspace(0, 1, 20001)
    zs = z(Ds)
    integral = np.sum(0.5 * (zs[1:] + zs[:-1]) * np.diff(Ds))
    op = 2 * f / k
    w = (G - 4 * f * f / (3 * k)) / (f * integral)
    d = np.linspace(0, op + w, n)
    r = np.minimum(d / op, 1)
    D = np.clip((d - op) / w, 0, 1)
    t = f * r * (2 - r) * np.where(d > op, z(D), 1)
    work = np.concatenate([[0], np.cumsum(0.5 * (t[1:] + t[:-1]) * np.diff(d))])
    return d, t, work, op, w, integral


def joint_pull_panels(png, k, area, columns, title, unit):
    """The joint-pull figure: per column (mode, f, G, run folder and prm
    settings per law, axis name) the traction from tmfdem's joint_work
    history (dW/dd / area) on the exact law, and the work against G area.
    k: the joint's penalty per unit area [Pa/m]; unit: of the work."""
    speed = 0.01
    fig, axes = plt.subplots(2, len(columns), figsize=(5.5 * len(columns), 7.5), dpi=150,
                             sharex="col", squeeze=False)
    colours = {"Munjiza": "C0", "linear": "C3"}
    print(f"{'law':>8} {'mode':>5} {'G A [' + unit + ']':>10} {'work [' + unit + ']':>12} "
          f"{'error [%]':>10} {'break at [mm]':>14} {'o_p+w [mm]':>11}")
    for col, m in enumerate(columns):
        ax_t, ax_w = axes[0, col], axes[1, col]
        GA = m["G"] * area
        for law in ("Munjiza", "linear"):
            run = m["run"](law)
            ensure_run(run, m["prm"], *m["settings"](law))
            h = read_csv(os.path.join(run, "history.csv"))
            h = h[np.unique(h["time"], return_index=True)[1]]  # the last row repeats
            s = read_summary(run)
            d = speed * h["time"]
            W = h["joint_work"]
            d_ex, t_ex, W_ex, op, w, integral = cohesive_curve(m["f"], m["G"], k, law)
            # traction from the work: dW/dd per unit area
            tm = np.gradient(W, d) / area
            broken = h["broken_joints"] > 0
            d_break = d[np.argmax(broken)] if broken.any() else float("nan")
            work = s["energy"]["joint_work"]
            err = 100 * abs(work / GA - 1)
            print(f"{law:>8} {m['mode']:>5} {GA:>10.0f} {work:>12.4f} {err:>10.4f} "
                  f"{1e3 * d_break:>14.4f} {1e3 * (op + w):>11.4f}")
            c = colours[law]
            ax_t.plot(1e3 * d_ex, 1e-6 * t_ex, "-", color=c, lw=1.2,
                      label=f"{law}: exact law (int z = {integral:.4f})")
            keep = ~broken
            ax_t.plot(1e3 * d[keep][::6], 1e-6 * tm[keep][::6], "o", color=c, ms=2.5,
                      mfc="none", label=f"{law}: tmfdem, dW/d{m.get('symbol', m['name'][-1])}")
            ax_w.plot(1e3 * d_ex, area * W_ex, "-", color=c, lw=1.2)
            ax_w.plot(1e3 * d[::6], W[::6], "o", color=c, ms=2.5, mfc="none",
                      label=f"{law}: {work:.3f} {unit} at break (error {err:.4f} %)")
        ax_w.axhline(GA, color="k", ls="--", lw=0.8, label=f"G A = {GA:.0f} {unit}")
        ax_t.set_title(f"Mode {m['mode']}{m.get('along', '')}: f = {m['f'] / 1e6:g} MPa, "
                       f"G = {m['G']:g} J/m^2, k = p / h = {k:.4g} Pa/m", fontsize=9)
        ax_t.set_ylabel("traction [MPa]")
        ax_w.set_ylabel(f"work done on the joint [{unit}]")
        ax_w.set_xlabel(f"{m['name']} [mm] (= 0.01 m/s x t)")
        for ax in (ax_t, ax_w):
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


def plot_joint_pull(folder, png):
    # prm/joint_pull.prm: E = 1e9, penalty factors 10 -> p = 1e10 Pa, joint length 1 m
    modes = {"I": dict(f=1e6, G=1000.0, v=("0.01", "0"), end="0.3", name="opening o"),
             "II": dict(f=2e6, G=5000.0, v=("0", "0.01"), end="0.7", name="slip s")}
    columns = []
    for mode, m in modes.items():
        columns.append(dict(
            m, mode=mode, prm="joint_pull.prm",
            run=lambda law, mode=mode: os.path.join(folder, f"{law}_{mode}"),
            settings=lambda law, m=m: (f"Discrete mechanics/Softening law={law}",
                                       f"Discrete bodies/Body 2/Velocity x={m['v'][0]}",
                                       f"Discrete bodies/Body 2/Velocity y={m['v'][1]}",
                                       f"Time stepping/End time={m['end']}")))
    print("joint_pull: work to break one 1 m joint")
    joint_pull_panels(png, 1e10, 1.0, columns,
                      "One joint pulled (Mode I) and sheared (Mode II): lines exact, "
                      "markers tmfdem", "J/m")


def plot_joint_pull_3d(folder, png):
    # prm/joint_pull-3d.prm: p = 10 E = 1e10 Pa over the face's mean edge
    # h = (1 + 1 + sqrt 2) / 3 m; face area 0.5 m^2
    h = (2 + math.sqrt(2)) / 3
    columns = []
    for mode, axis, f, G, end, name in (("I", "x", 1e6, 1000.0, "0.3", "opening o"),
                                        ("II", "y", 2e6, 5000.0, "0.7", "slip |s|"),
                                        ("II", "z", 2e6, 5000.0, "0.7", "slip |s|")):
        columns.append(dict(
            mode=mode, f=f, G=G, name=name, symbol=name.split()[-1], along=f" along {axis}",
            prm="joint_pull-3d.prm",
            run=lambda law, mode=mode, axis=axis: os.path.join(folder,
                                                               f"pull_{law}_{mode}_{axis}"),
            settings=lambda law, axis=axis, end=end: (
                f"Discrete mechanics/Softening law={law}",
                *[f"Discrete bodies/Body 2/Velocity {a}={'0.01' if a == axis else '0'}"
                  for a in "xyz"],
                f"Time stepping/End time={end}")))
    print("joint_pull-3d: work to break one face joint of 0.5 m^2")
    joint_pull_panels(png, 1e10 / h, 0.5, columns,
                      "One face joint between two tetrahedra pulled (Mode I) and slid "
                      "(Mode II, two directions): lines exact, markers tmfdem", "J")


# ---------------------------------------------------- block_on_incline
def plot_block_on_incline(folder, png):
    g = 9.81
    with open(os.path.join(ROOT, "prm", "block_on_incline.prm")) as f:
        ramp = float(re.search(r"Gravity ramp time\s*=\s*([0-9.eE+-]+)", f.read()).group(1))
    fig, (ax_u, ax_e) = plt.subplots(2, 1, figsize=(7, 7), dpi=150, sharex=True,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    print("block_on_incline: probe 'centre' u_x against the rigid block "
          f"(gravity ramped in over {ramp} s)")
    print(f"{'theta':>5} {'mu':>5} {'a exact':>10} {'a fit (t>=0.02)':>16} {'error [%]':>10} "
          f"{'max|ux - exact| [m]':>20}")
    sticks = [(22.0, 0.42, "C2"), (30.0, 0.6, "C3"), (35.0, 0.73, "C4"), (40.0, 0.9, "C5")]
    for degrees, mu, c in [(30.0, 0.3, "C0")] + sticks:
        theta = math.radians(degrees)
        run = os.path.join(folder, f"theta_{degrees:g}_mu_{mu}")
        ensure_run(run, "block_on_incline.prm", f"Discrete mechanics/Friction coefficient={mu}",
                   f"Discrete mechanics/Gravity={g * math.sin(theta)!r}, {-g * math.cos(theta)!r}")
        p = read_csv(os.path.join(run, "probes.csv"))
        t, ux = p["time"], p["ux"]
        a = max(0.0, g * (math.sin(theta) - mu * math.cos(theta)))
        # the rigid block under gravity growing as t / ramp: friction and
        # gravity grow together, so a(t) = a t / ramp until the ramp ends
        exact = np.where(t <= ramp, a * t ** 3 / (6 * ramp),
                         a * ramp ** 2 / 6 + a * ramp / 2 * (t - ramp) + a / 2 * (t - ramp) ** 2)
        late = t >= 0.02
        a_fit = 2 * np.polyfit(t[late], ux[late], 2)[0]
        err = 100 * abs(a_fit / a - 1) if a > 0 else float("nan")
        print(f"{degrees:>5g} {mu:>5} {a:>10.6f} {a_fit:>16.6f} {err:>10.4f} "
              f"{np.max(np.abs(ux - exact)):>20.3e}")
        if a > 0:
            ax_u.plot(t, 1e3 * exact, "-", color=c, lw=1.2,
                      label=f"{degrees:g} deg, mu = {mu}: rigid block, a = g (sin - mu cos) = {a:.4f} m/s^2")
            ax_u.plot(t, 1e3 * ux, "o", color=c, ms=3, mfc="none",
                      label=f"tmfdem (fitted a {a_fit:.4f}, {err:.4f} %)")
        else:
            ax_e.plot(t, 1e6 * ux, "o-", color=c, ms=2, lw=0.8,
                      label=f"{degrees:g} deg, mu = {mu} >= tan = {math.tan(theta):.3f}: "
                            f"max |u_x| {1e6 * np.max(np.abs(ux)):.3f} um")
    # the sticking cases again at Damping ratio 0.2
    for degrees, mu, c in sticks:
        theta = math.radians(degrees)
        run = os.path.join(folder, f"theta_{degrees:g}_mu_{mu}_damping_0.2")
        ensure_run(run, "block_on_incline.prm", f"Discrete mechanics/Friction coefficient={mu}",
                   f"Discrete mechanics/Gravity={g * math.sin(theta)!r}, {-g * math.cos(theta)!r}",
                   "Discrete mechanics/Damping ratio=0.2")
        p = read_csv(os.path.join(run, "probes.csv"))
        ax_e.plot(p["time"], 1e6 * p["ux"], "--", color=c, lw=1.0,
                  label=f"{degrees:g} deg, Damping ratio 0.2: "
                        f"max |u_x| {1e6 * np.max(np.abs(p['ux'])):.3f} um")
    ax_u.set_ylabel("u_x of the block centre [mm]")
    ax_u.set_title("Block on an incline: sliding (30 deg) and sticking cases")
    ax_u.legend(fontsize=7)
    ax_u.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_ylabel("u_x, sticking cases [micrometre]")
    ax_e.set_xlabel("t [s]")
    ax_e.legend(fontsize=7)
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


# ------------------------------------------------- two_blocks_collision
def plot_two_blocks_collision(folder, png):
    ensure_run(folder, "two_blocks_collision.prm")
    h = read_csv(os.path.join(folder, "history.csv"))
    s = read_summary(folder)
    e = s["energy"]
    t = 1e3 * h["time"]
    E0 = e["initial_kinetic"] + e["initial_strain"]
    fig, (ax_e, ax_b) = plt.subplots(2, 1, figsize=(7.5, 7.5), dpi=150, sharex=True,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    # contact_work already contains friction_dissipation: draw the penalty part
    terms = [("kinetic", h["kinetic"], "C0"),
             ("strain", h["strain"], "C1"),
             ("joint work (stored + dissipated)", h["joint_work"], "C2"),
             ("contact penalty work", h["contact_work"] - h["friction_dissipation"], "C4"),
             ("friction dissipation", h["friction_dissipation"], "C5")]
    total = sum(v for _, v, _ in terms) + h["viscous_dissipation"]
    for name, v, c in terms:
        ax_e.plot(t, v, "-", color=c, lw=1.2, label=f"{name}: {v[-1]:.3f} J/m at the end")
    ax_e.plot(t, total, "k--", lw=1.0, label=f"sum: {total[-1]:.3f} J/m")
    ax_e.axhline(E0, color="gray", lw=0.6, ls=":", label=f"initial kinetic {E0:.3f} J/m")
    ax_e.set_ylabel("energy [J/m]")
    p0x, p0y = 25.0 * 8.0 - 25.0 * 2.0, 25.0 * 0.5
    dp = math.hypot(s["momentum_x"] - p0x, s["momentum_y"] - p0y)
    ax_e.set_title("Two blocks colliding (8 m/s and -2 m/s): energy terms\n"
                   f"momentum ({s['momentum_x']:.12g}, {s['momentum_y']:.12g}) kg m/s/m vs "
                   f"({p0x:g}, {p0y:g}): change {dp:.1e}", fontsize=9)
    ax_e.legend(fontsize=7, loc="center right")
    ax_e.set_ylim(-20, 1.08 * E0)
    ax_e.grid(alpha=0.3)
    rel = h["balance_error"] / E0
    ax_b.plot(t, 100 * rel, "-", color="k", lw=1.0)
    ax_b.axhline(0, color="gray", lw=0.5)
    ax_b.set_ylabel("balance error / initial kinetic [%]")
    ax_b.set_xlabel("t [ms]")
    ax_b.set_title(f"balance error at the end {100 * e['relative_balance_error']:.5f} % "
                   f"({s['broken_joints']} broken joints, {s['cracks']} cracks)", fontsize=9)
    ax_b.grid(alpha=0.3)
    ax2 = ax_b.twinx()
    ax2.plot(t, h["broken_joints"], "-", color="C3", lw=0.8)
    ax2.set_ylabel("broken joints", color="C3")
    fig.tight_layout()
    fig.savefig(png)
    print("two_blocks_collision: energies at the end [J/m]")
    for k in ("initial_kinetic", "kinetic", "strain", "joint_work", "contact_work",
              "friction_dissipation", "viscous_dissipation", "balance_error",
              "relative_balance_error"):
        print(f"  {k:>24}: {e[k]:.6g}")
    print(f"  momentum change: {dp:.3e} kg m/s per m; max |balance error| / E0 over the "
          f"run: {np.max(np.abs(rel)):.3e}")
    print(f"wrote {png}")


# ---------------------------------------------- two_blocks_collision-3d
def plot_two_blocks_collision_3d(folder, png):
    """Reads OUTPUT_FOLDER/collision (verify_discrete_contact_3d.py)."""
    folder = os.path.join(folder, "collision")
    ensure_run(folder, "two_blocks_collision-3d.prm")
    h = read_csv(os.path.join(folder, "history.csv"))
    s = read_summary(folder)
    e = s["energy"]
    t = 1e3 * h["time"]
    E0 = e["initial_kinetic"]
    fig, (ax_e, ax_b) = plt.subplots(2, 1, figsize=(7.5, 7.5), dpi=150, sharex=True,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    # contact_work already contains friction_dissipation: draw the penalty part
    terms = [("kinetic", h["kinetic"], "C0"),
             ("strain", h["strain"], "C1"),
             ("joint work (stored + dissipated)", h["joint_work"], "C2"),
             ("contact penalty work", h["contact_work"] - h["friction_dissipation"], "C4"),
             ("friction dissipation", h["friction_dissipation"], "C5")]
    total = sum(v for _, v, _ in terms) + h["damping"]
    for name, v, c in terms:
        ax_e.plot(t, v, "-", color=c, lw=1.2, label=f"{name}: {v[-1]:.4f} J at the end")
    ax_e.plot(t, total, "k--", lw=1.0, label=f"sum: {total[-1]:.4f} J")
    ax_e.axhline(E0, color="gray", lw=0.6, ls=":", label=f"initial kinetic {E0:.4f} J")
    ax_e.set_ylabel("energy [J]")
    p0 = (2.5 * (8.0 - 2.0), 2.5 * 0.5, 2.5 * 0.3)
    p = (s["momentum_x"], s["momentum_y"], s["momentum_z"])
    dp = math.sqrt(sum((a - b) ** 2 for a, b in zip(p, p0)))
    ax_e.set_title("Two cubes colliding off-centre (8 m/s and (-2, 0.5, 0.3) m/s): "
                   "energy terms\n"
                   f"momentum ({p[0]:.12g}, {p[1]:.12g}, {p[2]:.12g}) kg m/s vs "
                   f"({p0[0]:g}, {p0[1]:g}, {p0[2]:g}): change {dp:.1e}", fontsize=9)
    ax_e.legend(fontsize=7, loc="center right")
    ax_e.set_ylim(-0.05 * E0, 1.08 * E0)
    ax_e.grid(alpha=0.3)
    rel = h["balance_error"] / E0
    ax_b.plot(t, 100 * rel, "-", color="k", lw=1.0)
    ax_b.axhline(0, color="gray", lw=0.5)
    ax_b.set_ylabel("balance error / initial kinetic [%]")
    ax_b.set_xlabel("t [ms]")
    ax_b.set_title(f"balance error at the end {100 * e['balance_error'] / E0:.5f} % "
                   f"({s['broken_joints']} broken joints, {s['cracks']} cracks)", fontsize=9)
    ax_b.grid(alpha=0.3)
    ax2 = ax_b.twinx()
    ax2.plot(t, h["broken_joints"], "-", color="C3", lw=0.8)
    ax2.set_ylabel("broken joints", color="C3")
    fig.tight_layout()
    fig.savefig(png)
    print("two_blocks_collision-3d: energies at the end [J]")
    for k in ("initial_kinetic", "kinetic", "strain", "joint_work", "contact_work",
              "contact_penalty", "friction_dissipation", "damping", "balance_error"):
        print(f"  {k:>24}: {e[k]:.6g}")
    print(f"  momentum change: {dp:.3e} kg m/s; max |balance error| / E0 over the "
          f"run: {np.max(np.abs(rel)):.3e}")
    print(f"wrote {png}")


# ---------------------------------------------------- block_on_incline-3d
def plot_block_on_incline_3d(folder, png):
    """Reads OUTPUT_FOLDER/incline_mu_{0.3,0.7} (verify_discrete_contact_3d.py
    incline)."""
    with open(os.path.join(ROOT, "prm", "block_on_incline-3d.prm")) as f:
        text = f.read()
    ramp = float(re.search(r"Gravity ramp time\s*=\s*([0-9.eE+-]+)", text).group(1))
    g = [float(v) for v in re.search(r"set Gravity\s*=\s*([^\n]+)", text).group(1).split(",")]
    g_t, g_n = math.hypot(g[0], g[1]), abs(g[2])
    d = (g[0] / g_t, g[1] / g_t)
    fig, (ax_u, ax_s) = plt.subplots(2, 1, figsize=(7, 7), dpi=150, sharex=True,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    # mu = 0.3 slides: the rigid block under the ramp a(t) = a0 min(t / T, 1)
    mu = 0.3
    sub = os.path.join(folder, f"incline_mu_{mu}")
    ensure_run(sub, "block_on_incline-3d.prm", f"Discrete mechanics/Friction coefficient={mu}")
    h = read_csv(os.path.join(sub, "history.csv"))
    t = h["time"]
    down = h["body2_ux"] * d[0] + h["body2_uy"] * d[1]
    side = -h["body2_ux"] * d[1] + h["body2_uy"] * d[0]
    a0 = g_t - mu * g_n
    tt = np.linspace(0, t[-1], 400)
    exact = np.where(tt <= ramp, a0 * tt ** 3 / (6 * ramp),
                     a0 * ramp ** 2 / 6 + a0 * ramp / 2 * (tt - ramp)
                     + a0 / 2 * (tt - ramp) ** 2)
    late = t >= 0.02
    a_fit = 2.0 * np.polyfit(t[late], down[late], 2)[0]
    ax_u.plot(1e3 * tt, 1e3 * exact, "-", color="gray", lw=2.5, alpha=0.6,
              label=f"rigid block, a = |g_t| - mu |g_n| = {a0:.4f} m/s^2")
    ax_u.plot(1e3 * t, 1e3 * down, "C0.", ms=2.5,
              label=f"tmfdem, mu = {mu}: fitted a = {a_fit:.4f} m/s^2 "
                    f"({100 * abs(a_fit / a0 - 1):.4f} %)")
    ax_u.plot(1e3 * t, 1e3 * side, "C1-", lw=1, label="tmfdem, sideways")
    ax_u.set_ylabel("centre of mass along the steepest descent [mm]")
    ax_u.set_title(f"Block on a base under gravity tilted 30 deg at 30 deg from x "
                   f"(ramped over {1e3 * ramp:g} ms)", fontsize=9)
    ax_u.legend(fontsize=7)
    ax_u.grid(alpha=0.3)
    mu = 0.7
    sub = os.path.join(folder, f"incline_mu_{mu}")
    ensure_run(sub, "block_on_incline-3d.prm", f"Discrete mechanics/Friction coefficient={mu}")
    h = read_csv(os.path.join(sub, "history.csv"))
    u = np.hypot(h["body2_ux"], h["body2_uy"])
    ax_s.plot(1e3 * h["time"], 1e6 * u, "C3-", lw=1,
              label=f"tmfdem, mu = {mu} >= tan = {g_t / g_n:.3f}: sticks")
    ax_s.axhline(10, color="gray", ls=":", lw=1, label="test bound 10 um")
    ax_s.set_ylabel("|tangential displacement| [um]")
    ax_s.set_xlabel("t [ms]")
    ax_s.legend(fontsize=7)
    ax_s.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"block_on_incline-3d: a fit {a_fit:.6f} vs {a0:.6f} m/s^2; "
          f"sideways max {np.max(np.abs(side)):.3e} m; stick max {np.max(u):.3e} m")
    print(f"wrote {png}")


def plot_sphere_drop_3d(folder, png):
    """Reads OUTPUT_FOLDER/drop (verify_discrete_sphere_drop_3d.py)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
    from verify_discrete_sphere_drop_3d import R, E, nu, rho, v, gap
    sub = os.path.join(folder, "drop")
    ensure_run(sub, "sphere_drop-3d.prm")
    h = read_csv(os.path.join(sub, "history.csv"))
    t, F = h["time"], 4.0 * np.abs(h["body2_fz"])
    # Hertz: m delta'' = -4/3 E* sqrt(R) delta^(3/2), delta(0) = 0,
    # delta'(0) = v (RK4 until the sphere leaves the plate)
    m = 4.0 / 3.0 * math.pi * R ** 3 * rho
    K = 4.0 / 3.0 * E / (1.0 - nu * nu) * math.sqrt(R)
    acc = lambda d: -K / m * max(d, 0.0) ** 1.5  # noqa: E731
    dt, d, w, th, Fh = 1e-8, 0.0, v, [0.0], [0.0]
    while True:
        k1, l1 = w, acc(d)
        k2, l2 = w + 0.5 * dt * l1, acc(d + 0.5 * dt * k1)
        k3, l3 = w + 0.5 * dt * l2, acc(d + 0.5 * dt * k2)
        k4, l4 = w + dt * l3, acc(d + dt * k3)
        d += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        w += dt / 6.0 * (l1 + 2 * l2 + 2 * l3 + l4)
        if d <= 0.0:
            break
        th.append(th[-1] + dt)
        Fh.append(K * d ** 1.5)
    th.append(th[-1] + dt)
    Fh.append(0.0)
    th = np.array(th) + gap / v
    on = np.nonzero(F > 1e-6 * max(Fh))[0]
    duration = t[on[-1]] - t[on[0]]
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=150)
    ax.plot(1e6 * th, 1e-3 * np.array(Fh), "-", color="gray", lw=2.5, alpha=0.6,
            label=f"Hertz: t_c = {1e6 * (th[-1] - th[0]):.1f} us, "
                  f"F_max = {1e-3 * max(Fh):.0f} kN")
    ax.plot(1e6 * t, 1e-3 * F, "C0-", lw=1,
            label=f"tmfdem (4 x the quarter's reaction): contact "
                  f"{1e6 * duration:.1f} us, peak {1e-3 * F.max():.0f} kN")
    ax.set_xlabel("t [us]")
    ax.set_ylabel("contact force on the plate [kN]")
    ax.set_title(f"Sphere (R = {R} m, E = {E:g} Pa, nu = {nu}) dropped on a fixed "
                 f"plate at {v:g} m/s", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"sphere_drop-3d: contact {duration:.6e} s vs Hertz "
          f"{th[-1] - th[0]:.6e} s; peak {F.max():.6e} N vs {max(Fh):.6e} N")
    print(f"wrote {png}")


# ------------------------------------------------------- brazilian_disc
def plot_brazilian_disc(folder, png, magnify=1.0):
    ensure_run(folder, "brazilian_disc.prm")
    D, f_t, alpha = 0.05, 5e6, math.radians(7.5)
    P0 = math.pi * D * f_t / 2
    h = read_csv(os.path.join(folder, "history.csv"))
    load = 0.5 * (-h["body1_fy"] + h["body2_fy"])
    t = 1e3 * h["time"]
    i = int(np.argmax(load))
    peak = load[i]
    hondros = (math.sin(2 * alpha) - alpha) / math.sin(alpha)
    fig, (ax_p, ax_c) = plt.subplots(1, 2, figsize=(12, 5.6), dpi=150,
                                     gridspec_kw=dict(width_ratios=[1.1, 1]))
    ax_p.plot(t, 1e-3 * load, "-", color="C0", lw=1.2,
              label="tmfdem: (-P_top,y + P_bottom,y) / 2")
    ax_p.axhline(1e-3 * P0, color="k", ls="--", lw=0.8,
                 label=f"pi D f_t / 2 = {1e-3 * P0:.1f} kN/m")
    ax_p.axhline(1e-3 * P0 / hondros, color="gray", ls=":", lw=0.8,
                 label=f"with Hondros' arc factor {hondros:.4f}: {1e-3 * P0 / hondros:.1f} kN/m")
    ax_p.plot(t[i], 1e-3 * peak, "o", color="C3",
              label=f"peak {1e-3 * peak:.1f} kN/m at {t[i]:.3f} ms "
                    f"({100 * (peak / P0 - 1):+.1f} %)")
    ax2 = ax_p.twinx()
    ax2.plot(t, h["broken_joints"], "-", color="C2", lw=0.8)
    ax2.set_ylabel("broken joints", color="C2")
    ax_p.set_xlabel("t [ms]")
    ax_p.set_ylabel("load P per unit thickness [kN/m]")
    ax_p.set_title("Brazilian disc, D = 50 mm, f_t = 5 MPa, G_I = 5 J/m^2", fontsize=10)
    ax_p.legend(fontsize=7, loc="upper left")
    ax_p.grid(alpha=0.3)

    sol = sorted(glob.glob(os.path.join(folder, "solution_*.vtu")))[-1]
    crk = sorted(glob.glob(os.path.join(folder, "cracks_*.vtu")))[-1]
    pts, cells, arr = read_vtu(sol)
    u = arr["displacement"].reshape(-1, 3)
    X = pts[:, :2] + (magnify - 1) * u[:, :2]
    tri = np.array([c for c in cells]).reshape(-1, 3)
    mat = arr["material_id"].astype(int)
    segs = [X[[a, b, c, a]] for a, b, c in tri]
    colours = ["0.75" if m == 1 else "0.45" for m in mat]
    ax_c.add_collection(LineCollection(segs, colors=colours, linewidths=0.3))
    # cracks: midpoints of the joint faces; move them like the mesh
    cp, ccells, carr = read_vtu(crk)
    mode = carr.get("failure_mode", np.zeros(0)).astype(int)
    # displacement of a crack point: that of the nearest node
    names = {1: ("Mode I", "C3"), 2: ("Mode II", "C0"), 3: ("mixed", "C2")}
    counts = {}
    if len(mode):
        from numpy.linalg import norm  # noqa: F401
        ref = pts[:, :2]
        for m_id, (name, c) in names.items():
            sel = np.where(mode == m_id)[0]
            counts[name] = len(sel)
            if not len(sel):
                continue
            lines = []
            for k in sel:
                ends = cp[ccells[k], :2]
                moved = []
                for q in ends:
                    n = np.argmin(np.sum((ref - q) ** 2, axis=1))
                    moved.append(q + (magnify - 1) * u[n, :2])
                lines.append(moved)
            ax_c.add_collection(LineCollection(lines, colors=c, linewidths=1.6,
                                               label=f"{name}: {len(sel)} joints"))
    ax_c.set_aspect("equal")
    ax_c.autoscale()
    ax_c.set_xlim(-0.032, 0.032)
    ax_c.set_xlabel("x [m]")
    ax_c.set_ylabel("y [m]")
    t_end = h["time"][-1]
    ax_c.set_title(f"broken joints at t = {1e3 * t_end:.1f} ms by failure mode "
                   + ("(deformed, true scale)" if magnify == 1 else f"(displacement x {magnify:g})"), fontsize=10)
    ax_c.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(png)
    print("brazilian_disc:")
    print(f"  peak load {peak:.1f} N/m at t = {1e3 * h['time'][i]:.4f} ms; "
          f"pi D f_t / 2 = {P0:.1f} N/m; ratio {peak / P0:.4f} (error {100 * abs(peak / P0 - 1):.2f} %)")
    print(f"  f_t from the peak, 2 P / (pi D t) = {2 * peak / (math.pi * D) / 1e6:.3f} MPa; "
          f"Hondros factor (sin 2a - a) / sin a = {hondros:.4f} at 2a = 15 degrees")
    print(f"  broken joints at the end by mode: {counts}")
    print(f"wrote {png}")


def plot_brazilian_cylinder_3d(folder, png):
    """Reads OUTPUT_FOLDER/cylinder (verify_discrete_brazilian_3d.py)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
    from verify_discrete_brazilian_3d import D, t, alpha, reference_load, load_history, \
        broken_faces, on_loaded_plane
    sub = os.path.join(folder, "cylinder")
    ensure_run(sub, "brazilian_cylinder-3d.prm")
    time, load = load_history(sub)
    time, load = 1e3 * np.array(time), np.array(load)
    h = read_csv(os.path.join(sub, "history.csv"))
    P0 = reference_load()
    hondros = (math.sin(2 * alpha) - alpha) / math.sin(alpha)
    i = int(np.argmax(load))
    centroid, normal, area, _, mode = broken_faces(sub)
    fig, (ax_p, ax_t, ax_s) = plt.subplots(
        1, 3, figsize=(15, 5), dpi=150, gridspec_kw=dict(width_ratios=[1.2, 1, 0.55]))
    ax_p.plot(time, 1e-3 * load, "-", color="C0", lw=1.2,
              label="tmfdem: 2 x (-P_top,y + P_bottom,y) / 2 (half the thickness modelled)")
    ax_p.axhline(1e-3 * P0, color="k", ls="--", lw=0.8,
                 label=f"pi D t f_t / 2 = {1e-3 * P0:.3f} kN")
    ax_p.axhline(1e-3 * P0 / hondros, color="gray", ls=":", lw=0.8,
                 label=f"with Hondros' arc factor {hondros:.4f}: {1e-3 * P0 / hondros:.3f} kN")
    ax_p.plot(time[i], 1e-3 * load[i], "o", color="C3",
              label=f"peak {1e-3 * load[i]:.3f} kN at {time[i]:.3f} ms "
                    f"({100 * (load[i] / P0 - 1):+.1f} %)")
    ax2 = ax_p.twinx()
    ax2.plot(time, h["broken_joints"], "-", color="C2", lw=0.8)
    ax2.set_ylabel("broken joints", color="C2")
    ax_p.set_xlabel("t [ms]")
    ax_p.set_ylabel("load P [kN]")
    ax_p.set_title(f"Brazilian cylinder, D = {1e3 * D:g} mm, t = {1e3 * t:g} mm, "
                   "f_t = 5 MPa, G_I = 5 J/m^2", fontsize=10)
    ax_p.legend(fontsize=7, loc="upper left")
    ax_p.grid(alpha=0.3)
    names = {1: ("Mode I", "C3"), 2: ("Mode II", "C0"), 3: ("mixed", "C2")}
    # (b) along the axis: every broken face's centroid; (c) the loaded plane
    # x = 0 seen from +x: its broken faces' centroids
    on_plane = on_loaded_plane(centroid, normal)
    fraction = area[on_plane].sum() / (D * t / 2)
    for m_id, (name, c) in names.items():
        sel = mode == m_id
        if sel.any():
            ax_t.plot(1e3 * centroid[sel, 0], 1e3 * centroid[sel, 1], ".", color=c, ms=3,
                      label=f"{name}: {sel.sum()} faces")
        sel &= on_plane
        if sel.any():
            ax_s.plot(1e3 * centroid[sel, 2], 1e3 * centroid[sel, 1], ".", color=c, ms=4)
    phi = np.linspace(0, 2 * math.pi, 200)
    ax_t.plot(1e3 * D / 2 * np.cos(phi), 1e3 * D / 2 * np.sin(phi), "k-", lw=0.6)
    ax_t.set_aspect("equal")
    ax_t.set_xlabel("x [mm]")
    ax_t.set_ylabel("y [mm]")
    ax_t.set_title(f"broken faces at {time[-1]:.2f} ms (centroids, seen along the axis)",
                   fontsize=9)
    ax_t.legend(fontsize=7, loc="lower right")
    ax_s.add_patch(plt.Rectangle((0, -1e3 * D / 2), 1e3 * t / 2, 1e3 * D, fill=False, lw=0.6))
    ax_s.set_xlim(-1, 1e3 * t / 2 + 1)
    ax_s.set_aspect("equal")
    ax_s.set_xlabel("z [mm] (0: mid plane)")
    ax_s.set_ylabel("y [mm]")
    ax_s.set_title(f"the loaded plane x = 0:\n{100 * fraction:.0f} % of it broken", fontsize=9)
    fig.tight_layout()
    fig.savefig(png)
    print(f"brazilian_cylinder-3d: peak {load[i]:.1f} N at {time[i]:.4f} ms; "
          f"pi D t f_t / 2 = {P0:.1f} N; error {100 * (load[i] / P0 - 1):+.2f} %; "
          f"Hondros factor {hondros:.4f}")
    print(f"  broken faces {len(area)}, on the loaded plane {on_plane.sum()} "
          f"({100 * fraction:.1f} % of its area); end load {load[-1]:.1f} N")
    print(f"wrote {png}")


# ------------------------------------------------------- plate_traction
def plot_plate_traction(folder, png):
    """OUTPUT_FOLDER is the run itself (verify_discrete_dynamics.py traction
    writes it to OUT/traction)."""
    ensure_run(folder, "plate_traction.prm")
    sigma0, height = 1e6, 0.1
    d = read_csv(os.path.join(folder, "lines.csv"))
    last = d["time"] == d["time"].max()
    x, sxx, syy, sxy = d["x"][last], d["sxx"][last], d["syy"][last], d["sxy"][last]
    h = read_csv(os.path.join(folder, "history.csv"))
    h = h[np.unique(h["time"], return_index=True)[1]]
    t = h["time"]
    ramp = np.where(t < 1e-3, 0.5 * (1 - np.cos(np.pi * t / 1e-3)), 1.0)
    fig, (ax_s, ax_r) = plt.subplots(1, 2, figsize=(12, 4.8), dpi=150)
    ax_s.axhline(sigma0 / 1e6, color="k", ls="--", lw=0.8, label="applied traction 1 MPa")
    ax_s.plot(x, sxx / 1e6, "o-", color="C0", ms=3.5, lw=0.8,
              label=f"tmfdem sxx: mean {sxx.mean() / 1e6:.5f} MPa, worst "
                    f"{100 * np.abs(sxx / sigma0 - 1).max():.2f} % off")
    ax_s.plot(x, syy / 1e6, "s-", color="C1", ms=3, lw=0.8, mfc="none",
              label=f"syy (max |syy| {np.abs(syy).max():.0f} Pa)")
    ax_s.plot(x, sxy / 1e6, "^-", color="C2", ms=3, lw=0.8, mfc="none",
              label=f"sxy (max |sxy| {np.abs(sxy).max():.0f} Pa)")
    ax_s.set_xlabel("x along 'midline' (y = 0.05 m) [m]")
    ax_s.set_ylabel("stress [MPa]")
    ax_s.set_ylim(-0.1, 1.1)
    ax_s.set_title(f"stress along the midline at t = {1e3 * d['time'].max():.1f} ms", fontsize=10)
    ax_s.legend(fontsize=7, loc="center right")
    ax_s.grid(alpha=0.3)
    R = h["condition1_fx"]
    ax_r.plot(1e3 * t, -sigma0 * height * ramp / 1e3, "k--", lw=0.8,
              label="- traction(t) x 0.1 m (the static reaction)")
    ax_r.axhline(-sigma0 * height / 1e3, color="gray", ls=":", lw=0.8, label="-100 kN/m")
    ax_r.plot(1e3 * t, R / 1e3, "-", color="C3", lw=1.0,
              label=f"tmfdem condition1_fx (left rollers): {R[-1] / 1e3:.3f} kN/m at the end")
    ax_r.set_xlabel("t [ms]")
    ax_r.set_ylabel("reaction [kN/m]")
    ax_r.set_title("reaction of the left rollers", fontsize=10)
    ax_r.legend(fontsize=7, loc="upper right")
    ax_r.grid(alpha=0.3)
    fig.suptitle("Jointed plate 0.2 x 0.1 m on rollers pulled by 1 MPa (ramped over 1 ms)",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print("plate_traction: along 'midline' at the last output")
    print(f"  sxx mean {sxx.mean():.1f} Pa, min {sxx.min():.1f}, max {sxx.max():.1f}, worst "
          f"{100 * np.abs(sxx / sigma0 - 1).max():.3f} % off 1 MPa; max |syy| "
          f"{np.abs(syy).max():.0f} Pa, max |sxy| {np.abs(sxy).max():.0f} Pa")
    print(f"  left-roller reaction at t = {1e3 * t[-1]:.3f} ms: {R[-1]:.1f} N/m vs -100000 N/m "
          f"({100 * (R[-1] / (-sigma0 * height) - 1):+.3f} %); min over the run "
          f"{R.min():.1f} N/m at {1e3 * t[np.argmin(R)]:.3f} ms")
    print(f"wrote {png}")


# ------------------------------------------------------ plate_transient
def _analytic():
    """tests/scripts/analytic.py (the series and its lines.csv reader)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
    import analytic
    return analytic


def plot_plate_transient(folder, png):
    """OUTPUT_FOLDER as written by verify_discrete_plate.py: h0.05/,
    h0.025/, continuum_P1/, beta{100,1000,10000}/, explicit/."""
    an = _analytic()
    prm = "plate_transient.prm"
    ensure_run(os.path.join(folder, "h0.05"), prm)
    ensure_run(os.path.join(folder, "continuum_P1"), prm, "Model=continuum heat",
               "Heat solver/Polynomial degree=1", "Time stepping/Method=backward Euler",
               "Output/Write vtu=false")
    times = (2.0, 10.0, 20.0, 50.0)
    fig, (ax_t, ax_b) = plt.subplots(1, 2, figsize=(12.5, 5), dpi=150,
                                     gridspec_kw=dict(width_ratios=[1.35, 1]))
    lines = an.read_csv(os.path.join(folder, "h0.05", "lines.csv"))["midline"]
    xs = np.linspace(0, 1, 401)
    print("plate_transient (discrete, h = 0.05 m, beta = 1000): max |T - series| along 'midline'")
    for i, t in enumerate(times):
        x, _, f = lines[t]
        err = np.abs(f["T"] - an.plate_transient(x, t)).max()
        print(f"  t = {t:4.0f} s: {err:.4f} C")
        c = f"C{i}"
        ax_t.plot(xs, an.plate_transient(xs, t), "-", color=c, lw=1.0)
        ax_t.plot(x[::2], f["T"][::2], "o", color=c, ms=3, mfc="none",
                  label=f"t = {t:g} s: max error {err:.3f} C")
    ax_t.plot([], [], "k-", lw=1.0, label="corrected series (lines)")
    ax_t.set_xlabel("x along 'midline' (y = 0.125 m) [m]")
    ax_t.set_ylabel("T [C]")
    ax_t.set_title("discrete P1 triangles + joints, h = 0.05 m, beta = 1000, backward Euler "
                   "dt = 0.05 s", fontsize=9)
    ax_t.legend(fontsize=7, loc="upper left")
    ax_t.grid(alpha=0.3)

    ref = an.read_csv(os.path.join(folder, "continuum_P1", "lines.csv"))["midline"]
    betas = (100, 1000, 10000)
    diffs = []
    for beta in betas:
        run = os.path.join(folder, f"beta{beta}")
        ensure_run(run, prm, f"Discrete heat/Joint conductance factor={beta}",
                   "Output/Write vtu=false")
        d = an.read_csv(os.path.join(run, "lines.csv"))["midline"]
        diffs.append(max(np.abs(d[t][2]["T"] - ref[t][2]["T"]).max() for t in (2.0, 10.0, 50.0)))
    diffs = np.array(diffs)
    print("  max |T_discrete - T_continuum P1| over t = 2, 10, 50 s:")
    for beta, dd in zip(betas, diffs):
        print(f"    beta = {beta:6d}: {dd:.4e} C")
    b = np.array(betas, float)
    ax_b.loglog(b, diffs, "o", color="C3", ms=6, label="tmfdem: max over t = 2, 10, 50 s")
    for beta, dd in zip(betas, diffs):
        ax_b.annotate(f"{dd:.3g} C", (beta, dd), textcoords="offset points", xytext=(6, 4),
                      fontsize=7)
    bb = np.logspace(1.8, 4.2, 20)
    ax_b.loglog(bb, diffs[1] * 1000 / bb, "k--", lw=0.8, label="1 / beta (through beta = 1000)")
    ax_b.set_xlabel("joint conductance factor beta (k_i = beta k / h)")
    ax_b.set_ylabel("max |T_discrete - T_continuum P1| [C]")
    ax_b.set_title("difference to the continuum P1 solver on the same mesh and steps",
                   fontsize=9)
    ax_b.legend(fontsize=7)
    ax_b.grid(alpha=0.3, which="both")
    fig.suptitle("Paper Sec. 5.1 in the discrete layer: 1 m x 0.25 m plate, 0 C / 100 C edges, "
                 "kappa = 0.005 m^2/s", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    for sub, label in (("h0.025", "h = 0.025 m"), ("explicit", "explicit lumped, beta = 100")):
        path = os.path.join(folder, sub, "lines.csv")
        if os.path.exists(path):
            d = an.read_csv(path)["midline"]
            errs = ", ".join(f"{np.abs(d[t][2]['T'] - an.plate_transient(d[t][0], t)).max():.4f} C"
                             f" at {t:g} s" for t in times if t in d)
            print(f"  {label}: {errs}")
    print(f"wrote {png}")


def plot_plate_transient_3d(folder, png):
    """OUTPUT_FOLDER as written by verify_discrete_heat_3d.py: plate/ (the
    shipped prm) and plate_beta_{100,1000,10000}/ (to t = 10 s)."""
    an = _analytic()
    prm = "plate_transient-discrete-3d.prm"
    ensure_run(os.path.join(folder, "plate"), prm)
    fig, (ax_t, ax_b) = plt.subplots(1, 2, figsize=(12.5, 5), dpi=150,
                                     gridspec_kw=dict(width_ratios=[1.35, 1]))
    xs = np.linspace(0, 1, 401)
    print("plate_transient-discrete-3d (12 000 tetrahedra, beta = 1000): "
          "max |T - series| over all nodes")
    records = sorted(glob.glob(os.path.join(folder, "plate", "solution_*.vtu")))[1:]
    times = (2.0, 10.0, 20.0)
    for i, (t, path) in enumerate(zip(times, records)):
        points, _, arrays = read_vtu(path)
        X = points - arrays["displacement"].reshape(-1, 3)
        T = arrays["T"]
        err = np.abs(T - an.plate_transient(X[:, 0], t)).max()
        print(f"  t = {t:4.0f} s: {err:.4f} C")
        c = f"C{i}"
        ax_t.plot(xs, an.plate_transient(xs, t), "-", color=c, lw=1.0)
        ax_t.plot(X[::7, 0], T[::7], ".", color=c, ms=1.5, alpha=0.5,
                  label=f"t = {t:g} s: max error {err:.3f} C (every node)")
    ax_t.plot([], [], "k-", lw=1.0, label="corrected 1D series (lines)")
    ax_t.set_xlabel("x [m] (nodes of the whole slab; every 7th drawn)")
    ax_t.set_ylabel("T [C]")
    ax_t.set_title("exploded tetrahedra + face joints, h = 0.05 m, beta = 1000, backward "
                   "Euler dt = 0.05 s", fontsize=9)
    ax_t.legend(fontsize=7, loc="upper left")
    ax_t.grid(alpha=0.3)

    # beta = 1000: the shipped run's output at t = 10 s
    T10 = {1000: read_vtu(records[1])[2]["T"]}
    for beta in (100, 10000):
        run = os.path.join(folder, f"plate_beta_{beta}")
        ensure_run(run, prm, f"Discrete heat/Joint conductance factor={beta}",
                   "Time stepping/End time=10", "Output/Times=10")
        last = sorted(glob.glob(os.path.join(run, "solution_*.vtu")))[-1]
        T10[beta] = read_vtu(last)[2]["T"]
    steps = [np.abs(T10[100] - T10[1000]).max(), np.abs(T10[1000] - T10[10000]).max()]
    print(f"  t = 10 s: beta 100 -> 1000 changes T by {steps[0]:.4f} C, 1000 -> 10000 by "
          f"{steps[1]:.5f} C (ratio {steps[0] / steps[1]:.3f})")
    ax_b.loglog([100, 1000], steps, "o-", color="C3", ms=6,
                label="max |T(beta) - T(10 beta)| at t = 10 s")
    for beta, dd in zip((100, 1000), steps):
        ax_b.annotate(f"{dd:.3g} C", (beta, dd), textcoords="offset points", xytext=(6, 4),
                      fontsize=7)
    bb = np.logspace(1.8, 3.3, 20)
    ax_b.loglog(bb, steps[0] * 100 / bb, "k--", lw=0.8, label="1 / beta")
    ax_b.set_xlabel("joint conductance factor beta (k_i = beta k / h)")
    ax_b.set_ylabel("change of T when beta grows ten-fold [C]")
    ax_b.set_title("the joints' resistance falls as 1 / beta", fontsize=9)
    ax_b.legend(fontsize=7)
    ax_b.grid(alpha=0.3, which="both")
    fig.suptitle("Paper Sec. 5.1 extruded, discrete layer in 3D: 1 x 0.25 x 0.25 m slab, "
                 "0 C / 100 C faces, kappa = 0.005 m^2/s", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


# --------------------------------------------------- contact_conduction
def plot_contact_conduction(folder, png):
    """OUTPUT_FOLDER as written by verify_discrete_contact_heat.py: steady/
    and equilibrate/."""
    an = _analytic()
    prm = "contact_conduction.prm"
    width, delta, h_c = 0.05, 1e-5, 50.0
    k1, k2, L1, L2 = 2.0, 5.0, 0.1, 0.1 - delta
    steady, equil = os.path.join(folder, "steady"), os.path.join(folder, "equilibrate")
    ensure_run(steady, prm)
    ensure_run(equil, prm, "Thermal boundary conditions/Condition 1/Boundary ids=",
               "Thermal boundary conditions/Condition 2/Boundary ids=",
               "Materials/Material 1/Thermal conductivity=1000",
               "Materials/Material 2/Thermal conductivity=1000",
               "Materials/Material 1/Initial temperature=100",
               "Materials/Material 2/Initial temperature=0",
               "Time stepping/End time=6000", "Time stepping/Time step=5",
               "Output/Interval=500", "Output/Write vtu=false",
               "Monitors/Lines=", "Monitors/Probes=lower: 0.025, 0.05; upper: 0.025, 0.15")
    q = 100.0 / (L1 / k1 + 1.0 / h_c + L2 / k2)
    lines = an.read_csv(os.path.join(steady, "lines.csv"))["axis"]
    _, y, f = lines[max(lines)]
    T = f["T"]
    ym = 0.1 - delta / 2
    exact = np.where(y < ym, 100 - q * y / k1, q * (0.2 - delta - y) / k2)
    below, above = y < 0.1 - delta, y > 0.1      # leave out the 10 um overlap
    err = np.abs(T - exact)[below | above].max()
    Q = read_summary(steady)["heat_balance"]["boundary_heat_rate_last_step"]["1"]
    fig, (ax_s, ax_e) = plt.subplots(1, 2, figsize=(12, 5), dpi=150)
    yy = np.linspace(0, 0.2 - delta, 2001)
    ax_s.plot(100 * yy, np.where(yy < ym, 100 - q * yy / k1, q * (0.2 - delta - yy) / k2),
              "k-", lw=1.0, label=f"exact: q = dT / (L1/k1 + 1/h_c + L2/k2) = {q:.2f} W/m^2, "
                                  f"jump q / h_c = {q / h_c:.3f} C")
    ax_s.plot(100 * y[::4], T[::4], "o", color="C0", ms=3, mfc="none",
              label=f"tmfdem, t = 1e7 s (max error {err:.3f} C)")
    ax_s.axvline(100 * ym, color="gray", lw=0.5, ls=":")
    ax_s.set_xlabel("y along 'axis' (x = 0.025 m) [cm]")
    ax_s.set_ylabel("T [C]")
    ax_s.set_title(f"steady: k1 = {k1:g} | h_c = {h_c:g} W/(m^2 K) | k2 = {k2:g} W/(m K); "
                   f"heat flow {Q:.4f} W/m vs q w = {q * width:.4f} W/m", fontsize=8.5)
    ax_s.legend(fontsize=7, loc="upper right")
    ax_s.grid(alpha=0.3)

    probes = an.read_csv(os.path.join(equil, "probes.csv"))
    times = np.array(sorted(probes["lower"]))
    diff = np.array([probes["lower"][t][2]["T"][0] - probes["upper"][t][2]["T"][0]
                     for t in times])
    C1 = 2500.0 * 800.0 * width * 0.1
    C2 = 2500.0 * 800.0 * width * (0.1 - delta)
    tau = C1 * C2 / ((C1 + C2) * h_c * width)
    pos = times > 0
    fit = np.polyfit(times[pos], np.log(diff[pos]), 1)
    tau_fit, amp = -1.0 / fit[0], np.exp(fit[1])
    tt = np.linspace(0, times.max(), 400)
    ax_e.semilogy(tt, 100 * np.exp(-tt / tau), "k-", lw=1.0,
                  label=f"100 exp(-t / tau), tau = C1 C2 / ((C1 + C2) h_c w) = {tau:.2f} s")
    # per-material initial temperatures: each block starts uniform (a
    # threshold in y could not separate the overlapping blocks)
    ax_e.semilogy(tt, amp * np.exp(-tt / tau), "k:", lw=1.0,
                  label=f"{amp:.2f} exp(-t / tau) (amplitude fitted)")
    ax_e.semilogy(times, diff, "o", color="C3", ms=4, mfc="none",
                  label=f"tmfdem T(lower probe) - T(upper probe): fitted tau {tau_fit:.2f} s")
    ax_e.set_xlabel("t [s]")
    ax_e.set_ylabel("T_lower - T_upper [C]")
    ax_e.set_title("equilibration of two insulated blocks (k = 1000 W/(m K)), 100 C and 0 C "
                   "at t = 0", fontsize=8.5)
    ax_e.legend(fontsize=7)
    ax_e.grid(alpha=0.3, which="both")
    fig.suptitle("Heat across a contact: two blocks pressed together (overlap 10 um)",
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print("contact_conduction:")
    print(f"  steady: heat flow {Q:.5f} W/m vs q w = {q * width:.5f} W/m "
          f"({100 * (Q / (q * width) - 1):+.3f} %); max |T - exact| on 'axis' "
          f"{err:.4f} C (below the contact {np.abs(T - exact)[below].max():.4f}, "
          f"above {np.abs(T - exact)[above].max():.4f})")
    print(f"  equilibrate: tau fitted {tau_fit:.2f} s vs {tau:.2f} s "
          f"({100 * (tau_fit / tau - 1):+.3f} %), fitted amplitude {amp:.3f} C; difference at t = {times[-1]:g} s: "
          f"{diff[-1]:.4f} C vs {100 * np.exp(-times[-1] / tau):.4f} C")
    for t, d in zip(times, diff):
        print(f"    t = {t:6g} s: {d:9.4f} C   exact {100 * np.exp(-t / tau):9.4f} C")
    print(f"wrote {png}")


# ------------------------------- sheet_free_expansion, sheet_restrained_expansion
SHEET = dict(E=75.1e9, nu=0.311, alpha=3e-6)   # Table 3


def _sheet_run(folder, kind, dT, idealisation="plane stress"):
    """The runs of verify_discrete_sheets.py: free_{+100,-100}/,
    restrained_{plane_stress,plane_strain}_{+100,-100}/."""
    if kind == "free":
        run = os.path.join(folder, f"free_{dT:+.0f}")
        ensure_run(run, "sheet_free_expansion.prm", f"Initial conditions/Temperature={dT}",
                   "Output/Write vtu=false")
    else:
        run = os.path.join(folder, f"restrained_{idealisation.replace(' ', '_')}_{dT:+.0f}")
        ensure_run(run, "sheet_restrained_expansion.prm", f"Initial conditions/Temperature={dT}",
                   f"Mechanics/Idealisation={idealisation}", "Output/Write vtu=false")
    an = _analytic()
    lines = an.read_csv(os.path.join(run, "lines.csv"))["diagonal"]
    return lines[max(lines)], read_summary(run)


def plot_sheet_free_expansion(folder, png):
    E, alpha = SHEET["E"], SHEET["alpha"]
    fig, (ax_u, ax_e) = plt.subplots(1, 2, figsize=(12, 5), dpi=150)
    print("sheet_free_expansion (plane stress): along 'diagonal' at the end")
    for dT, c in ((100.0, "C3"), (-100.0, "C0")):
        (x, y, f), s = _sheet_run(folder, "free", dT)
        ex, ey = alpha * dT * x, alpha * dT * y
        xs = np.linspace(0, 2, 50)
        ax_u.plot(xs, 1e3 * alpha * dT * xs, "-", color=c, lw=1.0,
                  label=f"dT = {dT:+.0f} C: alpha dT x (= alpha dT y)")
        ax_u.plot(x, 1e3 * f["ux"], "o", color=c, ms=4, mfc="none", label=f"dT = {dT:+.0f} C: ux")
        ax_u.plot(y, 1e3 * f["uy"], "x", color=c, ms=4, label=f"dT = {dT:+.0f} C: uy")
        rx, ry = f["ux"] / ex - 1, f["uy"] / ey - 1
        ax_e.plot(x, 100 * rx, "o-", color=c, ms=3, lw=0.7, mfc="none",
                  label=f"dT = {dT:+.0f} C: ux / (alpha dT x) - 1")
        ax_e.plot(y, 100 * ry, "x--", color=c, ms=3, lw=0.7,
                  label=f"dT = {dT:+.0f} C: uy / (alpha dT y) - 1")
        smax = max(np.abs(f[k]).max() for k in ("sxx", "syy", "sxy"))
        print(f"  dT = {dT:+.0f} C: u / (alpha dT X) - 1 in [{100 * min(rx.min(), ry.min()):.4f}, "
              f"{100 * max(rx.max(), ry.max()):.4f}] %; max |stress| {smax:.0f} Pa = "
              f"{smax / (E * alpha * abs(dT)):.1e} E alpha |dT|; corner u = ({f['ux'][-1]:.6e}, "
              f"{f['uy'][-1]:.6e}) m vs {alpha * dT * x[-1]:.6e}; energy balance "
              f"{s['energy']['relative_balance_error']:.1e}, steps {s['steps']}")
    ax_u.set_xlabel("x (for ux), y (for uy) along 'diagonal' [m]")
    ax_u.set_ylabel("displacement [mm]")
    ax_u.set_title("displacement along the diagonal at t = 4 ms", fontsize=10)
    ax_u.legend(fontsize=7)
    ax_u.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_xlabel("x (for ux), y (for uy) along 'diagonal' [m]")
    ax_e.set_ylabel("relative error [%]")
    ax_e.set_title("strain error u / (alpha dT X) - 1", fontsize=10)
    ax_e.legend(fontsize=7)
    ax_e.grid(alpha=0.3)
    fig.suptitle("Free 2 m sheet of jointed triangles at a uniform dT (discrete thermo-mechanics, "
                 "plane stress)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


def plot_sheet_restrained_expansion(folder, png):
    E, nu, alpha = SHEET["E"], SHEET["nu"], SHEET["alpha"]
    fig, (ax_s, ax_e) = plt.subplots(1, 2, figsize=(12, 5), dpi=150)
    print("sheet_restrained_expansion: along 'diagonal' at the end")
    runs = ((100.0, "plane stress", E / (1 - nu), "C3"),
            (-100.0, "plane stress", E / (1 - nu), "C0"),
            (100.0, "plane strain", E / (1 - 2 * nu), "C2"))
    for dT, ideal, modulus, c in runs:
        (x, y, f), s = _sheet_run(folder, "restrained", dT, ideal)
        exact = -modulus * alpha * dT
        d = np.hypot(x, y)
        tag = f"{ideal}, dT = {dT:+.0f} C"
        ax_s.axhline(exact / 1e6, color=c, lw=1.0,
                     label=f"{tag}: -E alpha dT / (1 - {'nu' if ideal == 'plane stress' else '2 nu'})"
                           f" = {exact / 1e6:.4f} MPa")
        ax_s.plot(d, f["sxx"] / 1e6, "o", color=c, ms=4, mfc="none", label=f"{tag}: sxx")
        ax_s.plot(d, f["syy"] / 1e6, "x", color=c, ms=4, label=f"{tag}: syy")
        rx, ry = f["sxx"] / exact - 1, f["syy"] / exact - 1
        ax_e.plot(d, 100 * rx, "o-", color=c, ms=3, lw=0.7, mfc="none", label=f"{tag}: sxx")
        ax_e.plot(d, 100 * ry, "x--", color=c, ms=3, lw=0.7, label=f"{tag}: syy")
        print(f"  {tag}: exact {exact / 1e6:.4f} MPa; sxx/exact - 1 in [{100 * rx.min():.3f}, "
              f"{100 * rx.max():.3f}] %, syy/exact - 1 in [{100 * ry.min():.3f}, {100 * ry.max():.3f}] %,"
              f" mean {100 * np.mean(np.r_[rx, ry]):.3f} %; max |sxy| {np.abs(f['sxy']).max():.0f} Pa;"
              f" energy balance {s['energy']['relative_balance_error']:.1e}, steps {s['steps']}")
    ax_s.set_xlabel("distance along 'diagonal' from (0, 0) [m]")
    ax_s.set_ylabel("stress [MPa]")
    ax_s.set_title("sxx, syy along the diagonal at t = 4 ms", fontsize=10)
    ax_s.legend(fontsize=6.5, loc="center right")
    ax_s.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_xlabel("distance along 'diagonal' from (0, 0) [m]")
    ax_e.set_ylabel("sigma / exact - 1 [%]")
    ax_e.set_title("relative error (penalty 1000 E)", fontsize=10)
    ax_e.legend(fontsize=6.5)
    ax_e.grid(alpha=0.3)
    fig.suptitle("2 m sheet of jointed triangles on rollers at a uniform dT (discrete "
                 "thermo-mechanics)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


# ------------------------------------------------ thermal_shock_disc-3d
def plot_thermal_shock_disc_3d(folder, png):
    """OUTPUT_FOLDER as written by verify_discrete_thermal_shock_3d.py:
    disc-3d/ (prm/thermal_shock_disc-3d.prm at 400 C) and disc-2d/ (the 2D
    case at 400 C over the same span)."""
    sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
    import verify_discrete_thermal_shock_3d as v
    run3, run2 = os.path.join(folder, "disc-3d"), os.path.join(folder, "disc-2d")
    if not os.path.exists(os.path.join(run3, "summary.json")):
        v.run_case(BINARY, folder)
    series = v.outputs(run3)
    fig, (ax_z, ax_t) = plt.subplots(1, 2, figsize=(12.5, 5), dpi=150)
    # left: each rim tetrahedron's hoop stress over the plane-stress value
    # averaged over it, against the height of its centroid
    intact = [(t, a) for t, a in series if t > 0 and not np.any(a[("CellData", "joint_damage")] > 0)]
    for i, (t, arrays) in enumerate(intact[1::2]):
        tet = v.tetrahedra(arrays)
        rim = tet["on_mantle"] == 3
        ratio = tet["hoop"][rim] / v.element_mean(v.plane_stress_hoop(t), tet["vertices"][rim])
        ax_z.plot(tet["z"][rim] * 1e3, ratio, ".", ms=2, color=f"C{i}", alpha=0.6,
                  label=f"t = {t * 1e3:g} ms (rim tetrahedra)")
    ax_z.axhline(1.0, color="k", lw=1, label="plane stress (thin disc)")
    ax_z.axhline(1 / (1 - v.NU), color="k", ls="--", lw=1,
                 label="generalised plane strain (long cylinder): 1 / (1 - nu)")
    ax_z.set_xlabel("z of the centroid [mm] (faces at -0.5 and 0.5 mm)")
    ax_z.set_ylabel("hoop stress / plane-stress closed form (mean over the tetrahedron)")
    ax_z.set_title("before cracking: the rim carries more than plane stress, less as the layer deepens", fontsize=9)
    ax_z.legend(fontsize=7, loc="lower center")
    ax_z.grid(alpha=0.3)
    # right: the largest rim hoop stress against time, the closed forms'
    # element means, and the first damage in 3D and 2D
    tet0 = v.tetrahedra(series[0][1])
    rim0 = tet0["on_mantle"] == 3
    times = np.linspace(0.5e-3, max(t for t, _ in series), 60)
    ps = np.array([v.element_mean(v.plane_stress_hoop(t), tet0["vertices"][rim0]).max()
                   for t in times])
    ax_t.plot(times * 1e3, ps / 1e6, "k-", lw=1, label="plane stress, largest rim element mean")
    ax_t.plot(times * 1e3, ps / (1 - v.NU) / 1e6, "k--", lw=1,
              label="generalised plane strain, the same")
    measured = [(t, v.tetrahedra(a)["hoop"][rim0].max()) for t, a in series if t > 0]
    ax_t.plot([m[0] * 1e3 for m in measured], [m[1] / 1e6 for m in measured], "o", color="C3",
              label="3D discrete: largest rim hoop stress")
    ax_t.axhline(v.F_T / 1e6, color="C7", lw=0.8)
    ax_t.annotate("f_t", (times[0] * 1e3, v.F_T / 1e6), fontsize=8, xytext=(2, 3),
                  textcoords="offset points")
    onset = v.first_damage(run3)
    if onset:
        ax_t.axvspan(onset[0] * 1e3, onset[1] * 1e3, color="C3", alpha=0.4)
        ax_t.axvline(onset[1] * 1e3, color="C3", lw=1,
                     label=f"3D first damage: {onset[1] * 1e3:.2f} ms")
    if os.path.exists(os.path.join(run2, "history.csv")):
        onset2 = v.first_damage(run2)
        if onset2:
            ax_t.axvline(onset2[1] * 1e3, color="C0", lw=1,
                         label=f"2D plane stress (0.4 mm triangles): {onset2[1] * 1e3:.2f} ms")
    t1, t2 = v.window(series[0][1])
    ax_t.axvspan(t1 * 1e3, t2 * 1e3, color="C2", alpha=0.12, label="window of the closed forms")
    print(f"thermal_shock_disc-3d: window {t1 * 1e3:.3f} .. {t2 * 1e3:.3f} ms, first damage "
          f"{onset}")
    ax_t.set_xlabel("t [ms]")
    ax_t.set_ylabel("hoop stress at the rim [MPa]")
    ax_t.set_title("cracking starts earlier than plane stress predicts",
                   fontsize=9)
    ax_t.legend(fontsize=7, loc="lower right")
    ax_t.grid(alpha=0.3)
    fig.suptitle("Paper 5.6 in 3D: 13 x 1 mm alumina disc quenched at the rim from 400 C, "
                 "faces insulated (tetrahedra 0.25 mm at the rim)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")



# ------------------------------------------------ contact_conduction-3d
def plot_contact_conduction_3d(folder, png):
    """OUTPUT_FOLDER as written by verify_discrete_contact_heat_3d.py:
    steady/ and equilibrate/."""
    import vtu_pieces
    prm = "contact_conduction-3d.prm"
    section, delta, h_c = 0.05 * 0.05, 1e-5, 50.0
    k1, k2, L1, L2 = 2.0, 5.0, 0.1, 0.1 - delta
    steady, equil = os.path.join(folder, "steady"), os.path.join(folder, "equilibrate")
    ensure_run(steady, prm, "Discrete heat/Contact conductance=50")
    ensure_run(equil, prm, "Thermal boundary conditions/Condition 1/Boundary ids=",
               "Thermal boundary conditions/Condition 2/Boundary ids=",
               "Materials/Material 1/Thermal conductivity=1000",
               "Materials/Material 2/Thermal conductivity=1000",
               "Materials/Material 1/Initial temperature=100",
               "Materials/Material 2/Initial temperature=0",
               "Discrete heat/Contact conductance=50", "Time stepping/Time step=5",
               "Discrete heat/Joint conductance factor=100",
               "Time stepping/End time=3000",
               "Output/Times=" + ", ".join(str(250 * i) for i in range(1, 13)))

    def nodal(arrays):
        z = arrays[("Points", None)].reshape(-1, 3)[:, 2]
        material = np.repeat(arrays[("CellData", "material_id")], 4)
        return z, material, arrays[("PointData", "T")]

    q = 100.0 / (L1 / k1 + 1.0 / h_c + L2 / k2)
    zm = 0.1 - delta / 2
    z, material, T = nodal(vtu_pieces.read_series(steady)[-1][1])
    exact = np.where(material == 1, 100 - q * z / k1, q * (0.2 - delta - z) / k2)
    err = np.abs(T - exact).max()
    Q = read_summary(steady)["heat_balance"]["boundary_heat_rate_last_step"]["1"]
    fig, (ax_s, ax_e) = plt.subplots(1, 2, figsize=(12, 5), dpi=150)
    zz = np.linspace(0, 0.2 - delta, 2001)
    ax_s.plot(100 * zz, np.where(zz < zm, 100 - q * zz / k1, q * (0.2 - delta - zz) / k2),
              "k-", lw=1.0, label=f"exact: q = dT / (L1/k1 + 1/h_c + L2/k2) = {q:.2f} W/m^2, "
                                  f"jump q / h_c = {q / h_c:.3f} C")
    for m, color in ((1, "C0"), (2, "C3")):
        sel = material == m
        ax_s.plot(100 * z[sel], T[sel], "o", color=color, ms=2, mfc="none", alpha=0.5,
                  label=f"tmfdem, block {m}: {sel.sum()} nodes")
    ax_s.axvline(100 * zm, color="gray", lw=0.5, ls=":")
    ax_s.set_xlabel("z [cm]")
    ax_s.set_ylabel("T [C]")
    ax_s.set_title(f"steady, every node (max |T - exact| {err:.3f} C); heat flow {Q:.4f} W vs "
                   f"q A = {q * section:.4f} W", fontsize=8.5)
    ax_s.legend(fontsize=7, loc="upper right")
    ax_s.grid(alpha=0.3)

    times, diff = [], []
    for t, arrays in vtu_pieces.read_series(equil)[1:]:
        z, material, T = nodal(arrays)
        times.append(t)
        diff.append(T[material == 1].mean() - T[material == 2].mean())
    times, diff = np.array(times), np.array(diff)
    C1, C2 = 2500.0 * 800.0 * section * L1, 2500.0 * 800.0 * section * L2
    tau = C1 * C2 / ((C1 + C2) * h_c * section)
    fit = np.polyfit(times, np.log(diff), 1)
    tau_fit, amp = -1.0 / fit[0], np.exp(fit[1])
    tt = np.linspace(0, times.max(), 400)
    ax_e.semilogy(tt, 100 * np.exp(-tt / tau), "k-", lw=1.0,
                  label=f"100 exp(-t / tau), tau = C1 C2 / ((C1 + C2) h_c A) = {tau:.2f} s")
    ax_e.semilogy(times, diff, "o", color="C3", ms=4, mfc="none",
                  label=f"tmfdem, difference of the blocks' mean T: fitted tau {tau_fit:.2f} s")
    ax_e.set_xlabel("t [s]")
    ax_e.set_ylabel("mean T (block 1) - mean T (block 2) [C]")
    ax_e.set_title("equilibration of two insulated blocks (k = 1000 W/(m K)), 100 C and 0 C "
                   "at t = 0", fontsize=8.5)
    ax_e.legend(fontsize=7)
    ax_e.grid(alpha=0.3, which="both")
    fig.suptitle("Heat across a contact between tetrahedra: two blocks pressed together "
                 "(overlap 10 um)", fontsize=11)
    fig.tight_layout()
    fig.savefig(png)
    print("contact_conduction-3d:")
    print(f"  steady: heat flow {Q:.5f} W vs q A = {q * section:.5f} W "
          f"({100 * (Q / (q * section) - 1):+.3f} %); max |T - exact| at the nodes {err:.4f} C")
    print(f"  equilibrate: tau fitted {tau_fit:.2f} s vs {tau:.2f} s "
          f"({100 * (tau_fit / tau - 1):+.3f} %), fitted amplitude {amp:.3f} C")
    print(f"wrote {png}")


def plot_rock_heap_3d(folder, png):
    """OUTPUT_FOLDER with settle/ (prm/rock_heap-3d.prm) and heat/
    (prm/rock_heap-heat-3d.prm on settle/final_mesh.msh)."""
    import vtu_pieces
    settle, heat = os.path.join(folder, "settle"), os.path.join(folder, "heat")
    ensure_run(settle, "rock_heap-3d.prm")
    ensure_run(heat, "rock_heap-heat-3d.prm",
               f"Mesh/File name={os.path.join(settle, 'final_mesh.msh')}")
    rho, g = 2500.0, 9.81
    h = read_csv(os.path.join(settle, "history.csv"))
    s = read_summary(settle)

    # the settled mesh: the blocks' and the container's volumes
    def msh_volumes(path):
        with open(path) as f:
            lines = f.read().split("\n")
        i = lines.index("$Nodes")
        n = int(lines[i + 1])
        xyz = {int(v[0]): np.array([float(a) for a in v[1:4]])
               for v in (line.split() for line in lines[i + 2:i + 2 + n])}
        i = lines.index("$Elements")
        vol = {1: 0.0, 2: 0.0}
        for line in lines[i + 2:i + 2 + int(lines[i + 1])]:
            v = [int(a) for a in line.split()]
            if v[1] == 4:
                a, b, c, d = (xyz[k] for k in v[3 + v[2]:7 + v[2]])
                vol[v[3]] += abs(np.dot(np.cross(b - a, c - a), d - a)) / 6
        return vol
    # the masses from the generated mesh (reference volumes)
    vol = msh_volumes(os.path.join(settle, "mesh.msh"))
    W_blocks, W_container = rho * g * vol[1], rho * g * vol[2]

    fig, axes = plt.subplots(2, 2, figsize=(12, 9), dpi=150)
    ax = axes[0, 0]
    t = h["time"]
    ax.semilogy(t, np.maximum(h["kinetic"], 1e-12), "C0-", lw=1.0, label="kinetic energy")
    ax.semilogy(t, np.maximum(h["external_work"], 1e-12), "k-", lw=1.0, label="gravity work")
    ax.semilogy(t, np.maximum(h["damping"], 1e-12), "C2--", lw=1.0, label="damping (viscous + mass)")
    ax.semilogy(t, np.maximum(h["friction_dissipation"], 1e-12), "C3--", lw=1.0,
                label="friction dissipation")
    ax.semilogy(t, np.maximum(np.abs(h["balance_error"]), 1e-12), "C7:", lw=1.0,
                label="|energy balance error|")
    e = s["energy"]
    ax.set_title(f"settling: kinetic energy at the end {e['kinetic']:.2e} J = "
                 f"{e['kinetic'] / e['external_work']:.1e} of the gravity work", fontsize=9)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("energy [J]")
    ax.set_ylim(1e-8, None)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)

    ax = axes[0, 1]
    carried = h["body1_fz"] - W_container
    late = t >= t[-1] - 0.1
    ax.plot(t, carried, "C0-", lw=0.8, label="container reaction less its own weight")
    ax.axhline(W_blocks, color="k", lw=1.0, label=f"blocks' weight m g = {W_blocks:.2f} N")
    mean = carried[late].mean()
    ax.set_title(f"at rest (mean over the last 0.1 s): {mean:.2f} N, "
                 f"{(mean / W_blocks - 1) * 100:+.2f} % of m g", fontsize=9)
    ax.set_ylim(-0.2 * W_blocks, 2.5 * W_blocks)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("vertical force [N]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)

    # heating: the blocks' mean temperature by height at the output times
    ax = axes[1, 0]
    # the prm's output times (0.5, 2, 5, 12 h)
    series = [(time, arrays) for time, arrays in vtu_pieces.read_series(heat)
              if any(abs(time - t) < 1 for t in (1800, 7200, 18000, 43200))]
    top = None
    for k, (time, arrays) in enumerate(series):
        z = arrays[("Points", None)].reshape(-1, 3)[:, 2]
        material = np.repeat(arrays[("CellData", "material_id")], 4)
        T = arrays[("PointData", "T")]
        zb, Tb = z[material == 1], T[material == 1]
        top = zb.max() if top is None else top
        edges = np.linspace(0.0, top, 11)
        centre = 0.5 * (edges[:-1] + edges[1:])
        means = [Tb[(zb >= lo) & (zb < hi)].mean() for lo, hi in zip(edges[:-1], edges[1:])]
        ax.plot(means, 100 * centre, "o-", color=f"C{k}", ms=3, lw=1.0,
                label=f"t = {time / 3600:g} h")
        thirds = np.linspace(0.0, top, 4)
        print(f"t = {time / 3600:g} h: blocks' mean temperature by thirds of the height "
              "(bottom, middle, top): " +
              ", ".join(f"{Tb[(zb >= lo) & (zb < hi)].mean():.1f}"
                        for lo, hi in zip(thirds[:-1], thirds[1:])) +
              f" C; all blocks {Tb.mean():.1f} C")
    ax.set_xlabel("blocks' mean temperature in a layer [C]")
    ax.set_ylabel("height z [cm]")
    ax.set_title("heating from the base (100 C), walls at 0 C: layers of a tenth of "
                 "the heap's height", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)

    ax = axes[1, 1]
    hh = read_csv(os.path.join(heat, "history.csv"))
    hb = read_summary(heat)["heat_balance"]
    ax.plot(hh["time"] / 3600, hh["stored_heat"] / 1e6, "C0-", lw=1.0, label="stored heat")
    ax.plot(hh["time"] / 3600, np.abs(hh["heat_imbalance"]) / 1e6, "C3:", lw=1.0,
            label="|in - out - stored|")
    q = hb["boundary_heat_in"]
    ax.set_title(f"heat balance at the end: in {q.get('1', 0) / 1e6:.4f} MJ (base), "
                 f"{q.get('2', 0) / 1e6:.4f} MJ (walls), relative imbalance "
                 f"{hb['relative_imbalance']:.1e}", fontsize=8.5)
    ax.set_xlabel("t [h]")
    ax.set_ylabel("heat [MJ]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.suptitle(f"rock heap in 3D: {s['elements']} tetrahedra, "
                 f"{read_summary(heat)['contact_heat_pairs']} contact pairs conducting", fontsize=10)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


CASES = {"joint_pull": plot_joint_pull,
         "joint_pull-3d": plot_joint_pull_3d,
         "block_on_incline": plot_block_on_incline,
         "two_blocks_collision": plot_two_blocks_collision,
         "two_blocks_collision-3d": plot_two_blocks_collision_3d,
         "block_on_incline-3d": plot_block_on_incline_3d,
         "brazilian_disc": plot_brazilian_disc,
         "plate_traction": plot_plate_traction,
         "plate_transient": plot_plate_transient,
         "plate_transient-discrete-3d": plot_plate_transient_3d,
         "contact_conduction": plot_contact_conduction,
         "contact_conduction-3d": plot_contact_conduction_3d,
         "sheet_free_expansion": plot_sheet_free_expansion,
         "sheet_restrained_expansion": plot_sheet_restrained_expansion,
         "thermal_shock_disc-3d": plot_thermal_shock_disc_3d,
         "sphere_drop-3d": plot_sphere_drop_3d,
         "brazilian_cylinder-3d": plot_brazilian_cylinder_3d,
         "rock_heap-3d": plot_rock_heap_3d}


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in CASES:
        sys.exit(f"usage: {os.path.basename(sys.argv[0])} CASE OUTPUT_FOLDER PNG\n"
                 f"  CASE: {', '.join(CASES)}")
    case, folder, png = sys.argv[1:]
    CASES[case](os.path.abspath(folder), png)


if __name__ == "__main__":
    main()
