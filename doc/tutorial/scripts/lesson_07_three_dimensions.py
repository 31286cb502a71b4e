#!/usr/bin/python3
"""Tutorial lesson 7: three dimensions, and what the 2D idealisations stand
for.

Runs doc/tutorial/prm/lesson-07-cube.prm and lesson-07-disc.prm in 3D
(Mesh/Dimension = 3, Mechanics/Idealisation = 3D). Checks (small strain,
tension positive; references and bounds from the physics):
  cube, rollers on all six faces, dT = 100 C: sigma_xx = sigma_yy =
      sigma_zz = -E alpha dT / (1 - 2 nu), the 2D plane-strain value of
      the restrained sheet (lesson 3), relative error < 1e-9 at every probe
      (the exact field, u = 0, lies in the element space);
  cube, top face free: sigma_xx = sigma_yy = -E alpha dT / (1 - nu), the
      plane-stress value, sigma_zz = 0 (< 1e-9 E alpha dT), and the top
      rises by (1 + nu) / (1 - nu) alpha dT (relative error < 1e-9);
  the lesson-4 cylinder as a disc of thickness t (faces free, half the
      disc with its mid-plane on rollers), hoop stress sigma_theta = syy on
      the mid-plane along x, against the 2D solutions (Timoshenko and
      Goodier Sec. 151, analytic.cylinder_stress):
      t = 5 mm (t / (b - a) = 1/24): within 1 % of max |sigma_theta| of
          plane stress;
      t = 20 mm: further from plane stress than the 5 mm disc, and closer
          to plane stress than to plane strain (a disc, not yet a cylinder);
      t = 20 mm with both faces on rollers: within 1 % of plane strain;
      sigma_zz on the mid-plane of the 5 mm disc below 1 % of max
          |sigma_theta| (plane stress: 0)."""
import os
import numpy as np
from tutorial import arguments, prm, run, summary, check, pyplot, finish
from analytic import read_csv_xyz, cylinder_stress

args = arguments(__doc__)
ok = True

# ------------------------------------------------------------ the cube
E, nu, alpha, dT = 75.1e9, 0.311, 3e-6, 100.0


def cube_probes(folder):
    data = read_csv_xyz(os.path.join(folder, "probes.csv"))
    return {name: by_time[max(by_time)][1] for name, by_time in data.items()}


folder = f"{args.out}/cube_restrained"
run(args.tmfdem, prm("lesson-07-cube.prm"), folder)
p = cube_probes(folder)
exact = -E * alpha * dT / (1 - 2 * nu)
err = max(abs(p[name][c][0] / exact - 1) for name in p for c in ("sxx", "syy", "szz"))
ok &= check(err < 1e-9, f"cube on six rollers: sigma_xx = sigma_yy = sigma_zz = {p['centre']['sxx'][0] / 1e6:.6f} "
            f"MPa vs -E alpha dT / (1 - 2 nu) = {exact / 1e6:.6f} MPa (2D plane strain), worst relative error "
            f"{err:.1e} < 1e-9")
restrained_3d = p["centre"]["sxx"][0]

folder = f"{args.out}/cube_top_free"
run(args.tmfdem, prm("lesson-07-cube.prm"), folder, "Mechanical boundary conditions/Condition 3/Boundary ids=4")
p = cube_probes(folder)
exact = -E * alpha * dT / (1 - nu)
err = max(abs(p[name][c][0] / exact - 1) for name in p for c in ("sxx", "syy"))
ok &= check(err < 1e-9, f"cube, top free: sigma_xx = sigma_yy = {p['centre']['sxx'][0] / 1e6:.6f} MPa vs "
            f"-E alpha dT / (1 - nu) = {exact / 1e6:.6f} MPa (2D plane stress), worst relative error {err:.1e} < 1e-9")
szz = max(abs(p[name]["szz"][0]) for name in p)
ok &= check(szz < 1e-9 * E * alpha * dT, f"cube, top free: max |sigma_zz| = {szz:.2e} Pa < 1e-9 E alpha dT")
rise = (1 + nu) / (1 - nu) * alpha * dT
err = abs(p["top"]["uz"][0] / rise - 1)
ok &= check(err < 1e-9, f"cube, top free: the top rises by {p['top']['uz'][0] * 1e6:.4f} um vs (1 + nu)/(1 - nu) "
            f"alpha dT x 1 m = {rise * 1e6:.4f} um, relative error {err:.1e} < 1e-9")

