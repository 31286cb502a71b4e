#!/usr/bin/python3
"""Tutorial lesson 3: plane stress against plane strain.

Runs doc/tutorial/prm/lesson-03-plane-strain.prm: the restrained sheet at
dT = +100 C in plane strain and plane stress for nu = 0.2 and 0.45, and the
free sheet (rollers on the left and bottom edges only) in plane strain for
nu = 0.311 (Table 3). Checks against the closed forms (small strain, tension
positive), relative errors < 1e-9 (the exact fields lie in the element
space: only the solver tolerance 1e-12 remains):
  restrained, plane stress: sigma_xx = sigma_yy = -E alpha dT / (1 - nu);
  restrained, plane strain: sigma_xx = sigma_yy = -E alpha dT / (1 - 2 nu)
      at the probes, and sigma_zz = nu (sigma_xx + sigma_yy) - E alpha dT
      = -E alpha dT / (1 - 2 nu) at every vertex of the vtu output;
      the ratio plane strain / plane stress = (1 - nu) / (1 - 2 nu);
  free, plane strain: eps_xx = eps_yy = (1 + nu) alpha dT, sigma_zz =
      -E alpha dT at every vertex, in-plane stress < 1e-9 E alpha dT."""
import os
import numpy as np
from tutorial import arguments, prm, run, summary, check, probes, pyplot, finish
from plot_vtu import read_vtu

E, alpha, dT = 75.1e9, 3e-6, 100.0
args = arguments(__doc__)
ok = True
restrained = {}


def szz_values(folder):
    return read_vtu(os.path.join(folder, "solution_00000.vtu"), "szz")[2]


for nu in (0.2, 0.45):
    for idealisation in ("plane stress", "plane strain"):
        folder = f"{args.out}/restrained_nu{nu}_{idealisation.replace(' ', '_')}"
        run(args.tmfdem, prm("lesson-03-plane-strain.prm"), folder,
            f"Materials/Material 0/Poisson's ratio={nu}", f"Mechanics/Idealisation={idealisation}")
        p = probes(folder)
        denominator = 1 - nu if idealisation == "plane stress" else 1 - 2 * nu
        exact = -E * alpha * dT / denominator
        err = max(abs(p[name][0][c] / exact - 1) for name in p for c in ("sxx", "syy"))
        ok &= check(err < 1e-9, f"restrained, nu = {nu}, {idealisation}: sigma_xx = "
                    f"{p['centre'][0]['sxx'] / 1e6:.6f} MPa vs {exact / 1e6:.6f} MPa, worst relative "
                    f"error {err:.1e} < 1e-9")
        restrained[(nu, idealisation)] = p["centre"][0]["sxx"]
        if idealisation == "plane strain":
            szz = szz_values(folder)
            err = np.abs(szz / exact - 1).max()
            ok &= check(err < 1e-9, f"restrained, nu = {nu}, plane strain: sigma_zz = {szz[0] / 1e6:.6f} MPa "
                        f"= sigma_xx (hydrostatic), worst relative error at {len(szz)} vertices {err:.1e} < 1e-9")
    ratio = restrained[(nu, "plane strain")] / restrained[(nu, "plane stress")]
    exact_ratio = (1 - nu) / (1 - 2 * nu)
    ok &= check(abs(ratio / exact_ratio - 1) < 1e-9, f"nu = {nu}: plane strain / plane stress = {ratio:.9f} "
                f"vs (1 - nu)/(1 - 2 nu) = {exact_ratio:.9f}")

nu = 0.311
folder = f"{args.out}/free_nu{nu}_plane_strain"
run(args.tmfdem, prm("lesson-03-plane-strain.prm"), folder, f"Materials/Material 0/Poisson's ratio={nu}",
    "Mechanical boundary conditions/Condition 1/Boundary ids=0",
    "Mechanical boundary conditions/Condition 2/Boundary ids=2")
p = probes(folder)
exact = (1 + nu) * alpha * dT
strains = [p["right"][0]["ux"] / 2, p["corner"][0]["ux"] / 2, p["top"][0]["uy"] / 2, p["corner"][0]["uy"] / 2]
err = max(abs(v / exact - 1) for v in strains)
ok &= check(err < 1e-9, f"free, nu = {nu}, plane strain: in-plane strain {strains[0]:.10e} vs (1 + nu) alpha dT "
            f"= {exact:.10e}, worst relative error {err:.1e} < 1e-9 (plane stress: alpha dT = {alpha * dT:.1e})")
szz = szz_values(folder)
err = np.abs(szz / (-E * alpha * dT) - 1).max()
ok &= check(err < 1e-9, f"free, nu = {nu}, plane strain: sigma_zz = {szz[0] / 1e6:.6f} MPa vs -E alpha dT = "
            f"{-E * alpha * dT / 1e6:.6f} MPa, worst relative error {err:.1e} < 1e-9")
st = summary(folder)["stress"]
largest = max(st["max_abs_sxx"], st["max_abs_syy"], st["max_abs_sxy"])
ok &= check(largest < 1e-9 * E * alpha * dT, f"free, nu = {nu}, plane strain: largest in-plane |stress| "
            f"{largest:.2e} Pa < 1e-9 E alpha dT = {1e-9 * E * alpha * dT:.2e} Pa")

if args.plot:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6))
    nus = np.linspace(0, 0.49, 200)
    a1.plot(nus, E * alpha * dT / (1 - nus) / 1e6, "C1-", label=r"plane stress: $E\alpha\Delta T/(1-\nu)$")
    a1.plot(nus, E * alpha * dT / (1 - 2 * nus) / 1e6, "C2-", label=r"plane strain: $E\alpha\Delta T/(1-2\nu)$")
    for (n, idealisation), s in restrained.items():
        a1.plot(n, -s / 1e6, "o", color="C1" if idealisation == "plane stress" else "C2")
    a1.plot([], [], "ko", label="tmfdem")
    a1.set_ylim(0, 250)
    a1.set_xlabel(r"Poisson's ratio $\nu$")
    a1.set_ylabel(r"$-\sigma_{xx}$ [MPa]")
    a1.set_title(r"restrained sheet, $\Delta T$ = 100 C")
    a1.legend(fontsize=8)
    a2.plot(nus, (1 - nus) / (1 - 2 * nus), "k-", label=r"$(1-\nu)/(1-2\nu)$")
    for n in (0.2, 0.45):
        a2.plot(n, restrained[(n, "plane strain")] / restrained[(n, "plane stress")], "ko")
    a2.plot(nus, 1 + nus, "k--", label=r"free sheet, in-plane strain: $(1+\nu)$")
    a2.plot(0.311, strains[0] / (alpha * dT), "ks")
    a2.set_ylim(0.9, 6)
    a2.set_xlabel(r"Poisson's ratio $\nu$")
    a2.set_ylabel("plane strain / plane stress")
    a2.set_title("how much plane strain adds")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
