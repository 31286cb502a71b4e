#!/usr/bin/python3
"""Tutorial lesson 6: thermal shock and cracking (short version of
prm/thermal_shock_disc.prm).

Runs doc/tutorial/prm/lesson-06-quench.prm (13 mm alumina disc at 500 C,
rim quenched at t = 0, h = 0.8 mm, 20 ms) and checks, with the window fixed
by the analytic quenched disc (Carslaw and Jaeger 7.6 for T, Timoshenko and
Goodier 150 for the plane-stress hoop stress, tests/scripts/analytic.py):
  the first damaged joint appears in the thermal step (t_prev, t_first] with
      t_first >= t1 and t_prev <= t2, where t1 and t2 are the times at which
      the analytic hoop stress reaches f_t = 180 MPa at the depths of the
      centroids of the rim triangles (t1: the median depth of those with an
      edge on the rim; t2: the largest depth of those with only a vertex on
      it), measured on the run's mesh: a joint at the rim is loaded by
      constant-stress triangles, which carry the stress at their centroids;
  the broken joints start at the rim (the outermost one within 2 h of it);
  the heat balance closes to 1e-6."""
import numpy as np
from tutorial import arguments, prm, run, summary, check, pyplot, finish
from verify_discrete_thermal_cracking import history, series, rim_centroid_depths, broken_joints
import analytic

R, h_mesh, T0 = 6.5e-3, 0.8e-3, 500.0
E, alpha, f_t = 370e9, 7.5e-6, 180e6
kw = dict(radius=R, conductivity=35., diffusivity=35. / (3980 * 850.), h=3e4, t_ambient=15.)
args = arguments(__doc__)
ok = True
folder = f"{args.out}/quench"
run(args.tmfdem, prm("lesson-06-quench.prm"), folder)
hist = history(folder)
onset = np.nonzero(hist["damaged_joints"] > 0)[0]
ok &= check(len(onset) > 0, "joints damaged by 20 ms")
if len(onset) == 0:
    finish(False)
t_first = hist["time"][onset[0]]
t_prev = hist["time"][onset[0] - 1] if onset[0] > 0 else 0.
t_rim = analytic.quenched_disc_first_crack_time(f_t, E, alpha, t_initial=T0, **kw)
d1, d2 = rim_centroid_depths(series(folder, "solution")[0][1], R)
t1 = analytic.quenched_disc_hoop_stress_time(f_t, E, alpha, R - d1, t_initial=T0, **kw)
t2 = analytic.quenched_disc_hoop_stress_time(f_t, E, alpha, R - d2, t_initial=T0, **kw)
ok &= check(t_first >= t1 and t_prev <= t2,
            f"first damage in ({t_prev * 1e3:.2f}, {t_first * 1e3:.2f}] ms; the analytic hoop stress "
            f"reaches f_t at the rim at {t_rim * 1e3:.2f} ms, {d1 * 1e3:.3f} mm inside at "
            f"{t1 * 1e3:.2f} ms, {d2 * 1e3:.3f} mm inside at {t2 * 1e3:.2f} ms (first damage must "
            "fall in between)")
r, radial = broken_joints(series(folder, "cracks")[-1][1])
s = summary(folder)
ok &= check(len(r) > 0 and r.max() > R - 2 * h_mesh,
            f"{len(r)} broken joints in {s['cracks']} cracks at 20 ms, the outermost at r = "
            f"{(r.max() if len(r) else 0) * 1e3:.3f} mm (> R - 2 h = {(R - 2 * h_mesh) * 1e3:.1f} mm)")
rel = s["heat_balance"]["relative_imbalance"]
ok &= check(rel < 1e-6, f"heat balance {rel:.1e} (< 1e-6)")

if args.plot:
    from matplotlib.collections import PolyCollection, LineCollection
    from plot_vtu import read_vtu
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9.5, 4), gridspec_kw=dict(width_ratios=[1.3, 1]))
    times = np.linspace(2e-4, 0.04, 120)
    for depth, style, label in ((0, "k-", "rim"), (d1, "C0-", f"{d1 * 1e3:.2f} mm inside"),
                                (d2, "C1-", f"{d2 * 1e3:.2f} mm inside")):
        sig = [analytic.quenched_disc_hoop_stress(R - depth, t, E, alpha, t_initial=T0, **kw) for t in times]
        a1.plot(1e3 * times, np.array(sig) / 1e6, style, label=r"analytic $\sigma_\theta$, " + label)
    a1.axhline(f_t / 1e6, color="r", lw=0.8, label=r"$f_t$ = 180 MPa")
    a1.axvspan(1e3 * t1, 1e3 * t2, color="C0", alpha=0.12, label="analytic window")
    a1.axvspan(1e3 * t_prev, 1e3 * t_first, color="k", alpha=0.35, label="tmfdem: first damage")
    a1.set_xlabel("t [ms]")
    a1.set_ylabel(r"hoop stress [MPa]")
    a1.set_title(f"quench from {T0:.0f} C: when does the rim crack?")
    a1.legend(fontsize=7, loc="lower right")
    last = series(folder, "solution")[-1]
    pts, cells, T, point = read_vtu(last[1], "T")
    values = np.array([T[c].mean() for c in cells]) if point else T
    pc = PolyCollection([1e3 * pts[c] for c in cells], array=values, cmap="coolwarm", edgecolors="none")
    a2.add_collection(pc)
    fig.colorbar(pc, ax=a2, label="T [C]", shrink=0.8)
    cp, lines, _, _ = read_vtu(series(folder, "cracks")[-1][1], "break_time")
    a2.add_collection(LineCollection([1e3 * cp[l] for l in lines], colors="k", linewidths=2))
    a2.set_xlim(-7, 7)
    a2.set_ylim(-7, 7)
    a2.set_aspect("equal")
    a2.grid(False)
    a2.set_xlabel("x [mm]")
    a2.set_ylabel("y [mm]")
    a2.set_title(f"t = {last[0] * 1e3:.0f} ms: broken joints (black)")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
