#!/usr/bin/python3
"""Plot a case's computed line samples against its analytic reference.

    plot_case.py CASE OUTPUT_FOLDER PNG

Reads OUTPUT_FOLDER/lines.csv (header time,name,x,y,<fields>, or
time,name,x,y,z,<fields> for 3D runs; one row per sample point per output
time), evaluates the reference from
tests/scripts/analytic.py on the same points, and draws two panels: the
field (computed as markers, reference as lines, one colour per time or per
field) and the error. The max abs error is printed as a table. To add a
case, add an entry to CASES; `fields` lists (column, reference, label,
scale) for cases other than temperature. 3D cases (dim=3) get the n x 3
array of points as the first argument of reference and abscissa and None
as the second.
"""
import os
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "scripts"))
sys.dont_write_bytecode = True  # keep tests/scripts free of __pycache__
import analytic  # noqa: E402

def shell_stress(p):
    """(sigma_r, sigma_t) of prm/spherical_shell_stress.prm at points p."""
    return analytic.spherical_shell_stress(np.linalg.norm(p, axis=1), 20e9, 0.2, 1.8e-5,
                                           0.03, 0.15, 100.0, 0.0)


def cylinder_plane_strain(p):
    """(sigma_r, sigma_theta, sigma_zz) of the 5.4 cylinder in plane strain at points p."""
    r = np.linalg.norm(p, axis=1)
    s_r, s_t = analytic.cylinder_stress(r)
    return s_r, s_t, 0.2 * (s_r + s_t) - 20e9 * 1.8e-5 * analytic.cylinder_temperature(r)


