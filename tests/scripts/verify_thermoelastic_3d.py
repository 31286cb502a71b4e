#!/usr/bin/python3
"""The continuum thermoelastic solver in 3D against closed forms (references
and bounds fixed before the runs; sigma tension positive):

free        prm/cube_thermal_stress.prm: a free cube under T = 20 + 1000 x
            C (stress-free at 20 C), on hexahedra (Q2) and on tetrahedra
            (P2). A linear temperature in a free body gives no stress and
            the compatible displacement u_x = alpha g (x^2 - y^2 - z^2) / 2,
            u_y = alpha g x y, u_z = alpha g x z, which both element spaces
            hold: max |sigma_ij| <= 1e-6 E alpha (T_max - T_ref) and
            max |u - u_exact| <= 1e-6 max |u_exact| on a diagonal and an
            edge (the solver's tolerances).
restrained  the same cube at a uniform T = 120 C with rollers on all six
            faces: sigma_xx = sigma_yy = sigma_zz = -E alpha dT / (1 - 2 nu),
            no shear, u = 0, to 1e-6 of that stress.
rotation    finite strain: every face driven to u = (s R(t) - I) X, R a
            rotation by 90 t degrees about (1, 1, 1) / sqrt(3), 10 load
            steps, at T = 120 C. With s = 1 + alpha dT (free expansion,
            rotated) the body is stress free: max |sigma_ij| <= 1e-6 E alpha
            dT; with s = 1 (restrained, rotated) the Cauchy stress is
            hydrostatic, mu theta^3 (theta^-2 - 1) + lambda / 2 (theta^-3 -
            theta^3), theta = 1 + alpha dT (Eq. 44 on F_e = R / theta), to
            1e-6 of itself, and u = (R - I) X to 1e-6 of max |u|.
sphere      prm/spherical_shell_stress.prm: steady conduction through the
            thick-walled sphere a = 0.03, b = 0.15 m (100 / 0 C, heat solver)
            and its thermal stress: sigma_r (= sxx) and sigma_t (= syy =
            szz) on the x axis within 1 % of max |sigma_t| of Timoshenko &
            Goodier's solution (the bound of the 2D cylinder, paper 5.4),
            |T - T_exact| <= 0.5 C.
cylinder    prm/thick_cylinder-3d.prm: the paper's 5.4 cylinder as a 3D
            slice with rollers on its end faces (hexahedra, Q3, heat solver):
            sigma_r, sigma_theta, sigma_zz on the x axis within 1 % of max
            |sigma_theta| of the plane-strain solution (-Eq. 49, sigma_zz =
            nu (sigma_r + sigma_theta) - E alpha T), and the polar frame's
            srr, stt about the axis on a diagonal at z = 0.005 m within the
            same bound, |u_z| <= 1e-9 m; and
            the cross-dimension check: the 3D stresses within 1 % of max
            |sigma_theta| of the 2D plane-strain run
            (prm/thick_cylinder-continuum.prm, its sigma_zz = nu (sigma_xx
            + sigma_yy) - E alpha T) at the same points.
amr         adaptive refinement of the displacement in 3D (Kelly, p4est
            hexahedra, hanging nodes on the cylinders): the same slice with
            the exact T(r) as a function, Q2, uniform rings; three steady
            cycles refining the cells with 30 % of the estimated error
            reduce max |sigma_r - plane strain| to at most half that of the
            unrefined mesh (Q2 stress error ~ h^2 where refined), and u_z
            stays 0 (<= 1e-9 m) across the hanging nodes.

Usage: verify_thermoelastic_3d.py TMFDEM PRM_FOLDER OUT [case ...]
"""
import math
import sys
import numpy as np
from common import run, summary, check
from analytic import (read_csv, read_csv_xyz, spherical_shell_stress, spherical_shell_temperature,
                      cylinder_stress, cylinder_temperature)

binary, prm_folder, out = sys.argv[1:4]
cases = sys.argv[4:] or ["free", "restrained", "rotation", "sphere", "cylinder", "amr"]
ok = True

# Table 3 rock of prm/cube_thermal_stress.prm
E, nu, alpha, T_ref = 75.1e9, 0.311, 3e-6, 20.0
mu = E / (2 * (1 + nu))
lam = E * nu / ((1 + nu) * (1 - 2 * nu))
cube = f"{prm_folder}/cube_thermal_stress.prm"
STRESS = ["sxx", "syy", "szz", "sxy", "syz", "sxz"]


