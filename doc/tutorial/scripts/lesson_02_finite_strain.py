#!/usr/bin/python3
"""Tutorial lesson 2: small against finite strain at growing alpha dT.

Runs doc/tutorial/prm/lesson-02-finite-sheet.prm (restrained sheet, plane
stress, s = alpha dT = 2e-4 ... 0.2 in 13 load steps) with finite and with
small strain, for nu = 0.2 and nu = 0.311 (Table 3), and checks against the
closed forms (doc/theory.md 3.5, 3.6), tension positive, s = alpha dT:
  finite: sigma_f = mu (1 - (1 + s)^2) + (lambda/2) ((1 + s)^-2 - (1 + s)^2),
          relative error < 1e-8 at every s (the exact u = 0 is in the element
          space; Newton tolerance 1e-10);
  small:  sigma_s = -2 (lambda + mu) s, relative error < 1e-9;
  the relative difference d = sigma_f / sigma_s - 1 against its closed form
          to 1e-6 of itself + 1e-10 (the csv's 12 significant digits);
  d / s at the smallest s against the leading term
          (mu - lambda) / (2 (lambda + mu)) within 1 % (the next term,
          lambda s / (lambda + mu), is below 0.4 % of it there);
  where they part: the s at which d = 1 %, interpolated (log-log) between
          the measured load steps, within 2 % of the root of the closed form
          (the interpolation itself is good to 0.2 %)."""
import numpy as np
from scipy.optimize import brentq
from tutorial import arguments, prm, run, check, probes, pyplot, finish
from analytic import in_plane_constants

E, alpha = 75.1e9, 1e-3
args = arguments(__doc__)
ok = True


def closed_form(s, nu, finite):
    lam, mu, _ = in_plane_constants(E, nu, "plane stress")
    if finite:
        return mu * (1 - (1 + s)**2) + 0.5 * lam * ((1 + s)**-2 - (1 + s)**2)
    return -2 * (lam + mu) * s


def d_exact(s, nu):
    return closed_form(s, nu, True) / closed_form(s, nu, False) - 1


results = {}
for nu in (0.2, 0.311):
    lam, mu, _ = in_plane_constants(E, nu, "plane stress")
    sigma = {}
    for measure in ("finite", "small"):
        folder = f"{args.out}/nu{nu}_{measure}"
        run(args.tmfdem, prm("lesson-02-finite-sheet.prm"), folder,
            f"Materials/Material 0/Poisson's ratio={nu}", f"Mechanics/Strain measure={measure}")
        p = probes(folder)
        times = sorted(p["centre"])
        s = np.array([alpha * 200 * 10**((t - 6) / 2) for t in times])
        values = {name: np.array([p[name][t][c] for t in times]) for name in p for c in ("sxx", "syy")}
        exact = closed_form(s, nu, measure == "finite")
        err = max(np.abs(v / exact - 1).max() for v in values.values())
        bound = 1e-8 if measure == "finite" else 1e-9
        label = "Eq. 44 on F_e" if measure == "finite" else "-2 (lambda + mu) s"
        ok &= check(err < bound, f"nu = {nu}, {measure} strain: sigma_xx, sigma_yy at {len(times)} "
                    f"load steps s = {s[0]:.1e} ... {s[-1]:.2f} against {label}: worst relative "
                    f"error {err:.1e} < {bound:.0e}")
        sigma[measure] = p["centre"]
    d = np.array([sigma["finite"][t]["sxx"] / sigma["small"][t]["sxx"] - 1 for t in times])
    de = d_exact(s, nu)
    err = np.abs(d - de) / (1e-6 * np.abs(de) + 1e-10)
    ok &= check(err.max() < 1, f"nu = {nu}: d = sigma_f / sigma_s - 1 matches its closed form at every "
                f"s (worst |d - d_exact| = {np.abs(d - de).max():.1e}; d = {d[0]:.3e} at s = {s[0]:.0e}, "
                f"{d[-1]:.4f} at s = {s[-1]:.1f})")
    leading = (mu - lam) / (2 * (lam + mu))
    ok &= check(abs(d[0] / s[0] / leading - 1) < 0.01,
                f"nu = {nu}: d / s = {d[0] / s[0]:.5f} at s = {s[0]:.0e} vs leading term "
                f"(mu - lambda) / (2 (lambda + mu)) = {leading:.5f} (within 1 %)")
    i = int(np.nonzero(np.abs(d) >= 0.01)[0][0])
    s_part = float(np.exp(np.interp(np.log(0.01), np.log(np.abs(d[i - 1:i + 1])), np.log(s[i - 1:i + 1]))))
    s_root = brentq(lambda x: d_exact(x, nu) - 0.01, 1e-4, 0.5)
    ok &= check(abs(s_part / s_root - 1) < 0.02,
                f"nu = {nu}: small and finite strain part by 1 % at s = {s_part:.4f} (load steps) "
                f"vs {s_root:.4f} (closed form), within 2 %")
    results[nu] = dict(s=s, d=d, finite=np.array([sigma["finite"][t]["sxx"] for t in times]),
                       small=np.array([sigma["small"][t]["sxx"] for t in times]),
                       leading=leading, s_root=s_root, lam=lam, mu=mu)

if args.plot:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
    ss = np.geomspace(1e-4, 0.3, 200)
    for k, (nu, r) in enumerate(results.items()):
        col = f"C{k}"
        a1.plot(r["s"], -r["finite"] / 1e9, "o", color=col, label=f"finite, nu = {nu}")
        a1.plot(r["s"], -r["small"] / 1e9, "x", color=col, label=f"small, nu = {nu}")
        sl = np.linspace(0, 0.21, 50)
        a1.plot(sl, -closed_form(sl, nu, True) / 1e9, "-", color=col, lw=0.8)
        a1.plot(sl, -closed_form(sl, nu, False) / 1e9, "--", color=col, lw=0.8)
        a2.loglog(r["s"], r["d"], "o", color=col, label=f"tmfdem, nu = {nu}")
        a2.loglog(ss, d_exact(ss, nu), "-", color=col, lw=0.8, label="closed form")
        a2.loglog(ss, r["leading"] * ss, ":", color=col, lw=0.8,
                  label=r"$(\mu-\lambda)s/(2(\lambda+\mu))$")
        a2.axvline(r["s_root"], color=col, lw=0.6, ls="--")
    a1.set_xlim(0, 0.21)
    a1.set_xlabel(r"$s = \alpha\,\Delta T$")
    a1.set_ylabel(r"$-\sigma_{xx}$ [GPa]")
    a1.set_title("restrained sheet, plane stress")
    a1.legend(fontsize=7)
    a2.axhline(0.01, color="k", lw=0.6)
    a2.set_xlabel(r"$s = \alpha\,\Delta T$")
    a2.set_ylabel(r"$d = \sigma_{finite}/\sigma_{small} - 1$")
    a2.set_title("relative difference (dashed: s where d = 1 %)")
    a2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