# case -> line in lines.csv, reference T(x, y, t), abscissa s(x, y) and its label,
# steady (plot one curve, no "t = " labels) or transient (skip t = 0, the initial state)
CASES = {
    "plate_transient-continuum": dict(
        line="midline",
        reference=lambda x, y, t: analytic.plate_transient(x, t),
        abscissa=lambda x, y: x, xlabel="x [m]",
        steady=False,
        title="Plate, transient conduction: midline y = 0.125"),
    "thick_cylinder-continuum": dict(
        line="radial",
        reference=lambda x, y, t: analytic.cylinder_temperature(np.hypot(x, y)),
        abscissa=lambda x, y: np.hypot(x, y), xlabel="r [m]",
        steady=True,
        title="Thick cylinder, steady conduction: radial line"),
    # thermoelastic cases: stresses in MPa (scale 1e-6)
    "thick_cylinder_stress-continuum": dict(
        line="radial",
        fields=[("srr", lambda x, y, t: analytic.cylinder_stress(np.hypot(x, y))[0], "sigma_r", 1e-6),
                ("stt", lambda x, y, t: analytic.cylinder_stress(np.hypot(x, y))[1], "sigma_theta", 1e-6)],
        unit="MPa",
        abscissa=lambda x, y: np.hypot(x, y), xlabel="r [m]",
        steady=True,
        title="Thick cylinder, steady thermal stress (plane strain, tension +)"),
    "sheet_free_expansion-continuum": dict(
        line="diagonal",
        fields=[("ux", lambda x, y, t: 3e-6 * 100 * x, "u_x", 1e3),
                ("uy", lambda x, y, t: 3e-6 * 100 * y, "u_y", 1e3),
                ("sxx", lambda x, y, t: 0 * x, "sigma_xx in mPa (1e-3 Pa)", 1e3)],
        unit="mm",
        abscissa=lambda x, y: np.hypot(x, y), xlabel="distance along the diagonal [m]",
        steady=True,
        title="Free sheet, dT = 100 C (plane stress): u = alpha dT x, no stress"),
    "sheet_restrained_expansion-continuum": dict(
        line="diagonal",
        fields=[("sxx", lambda x, y, t: -75.1e9 * 3e-6 * 100 / (1 - 0.311) + 0 * x, "sigma_xx", 1e-6),
                ("syy", lambda x, y, t: -75.1e9 * 3e-6 * 100 / (1 - 0.311) + 0 * x, "sigma_yy", 1e-6)],
        unit="MPa",
        abscissa=lambda x, y: np.hypot(x, y), xlabel="distance along the diagonal [m]",
        steady=True,
        title="Restrained sheet, dT = 100 C (plane stress): -E alpha dT / (1 - nu)"),
    # 3D cases: p is the n x 3 array of sample points
    "sphere_quench": dict(
        dim=3,
        line="radius",
        reference=lambda p, _, t: analytic.sphere_quench(
            np.linalg.norm(p, axis=1), t, 0.05, 3.0 / (2700 * 900), 100.0, 0.0),
        abscissa=lambda p, _: np.linalg.norm(p, axis=1), xlabel="r [m]",
        steady=False,
        title="Sphere quenched at its surface (3D): radius along x"),
    "spherical_shell_steady": dict(
        dim=3,
        line="radial",
        reference=lambda p, _, t: analytic.spherical_shell_temperature(
            np.linalg.norm(p, axis=1), 0.03, 0.15, 100.0, 0.0),
        abscissa=lambda p, _: np.linalg.norm(p, axis=1), xlabel="r [m]",
        steady=True,
        title="Thick-walled sphere, steady conduction (3D): radial line"),
    "spherical_shell_stress": dict(
        dim=3,
        line="radial",
        fields=[("sxx", lambda p, _, t: shell_stress(p)[0], "sigma_r (sxx on the x axis)", 1e-6),
                ("syy", lambda p, _, t: shell_stress(p)[1], "sigma_t (syy)", 1e-6),
                ("szz", lambda p, _, t: shell_stress(p)[1], "sigma_t (szz)", 1e-6)],
        unit="MPa",
        abscissa=lambda p, _: np.linalg.norm(p, axis=1), xlabel="r [m]",
        steady=True,
        title="Thick-walled sphere, steady thermal stress (3D, tension +)"),
    "thick_cylinder-3d": dict(
        dim=3,
        line="radial",
        fields=[("sxx", lambda p, _, t: cylinder_plane_strain(p)[0], "sigma_r (sxx)", 1e-6),
                ("syy", lambda p, _, t: cylinder_plane_strain(p)[1], "sigma_theta (syy)", 1e-6),
                ("szz", lambda p, _, t: cylinder_plane_strain(p)[2], "sigma_zz (szz)", 1e-6)],
        unit="MPa",
        abscissa=lambda p, _: np.linalg.norm(p, axis=1), xlabel="r [m]",
        steady=True,
        title="Thick cylinder in 3D, end rollers: plane strain (tension +)"),
    "cube_thermal_stress": dict(
        dim=3,
        line="diagonal",
        fields=[("ux", lambda p, _, t: 3e-6 * 1000 * (p[:, 0]**2 - p[:, 1]**2 - p[:, 2]**2) / 2,
                 "u_x [um]", 1e6),
                ("uy", lambda p, _, t: 3e-6 * 1000 * p[:, 0] * p[:, 1], "u_y [um]", 1e6),
                ("uz", lambda p, _, t: 3e-6 * 1000 * p[:, 0] * p[:, 2], "u_z [um]", 1e6),
                ("sxx", lambda p, _, t: 0 * p[:, 0], "sigma_xx [Pa]", 1.0)],
        unit="um, Pa",
        abscissa=lambda p, _: np.linalg.norm(p, axis=1), xlabel="distance along the diagonal [m]",
        steady=True,
        title="Free cube, T = 20 + 1000 x C (3D): compatible u, no stress"),
    "plate_transient-3d": dict(
        dim=3,
        line="corner line",
        reference=lambda p, _, t: analytic.plate_transient(p[:, 0], t),
        abscissa=lambda p, _: p[:, 0], xlabel="x [m]",
        steady=False,
        title="Slab (the 5.1 plate extruded, tetrahedra): edge y = 0, z = 0.25"),
}