def last(folder):
    """name -> (points, fields) at the last output time of lines.csv."""
    lines = read_csv_xyz(f"{folder}/lines.csv")
    return {name: by_time[max(by_time)] for name, by_time in lines.items()}


def max_stress(folder):
    return max(np.abs(f[c]).max() for _, f in last(folder).values() for c in STRESS)


def max_displacement_error(folder, exact):
    error, scale = 0.0, 0.0
    for points, f in last(folder).values():
        u = np.column_stack([f["ux"], f["uy"], f["uz"]])
        u_exact = exact(points)
        error = max(error, np.abs(u - u_exact).max())
        scale = max(scale, np.abs(u_exact).max())
    return error, scale


if "free" in cases:
    g = 1000.0
    bound = 1e-6 * E * alpha * g * 0.1

    def u_free(p):
        x, y, z = p.T
        return alpha * g * np.column_stack([(x**2 - y**2 - z**2) / 2, x * y, x * z])

    for element, label in (("quadrilaterals", "hexahedra Q2"), ("triangles", "tetrahedra P2")):
        folder = f"{out}/free_{element}"
        run(binary, cube, folder, f"Mesh/Element type={element}", "Output/Write vtu=false")
        s = max_stress(folder)
        ok &= check(s <= bound, f"free cube, {label}: max |sigma_ij| = {s:.3e} Pa <= {bound:.3e} Pa "
                                f"(1e-6 E alpha dT_max)")
        error, scale = max_displacement_error(folder, u_free)
        ok &= check(error <= 1e-6 * scale, f"free cube, {label}: max |u - u_exact| = {error:.3e} m "
                                           f"<= 1e-6 x {scale:.4e} m")
        principal = summary(folder)["stress"]
        ok &= check(max(abs(principal["max_principal"]), abs(principal["min_principal"])) <= bound,
                    f"free cube, {label}: summary principal stresses {principal['max_principal']:.3e}, "
                    f"{principal['min_principal']:.3e} Pa within the bound")

if "restrained" in cases:
    dT = 100.0
    expected = -E * alpha * dT / (1 - 2 * nu)
    folder = f"{out}/restrained"
    rollers = []
    for n, (ids, axis) in enumerate((("0, 1", "x"), ("2, 3", "y"), ("4, 5", "z")), start=1):
        rollers += [f"Mechanical boundary conditions/Condition {n}/Boundary ids={ids}",
                    f"Mechanical boundary conditions/Condition {n}/Type=roller {axis}"]
    run(binary, cube, folder, f"Mechanics/Temperature={T_ref + dT}", "Mechanics/Pinned points=",
        "Output/Write vtu=false", *rollers)
    error, u = 0.0, 0.0
    for points, f in last(folder).values():
        for c in ("sxx", "syy", "szz"):
            error = max(error, np.abs(f[c] - expected).max())
        for c in ("sxy", "syz", "sxz"):
            error = max(error, np.abs(f[c]).max())
        u = max([u] + [np.abs(f[c]).max() for c in ("ux", "uy", "uz")])
    ok &= check(error <= 1e-6 * abs(expected),
                f"restrained cube: max |sigma - (-E alpha dT / (1 - 2 nu))| = {error:.3e} Pa <= 1e-6 x "
                f"{abs(expected):.6e} Pa")
    ok &= check(u <= 1e-12, f"restrained cube: max |u| = {u:.2e} m (zero)")