# ------------------------------------------------------------ the disc
runs = {"5 mm, faces free": ("thin", []),
        "20 mm, faces free": ("thick", ["Mesh/Length=0.01", "Mesh/Center=0, 0, 0.005"]),
        "20 mm, faces on rollers": ("rollers", ["Mesh/Length=0.01", "Mesh/Center=0, 0, 0.005",
                                                "Mechanical boundary conditions/Condition 1/Boundary ids=2, 3"])}
profiles = {}
for label, (tag, settings) in runs.items():
    folder = f"{args.out}/disc_{tag}"
    run(args.tmfdem, prm("lesson-07-disc.prm"), folder, *settings)
    data = read_csv_xyz(os.path.join(folder, "lines.csv"))["radial"]
    points, fields = data[max(data)]
    profiles[label] = (np.linalg.norm(points, axis=1), fields)

r = profiles["5 mm, faces free"][0]
plane_stress = cylinder_stress(r, idealisation="plane stress")[1]
plane_strain = cylinder_stress(r, idealisation="plane strain")[1]
scale = np.abs(plane_strain).max()


def distance(label, reference):
    return np.abs(profiles[label][1]["syy"] - reference).max() / scale


thin_ps = distance("5 mm, faces free", plane_stress)
ok &= check(thin_ps < 0.01, f"5 mm disc: sigma_theta within {thin_ps:.2e} of max |sigma_theta| of plane stress "
            f"(< 1 %); sigma_theta(a) = {profiles['5 mm, faces free'][1]['syy'][0] / 1e6:.3f} MPa vs "
            f"{plane_stress[0] / 1e6:.3f} MPa")
szz = np.abs(profiles["5 mm, faces free"][1]["szz"]).max() / scale
ok &= check(szz < 0.01, f"5 mm disc: max |sigma_zz| on the mid-plane = {szz:.2e} of max |sigma_theta| (< 1 %)")
thick_ps = distance("20 mm, faces free", plane_stress)
thick_pe = distance("20 mm, faces free", plane_strain)
ok &= check(thin_ps < thick_ps < thick_pe, f"20 mm disc: {thick_ps:.2e} from plane stress (the 5 mm disc "
            f"{thin_ps:.2e}), {thick_pe:.2e} from plane strain: a thicker disc, still nearer plane stress")
rollers_pe = distance("20 mm, faces on rollers", plane_strain)
ok &= check(rollers_pe < 0.01, f"20 mm disc on rollers: sigma_theta within {rollers_pe:.2e} of max |sigma_theta| "
            f"of plane strain (< 1 %); sigma_theta(a) = {profiles['20 mm, faces on rollers'][1]['syy'][0] / 1e6:.3f} "
            f"MPa vs {plane_strain[0] / 1e6:.3f} MPa")

if args.plot:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
    rr = np.linspace(0.03, 0.15, 200)
    a1.plot(rr, cylinder_stress(rr, idealisation="plane stress")[1] / 1e6, "C1-", label="2D plane stress")
    a1.plot(rr, cylinder_stress(rr, idealisation="plane strain")[1] / 1e6, "C2-", label="2D plane strain")
    for (label, (rp, fields)), marker in zip(profiles.items(), ("o", "s", "^")):
        a1.plot(rp[::6], fields["syy"][::6] / 1e6, marker, color="k", mfc="none", ms=4, label=f"3D: {label}")
    a1.set_xlabel("r [m]")
    a1.set_ylabel(r"$\sigma_\theta$ on the mid-plane [MPa]")
    a1.set_title("thick cylinder as a 3D disc")
    a1.legend(fontsize=7)
    a2.set_xlim(0.03, 0.06)
    for (label, (rp, fields)), marker in zip(profiles.items(), ("o", "s", "^")):
        a2.plot(rp, fields["syy"] / 1e6, marker + "-", color="k", mfc="none", ms=3, lw=0.6, label=f"3D: {label}")
    a2.plot(rr, cylinder_stress(rr, idealisation="plane stress")[1] / 1e6, "C1-")
    a2.plot(rr, cylinder_stress(rr, idealisation="plane strain")[1] / 1e6, "C2-")
    a2.set_ylim(-34, -10)
    a2.set_xlabel("r [m]")
    a2.set_title("near the hot inner wall")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