def read_lines(folder, spec):
    """lines.csv as dict name -> time -> (x, y, cols); in 3D x is the
    n x 3 array of points and y None."""
    path = os.path.join(folder, "lines.csv")
    if spec.get("dim", 2) == 3:
        return {name: {t: (p, None, cols) for t, (p, cols) in by_time.items()}
                for name, by_time in analytic.read_csv_xyz(path).items()}
    return analytic.read_csv(path)


def plot_fields(case, spec, by_time, png):
    """Steady multi-field plot: each field computed (markers) against its
    reference (line), and the errors."""
    t = max(by_time)
    x, y, cols = by_time[t]
    s = spec["abscissa"](x, y)
    order = np.argsort(s)
    fig, (ax_f, ax_e) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, dpi=150,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    colours = plt.cm.viridis(np.linspace(0, 0.8, len(spec["fields"])))
    print(f"{case}: line '{spec['line']}', t = {t:g} s")
    print(f"{'field':>8} {'points':>7} {'max |computed - exact|':>24} [{spec['unit']}]")
    for (column, reference, label, scale), c in zip(spec["fields"], colours):
        computed = cols[column][order] * scale
        exact = reference(x, y, t)[order] * scale
        err = computed - exact
        print(f"{column:>8} {len(s):>7d} {np.max(np.abs(err)):>24.4g}")
        ax_f.plot(s[order], exact, "-", color=c, lw=1.2)
        ax_f.plot(s[order], computed, "o", color=c, ms=3, mfc="none",
                  label=f"{label} (max err {np.max(np.abs(err)):.3g} {spec['unit']})")
        ax_e.plot(s[order], err, "o-", color=c, ms=2, lw=0.8)
    ax_f.plot([], [], "-", color="gray", label="analytic")
    ax_f.set_ylabel(spec["unit"])
    ax_f.set_title(spec["title"])
    ax_f.legend(fontsize=8)
    ax_f.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_xlabel(spec["xlabel"])
    ax_e.set_ylabel(f"computed - exact [{spec['unit']}]")
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in CASES:
        sys.exit(f"usage: {os.path.basename(sys.argv[0])} CASE OUTPUT_FOLDER PNG\n"
                 f"  CASE: {', '.join(CASES)}")
    case, folder, png = sys.argv[1:]
    spec = CASES[case]
    data = read_lines(folder, spec)
    if spec["line"] not in data:
        sys.exit(f"{folder}/lines.csv: no line '{spec['line']}' (have: {', '.join(data)})")
    by_time = data[spec["line"]]
    if "fields" in spec:
        plot_fields(case, spec, by_time, png)
        return
    times = sorted(by_time)
    if spec["steady"]:
        times = times[-1:]
    else:
        times = [t for t in times if t > 0]

    fig, (ax_t, ax_e) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, dpi=150,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(times)))
    print(f"{case}: line '{spec['line']}'")
    print(f"{'time [s]':>10} {'points':>7} {'max |T - T_exact| [C]':>22}")
    for t, c in zip(times, colours):
        x, y, cols = by_time[t]
        s = spec["abscissa"](x, y)
        order = np.argsort(s)
        s, T, T_exact = s[order], cols["T"][order], spec["reference"](x, y, t)[order]
        err = T - T_exact
        max_err = np.max(np.abs(err))
        print(f"{t:>10g} {len(s):>7d} {max_err:>22.4g}")
        label = "computed" if spec["steady"] else f"t = {t:g} s"
        label += f" (max err {max_err:.3g} C)"
        ax_t.plot(s, T_exact, "-", color=c, lw=1.2)
        ax_t.plot(s, T, "o", color=c, ms=3, mfc="none", label=label)
        ax_e.plot(s, err, "o-", color=c, ms=2, lw=0.8)
    ax_t.plot([], [], "-", color="gray", label="analytic")
    ax_t.set_ylabel("T [C]")
    ax_t.set_title(spec["title"])
    ax_t.legend(fontsize=8)
    ax_t.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_xlabel(spec["xlabel"])
    ax_e.set_ylabel("T - T_exact [C]")
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