if "rotation" in cases:
    dT = 100.0
    theta = 1 + alpha * dT
    # Rodrigues: R = c I + s [n]x + (1 - c) n n^T, n = (1, 1, 1) / sqrt(3),
    # angle pi / 2 t
    c = "cos(pi/2*t)"
    k = f"(1-{c})/3"
    q = "sin(pi/2*t)/sqrt(3)"
    R = [[f"({c}+{k})", f"({k}-{q})", f"({k}+{q})"],
         [f"({k}+{q})", f"({c}+{k})", f"({k}-{q})"],
         [f"({k}-{q})", f"({k}+{q})", f"({c}+{k})"]]

    def R_at(t):
        a = math.pi / 2 * t
        n = np.ones(3) / math.sqrt(3)
        K = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
        return math.cos(a) * np.eye(3) + math.sin(a) * K + (1 - math.cos(a)) * np.outer(n, n)

    for stretch, label in ((theta, "free expansion"), (1.0, "restrained")):
        X = ("x", "y", "z")
        u = [f"{stretch!r}*({R[i][0]}*x+{R[i][1]}*y+{R[i][2]}*z)-{X[i]}" for i in range(3)]
        folder = f"{out}/rotation_{'free' if stretch != 1.0 else 'restrained'}"
        settings = ["Mechanics/Strain measure=finite", f"Mechanics/Temperature={T_ref + dT}",
                    "Mechanics/Pinned points=", "Time stepping/Mode=transient",
                    "Time stepping/End time=1", "Time stepping/Time step=0.1",
                    "Output/Write vtu=false",
                    "Mechanical boundary conditions/Condition 1/Boundary ids=0, 1, 2, 3, 4, 5",
                    "Mechanical boundary conditions/Condition 1/Type=displacement"]
        settings += [f"Mechanical boundary conditions/Condition 1/Displacement {a}={e}"
                     for a, e in zip(X, u)]
        run(binary, cube, folder, *settings)
        final = R_at(1.0)
        error, scale = max_displacement_error(folder, lambda p: stretch * p @ final.T - p)
        ok &= check(error <= 1e-6 * scale, f"rotation, {label}: max |u - (s R - I) X| = {error:.3e} m "
                                           f"<= 1e-6 x {scale:.4f} m")
        if stretch != 1.0:
            s = max_stress(folder)
            ok &= check(s <= 1e-6 * E * alpha * dT,
                        f"rotation, {label}: max |sigma_ij| = {s:.3e} Pa <= 1e-6 E alpha dT")
        else:
            expected = mu * theta**3 * (theta**-2 - 1) + lam / 2 * (theta**-3 - theta**3)
            error = 0.0
            for points, f in last(folder).values():
                for comp in ("sxx", "syy", "szz"):
                    error = max(error, np.abs(f[comp] - expected).max())
                for comp in ("sxy", "syz", "sxz"):
                    error = max(error, np.abs(f[comp]).max())
            ok &= check(error <= 1e-6 * abs(expected),
                        f"rotation, {label}: max |sigma - hydrostatic {expected / 1e6:.4f} MPa| = "
                        f"{error:.3e} Pa <= 1e-6 of it")

if "sphere" in cases:
    a, b, t_a, t_b = 0.03, 0.15, 100.0, 0.0
    E_s, nu_s, alpha_s = 20e9, 0.2, 1.8e-5
    folder = f"{out}/sphere"
    run(binary, f"{prm_folder}/spherical_shell_stress.prm", folder, "Output/Write vtu=false")
    points, f = last(folder)["radial"]
    r = np.linalg.norm(points, axis=1)
    s_r, s_t = spherical_shell_stress(r, E_s, nu_s, alpha_s, a, b, t_a, t_b)
    scale = np.abs(s_t).max()
    err_r = np.abs(f["sxx"] - s_r).max() / scale
    err_t = max(np.abs(f["syy"] - s_t).max(), np.abs(f["szz"] - s_t).max()) / scale
    err_T = np.abs(f["T"] - spherical_shell_temperature(r, a, b, t_a, t_b)).max()
    s = summary(folder)
    print(f"  sigma_t(a) = {f['syy'][0] / 1e6:.4f} MPa (exact {s_t[0] / 1e6:.4f}), sigma_t(b) = "
          f"{f['syy'][-1] / 1e6:.4f} MPa (exact {s_t[-1] / 1e6:.4f}); {s['cells']} cells, {s['dofs']} DoFs")
    ok &= check(err_r < 0.01, f"sphere: max |sigma_r - exact| / max |sigma_t| = {err_r:.2e} < 1 %")
    ok &= check(err_t < 0.01, f"sphere: max |sigma_t - exact| / max |sigma_t| = {err_t:.2e} < 1 %")
    ok &= check(err_T < 0.5, f"sphere: max |T - T_exact| = {err_T:.3f} C < 0.5 C")
    ok &= check(s["idealisation"] == "3D" and s["model"] == "continuum thermoelastic",
                "sphere: summary names the model and the 3D idealisation")

