#!/usr/bin/python3
"""Tutorial lesson 1: free and restrained thermal expansion of a sheet.

Runs doc/tutorial/prm/lesson-01-free.prm at dT = +100 and -100 C and
doc/tutorial/prm/lesson-01-restrained.prm at dT = +100 C in plane stress and
in plane strain, and checks, with references fixed by the
closed forms (small strain, tension positive):
  free sheet:       eps_xx = eps_yy = alpha dT at every probe, relative
                    error < 1e-9 (the exact displacement is linear and lies
                    in the element space: only the solver tolerance 1e-12
                    remains); largest stress < 1e-9 E alpha |dT|;
  restrained sheet: sigma_xx = sigma_yy = -E alpha dT / (1 - nu) (plane
                    stress), -E alpha dT / (1 - 2 nu) (plane strain) at every
                    probe, relative error < 1e-9."""
from tutorial import arguments, prm, run, summary, check, probes, pyplot, finish

E, nu, alpha = 75.1e9, 0.311, 3e-6
args = arguments(__doc__)
ok = True
results = {"free": {}, "restrained": {}}

for dT in (100.0, -100.0):
    folder = f"{args.out}/free_dT{dT:+.0f}"
    run(args.tmfdem, prm("lesson-01-free.prm"), folder, f"Mechanics/Temperature={dT}")
    p = probes(folder)
    exact = alpha * dT
    # strain = u/x on the right edge, u/y on the top edge (rollers at x = 0, y = 0)
    strains = {"eps_xx (right, corner)": [p["right"][0]["ux"] / 2, p["corner"][0]["ux"] / 2],
               "eps_yy (top, corner)": [p["top"][0]["uy"] / 2, p["corner"][0]["uy"] / 2]}
    for name, values in strains.items():
        err = max(abs(v / exact - 1) for v in values)
        ok &= check(err < 1e-9, f"free, dT = {dT:+.0f} C: {name} = {values[0]:.10e} vs "
                    f"alpha dT = {exact:.10e}, relative error {err:.1e} < 1e-9")
    st = summary(folder)["stress"]
    largest = max(st["max_abs_sxx"], st["max_abs_syy"], st["max_abs_sxy"])
    bound = 1e-9 * E * alpha * abs(dT)
    ok &= check(largest < bound, f"free, dT = {dT:+.0f} C: largest |stress| {largest:.2e} Pa "
                f"< 1e-9 E alpha |dT| = {bound:.2e} Pa")
    results["free"][dT] = strains["eps_xx (right, corner)"][0]

for idealisation, dT in (("plane stress", 100.0), ("plane strain", 100.0)):
    tag = idealisation.replace(" ", "_")
    folder = f"{args.out}/restrained_{tag}_dT{dT:+.0f}"
    run(args.tmfdem, prm("lesson-01-restrained.prm"), folder, f"Mechanics/Temperature={dT}",
        f"Mechanics/Idealisation={idealisation}")
    p = probes(folder)
    denominator = 1 - nu if idealisation == "plane stress" else 1 - 2 * nu
    exact = -E * alpha * dT / denominator
    err = max(abs(p[name][0][c] / exact - 1) for name in p for c in ("sxx", "syy"))
    formula = "(1 - nu)" if idealisation == "plane stress" else "(1 - 2 nu)"
    ok &= check(err < 1e-9, f"restrained, {idealisation}, dT = {dT:+.0f} C: sigma_xx = "
                f"{p['centre'][0]['sxx'] / 1e6:.6f} MPa vs -E alpha dT / {formula} = "
                f"{exact / 1e6:.6f} MPa, worst relative error over 4 probes x 2 components "
                f"{err:.1e} < 1e-9")
    results["restrained"][(idealisation, dT)] = p["centre"][0]["sxx"]

if args.plot:
    import numpy as np
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6))
    dT = np.linspace(-120, 120, 2)
    a1.plot(dT, 1e6 * alpha * dT, "k-", label=r"free: $\alpha\,\Delta T$")
    a1.plot(dT, 0 * dT, "k--", label="restrained: 0")
    a1.plot(list(results["free"]), [1e6 * v for v in results["free"].values()], "o",
            color="C0", label="tmfdem, free sheet")
    a1.set_xlabel(r"$\Delta T$ [C]")
    a1.set_ylabel(r"$\varepsilon_{xx}$ [$10^{-6}$]")
    a1.set_title("strain")
    a1.legend()
    a2.plot(dT, -E * alpha * dT / (1 - nu) / 1e6, "C1-", label=r"$-E\alpha\Delta T/(1-\nu)$ (plane stress)")
    a2.plot(dT, -E * alpha * dT / (1 - 2 * nu) / 1e6, "C2-", label=r"$-E\alpha\Delta T/(1-2\nu)$ (plane strain)")
    a2.plot(dT, 0 * dT, "k--", label="free: 0")
    for (idealisation, t), s in results["restrained"].items():
        a2.plot(t, s / 1e6, "o", color="C1" if idealisation == "plane stress" else "C2")
    a2.set_xlabel(r"$\Delta T$ [C]")
    a2.set_ylabel(r"$\sigma_{xx} = \sigma_{yy}$ [MPa]")
    a2.set_title("stress (dots: tmfdem, restrained sheet)")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
