#!/usr/bin/python3
"""Tutorial lesson 4: the thick cylinder (paper 5.4), steady temperature and
its thermal stress, against the closed form.

Runs doc/tutorial/prm/lesson-04-thick-cylinder.prm in plane strain and in
plane stress and checks along the monitor line `radial` (121 points,
r = a ... b), references from the closed forms (tests/scripts/analytic.py,
Timoshenko and Goodier Sec. 151, tension positive):
  T: max |T - T_exact| < 0.5 C (design target of paper 5.4);
  sigma_r, sigma_theta: max error < 1 % of max |sigma_theta| (both
      idealisations);
  sigma_theta changes sign at the radius r0 of the closed form, to within
      1 % of b - a (linear interpolation between the line's points);
  plane strain / plane stress: both stresses are the same bracket times
      C = E alpha dT / (2 (1 - nu)) or E alpha dT / 2, so the ratio of the
      hoop stresses at the inner wall is 1 / (1 - nu) = 1.25, to 1 %."""
import numpy as np
from scipy.optimize import brentq
from tutorial import arguments, prm, run, summary, check, line_at_end, pyplot, finish
from analytic import cylinder_stress, cylinder_temperature

a, b, nu = 0.03, 0.15, 0.2
args = arguments(__doc__)
ok = True
results = {}
for idealisation in ("plane strain", "plane stress"):
    folder = f"{args.out}/{idealisation.replace(' ', '_')}"
    run(args.tmfdem, prm("lesson-04-thick-cylinder.prm"), folder, f"Mechanics/Idealisation={idealisation}")
    x, y, f = line_at_end(folder, "radial")
    r = np.hypot(x, y)
    s_r, s_t = cylinder_stress(r, idealisation=idealisation)
    scale = np.abs(s_t).max()
    err_T = np.abs(f["T"] - cylinder_temperature(r)).max()
    err_r = np.abs(f["srr"] - s_r).max() / scale
    err_t = np.abs(f["stt"] - s_t).max() / scale
    dofs = (summary(f"{folder}/heat")["dofs"], summary(folder)["dofs"])
    ok &= check(err_T < 0.5, f"{idealisation}: max |T - T_exact| = {err_T:.3f} C < 0.5 C ({dofs[0]} "
                f"temperature DoFs, {dofs[1]} displacement DoFs)")
    ok &= check(err_r < 0.01, f"{idealisation}: max |sigma_r - exact| = {100 * err_r:.3f} % of max "
                f"|sigma_theta| = {scale / 1e6:.3f} MPa (< 1 %)")
    ok &= check(err_t < 0.01, f"{idealisation}: max |sigma_theta - exact| = {100 * err_t:.3f} % of max "
                f"|sigma_theta| (< 1 %); sigma_theta(a) = {f['stt'][0] / 1e6:.3f} MPa (exact "
                f"{s_t[0] / 1e6:.3f}), sigma_theta(b) = {f['stt'][-1] / 1e6:.3f} MPa (exact {s_t[-1] / 1e6:.3f})")
    i = int(np.nonzero(np.diff(np.sign(f["stt"])))[0][0])
    r0 = r[i] - f["stt"][i] * (r[i + 1] - r[i]) / (f["stt"][i + 1] - f["stt"][i])
    r0_exact = brentq(lambda q: cylinder_stress([q], idealisation=idealisation)[1][0], a, b)
    ok &= check(abs(r0 - r0_exact) < 0.01 * (b - a), f"{idealisation}: sigma_theta = 0 at r = {1e3 * r0:.2f} mm "
                f"vs {1e3 * r0_exact:.2f} mm (within 1 % of b - a = {1e3 * 0.01 * (b - a):.1f} mm)")
    results[idealisation] = dict(r=r, f=f, dofs=dofs, s_r=s_r, s_t=s_t)
ratio = results["plane strain"]["f"]["stt"][0] / results["plane stress"]["f"]["stt"][0]
ok &= check(abs(ratio * (1 - nu) - 1) < 0.01, f"sigma_theta(a): plane strain / plane stress = {ratio:.4f} "
            f"vs 1 / (1 - nu) = {1 / (1 - nu):.4f} (within 1 %)")

if args.plot:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6))
    rr = np.linspace(a, b, 300)
    pe = results["plane strain"]
    a1.plot(1e3 * rr, cylinder_temperature(rr), "k-", label=r"$T_a \ln(b/r)/\ln(b/a)$")
    a1.plot(1e3 * pe["r"][::4], pe["f"]["T"][::4], "o", ms=3, color="C3", label="tmfdem (heat, AMR)")
    a1.set_xlabel("r [mm]")
    a1.set_ylabel("T [C]")
    a1.set_title(f"steady T: {pe['dofs'][0]} DoFs after 7 Kelly cycles")
    a1.legend()
    for k, idealisation in enumerate(("plane strain", "plane stress")):
        res = results[idealisation]
        sr, st = cylinder_stress(rr, idealisation=idealisation)
        ls = "-" if k == 0 else "--"
        a2.plot(1e3 * rr, st / 1e6, "C0" + ls, lw=1, label=rf"$\sigma_\theta$ exact, {idealisation}")
        a2.plot(1e3 * rr, sr / 1e6, "C1" + ls, lw=1, label=rf"$\sigma_r$ exact, {idealisation}")
        a2.plot(1e3 * res["r"][::4], res["f"]["stt"][::4] / 1e6, "o" if k == 0 else "s", ms=3, color="C0", mfc="none")
        a2.plot(1e3 * res["r"][::4], res["f"]["srr"][::4] / 1e6, "o" if k == 0 else "s", ms=3, color="C1", mfc="none")
    a2.plot([], [], "ko", ms=3, mfc="none", label="tmfdem")
    a2.axhline(0, color="k", lw=0.5)
    a2.set_xlabel("r [mm]")
    a2.set_ylabel("stress [MPa] (tension positive)")
    a2.set_title(f"thermal stress: Q3, {pe['dofs'][1]} DoFs, same mesh")
    a2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