if "cylinder" in cases:
    E_c, nu_c, alpha_c = 20e9, 0.2, 1.8e-5
    folder = f"{out}/cylinder"
    run(binary, f"{prm_folder}/thick_cylinder-3d.prm", folder, "Output/Write vtu=false")
    points, f = last(folder)["radial"]
    r = np.linalg.norm(points, axis=1)
    s_r, s_t = cylinder_stress(r, idealisation="plane strain")
    T_exact = cylinder_temperature(r)
    s_z = nu_c * (s_r + s_t) - E_c * alpha_c * T_exact
    scale = np.abs(s_t).max()
    errors = {name: np.abs(f[column] - exact).max() / scale
              for name, column, exact in (("sigma_r", "sxx", s_r), ("sigma_theta", "syy", s_t),
                                          ("sigma_zz", "szz", s_z))}
    s = summary(folder)
    print(f"  sigma_theta(a) = {f['syy'][0] / 1e6:.4f} MPa (exact {s_t[0] / 1e6:.4f}), sigma_zz(a) = "
          f"{f['szz'][0] / 1e6:.4f} MPa (exact {s_z[0] / 1e6:.4f}); {s['cells']} cells, {s['dofs']} DoFs")
    for name, error in errors.items():
        ok &= check(error < 0.01, f"cylinder 3D: max |{name} - plane strain| / max |sigma_theta| = "
                                  f"{error:.2e} < 1 %")
    err_T = np.abs(f["T"] - T_exact).max()
    ok &= check(err_T < 0.5, f"cylinder 3D: max |T - T_exact| = {err_T:.3f} C < 0.5 C")
    diagonal, fd = last(folder)["diagonal"]
    r_d = np.hypot(diagonal[:, 0], diagonal[:, 1])
    d_r, d_t = cylinder_stress(r_d, idealisation="plane strain")
    for name, column, exact in (("sigma_r", "srr", d_r), ("sigma_theta", "stt", d_t)):
        error = np.abs(fd[column] - exact).max() / scale
        ok &= check(error < 0.01, f"cylinder 3D, polar frame on the diagonal: max |{column} - {name}| / "
                                  f"max |sigma_theta| = {error:.2e} < 1 %")
    uz = np.abs(f["uz"]).max()
    ok &= check(uz <= 1e-9, f"cylinder 3D: max |u_z| = {uz:.2e} m (end rollers: plane strain)")
    # the 2D plane-strain model of the same cylinder at the same points
    folder_2d = f"{out}/cylinder_2d"
    run(binary, f"{prm_folder}/thick_cylinder-continuum.prm", folder_2d, "Output/Write vtu=false")
    data = read_csv(f"{folder_2d}/lines.csv")["radial"]
    x2, y2, f2 = data[max(data)]
    ok &= check(np.allclose(x2, points[:, 0]) and np.allclose(y2, points[:, 1]),
                "cylinder: the 2D and 3D lines sample the same points")
    # the 2D monitors hold the in-plane stresses; sigma_zz of plane strain
    # from them
    f2 = dict(f2, szz=nu_c * (np.array(f2["sxx"]) + np.array(f2["syy"])) -
              E_c * alpha_c * np.array(f2["T"]))
    for name, column in (("sigma_r", "sxx"), ("sigma_theta", "syy"), ("sigma_zz", "szz")):
        difference = np.abs(f[column] - np.array(f2[column])).max() / scale
        ok &= check(difference < 0.01, f"cylinder 3D vs 2D plane strain: max |{name} difference| / "
                                       f"max |sigma_theta| = {difference:.2e} < 1 %")

if "amr" in cases:
    errors = {}
    for adapt in ("false", "true"):
        folder = f"{out}/amr_{adapt}"
        run(binary, f"{prm_folder}/thick_cylinder-3d.prm", folder, "Output/Write vtu=false",
            "Mechanics/Temperature source=function",
            "Mechanics/Temperature=100*log(0.15/sqrt(x^2+y^2))/log(5)",
            "Mechanics/Polynomial degree=2", "Mesh/Radial grading=1",
            f"Adaptive refinement/Enable={adapt}", "Adaptive refinement/Steady cycles=3",
            "Adaptive refinement/Refine fraction=0.3", "Adaptive refinement/Coarsen fraction=0")
        points, f = last(folder)["radial"]
        s_r, s_t = cylinder_stress(np.linalg.norm(points, axis=1), idealisation="plane strain")
        errors[adapt] = (np.abs(f["sxx"] - s_r).max() / np.abs(s_t).max(), np.abs(f["uz"]).max(),
                         summary(folder)["dofs"])
    (uniform, _, dofs_uniform), (adapted, uz, dofs_adapted) = errors["false"], errors["true"]
    ok &= check(adapted <= 0.5 * uniform,
                f"amr: max |sigma_r - plane strain| / max |sigma_theta| {uniform:.2e} ({dofs_uniform} DoFs) -> "
                f"{adapted:.2e} ({dofs_adapted} DoFs) after two refinements: at most half")
    ok &= check(uz <= 1e-9, f"amr: max |u_z| = {uz:.2e} m on the adapted mesh (hanging nodes)")

sys.exit(0 if ok else 1)
