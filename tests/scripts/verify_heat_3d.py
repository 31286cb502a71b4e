#!/usr/bin/python3
"""The continuum heat solver in 3D against closed forms (references and
bounds fixed before the runs):

sphere   prm/sphere_quench.prm (hexahedra, Q2, Crank-Nicolson): max
         |T - T_exact| along a radius and a diagonal <= 0.5 C (0.5 % of the
         100 C drop) at t = 100, 300, 600 s against the Carslaw-Jaeger
         series; the heat that left by 600 s within 1 % of rho c V (T0 -
         Ts) (1 - 6/pi^2 sum exp(-n^2 pi^2 Fo) / n^2); heat balance closed
         to 1e-8.
shell    prm/spherical_shell_steady.prm (hexahedra, Q2, steady): max
         |T - T_exact| along a radius and a diagonal <= 0.5 C; the heat
         flow through each surface within 1 % of 4 pi k dT / (1/a - 1/b).
slab     prm/plate_transient-3d.prm (tetrahedra, P2): the paper's 5.1
         plate extruded to a slab; max |T - T_exact| <= 0.5 C (the paper's
         target) along the centre line and along an edge of the slab at
         t = 2, 10, 20 s; then the same slab on hexahedra with transient
         Kelly refinement and coarsening (p4est, one level) to 10 s, same
         bound, heat balance to 1e-5 (the solution transfer).
file     tests/data/cube_tetrahedra.msh (a gmsh unit cube of tetrahedra,
         physical surfaces 1: x = 0, 2: x = 1, 3: the rest), steady, P1,
         0 C at x = 0 and 100 C at x = 1: T = 100 x lies in the P1 space,
         so |T - 100 x| <= 1e-6 C on a diagonal (the solver's tolerance);
         the heat flow through x = 1 within 1e-6 of k 100 C / 1 m x 1 m^2.

Usage: verify_heat_3d.py TMFDEM PRM_FOLDER OUT [sphere|shell|slab|file ...]
"""
import sys
import numpy as np
from common import run, summary, check
from analytic import (read_csv_xyz, sphere_quench, sphere_quench_heat_lost,
                      spherical_shell_temperature, spherical_shell_heat_flow,
                      plate_transient)

binary, prm_folder, out = sys.argv[1:4]
cases = sys.argv[4:] or ["sphere", "shell", "slab", "file"]
ok = True


def profile_errors(folder, times, exact, limit, label):
    """max |T - exact(points, t)| <= limit on every line at every time."""
    passed = True
    lines = read_csv_xyz(f"{folder}/lines.csv")
    for name, by_time in sorted(lines.items()):
        for t in times:
            points, fields = by_time[t]
            error = np.abs(fields["T"] - exact(points, t)).max()
            passed &= check(error <= limit,
                            f"{label}line '{name}', t = {t:g} s: max |T - T_exact| = "
                            f"{error:.4f} C <= {limit} C")
    return passed


if "sphere" in cases:
    R, k, rho, c, T0, Ts = 0.05, 3.0, 2700.0, 900.0, 100.0, 0.0
    kappa = k / (rho * c)
    folder = f"{out}/sphere"
    run(binary, f"{prm_folder}/sphere_quench.prm", folder, "Output/Write vtu=false")
    ok &= profile_errors(
        folder, (100.0, 300.0, 600.0),
        lambda p, t: sphere_quench(np.linalg.norm(p, axis=1), t, R, kappa, T0, Ts),
        0.5, "sphere: ")
    s = summary(folder)
    lost = -s["heat"]["stored_heat"]
    lost_exact = sphere_quench_heat_lost(600.0, R, kappa, rho * c, T0, Ts)
    ok &= check(abs(lost - lost_exact) <= 0.01 * lost_exact,
                f"sphere: heat lost by 600 s {lost:.1f} J vs {lost_exact:.1f} J "
                f"({100 * (lost / lost_exact - 1):+.3f} %, bound 1 %)")
    ok &= check(s["heat"]["relative_imbalance"] < 1e-8,
                f"sphere: heat balance relative imbalance {s['heat']['relative_imbalance']:.2e} < 1e-8")

if "shell" in cases:
    a, b, k, Ta, Tb = 0.03, 0.15, 3.0, 100.0, 0.0
    folder = f"{out}/shell"
    run(binary, f"{prm_folder}/spherical_shell_steady.prm", folder, "Output/Write vtu=false")
    lines = read_csv_xyz(f"{folder}/lines.csv")
    t_end = sorted(lines["radial"].keys())[-1]
    ok &= profile_errors(
        folder, (t_end,),
        lambda p, t: spherical_shell_temperature(np.linalg.norm(p, axis=1), a, b, Ta, Tb),
        0.5, "shell: ")
    s = summary(folder)
    q_exact = spherical_shell_heat_flow(k, a, b, Ta, Tb)
    for boundary, sign, where in (("0", 1.0, "in at r = a"), ("1", -1.0, "out at r = b")):
        q = sign * s["heat"]["boundary_heat_in"][boundary]
        ok &= check(abs(q - q_exact) <= 0.01 * q_exact,
                    f"shell: heat flow {where} {q:.3f} W vs 4 pi k dT / (1/a - 1/b) = "
                    f"{q_exact:.3f} W ({100 * (q / q_exact - 1):+.3f} %, bound 1 %)")

if "slab" in cases:
    def slab_exact(p, t):
        return plate_transient(p[:, 0], t)

    folder = f"{out}/slab"
    run(binary, f"{prm_folder}/plate_transient-3d.prm", folder, "Output/Write vtu=false")
    ok &= profile_errors(folder, (2.0, 10.0, 20.0), slab_exact, 0.5, "slab (tetrahedra): ")
    s = summary(folder)
    ok &= check(s["heat"]["relative_imbalance"] < 1e-8,
                f"slab: heat balance relative imbalance {s['heat']['relative_imbalance']:.2e} < 1e-8")

    amr = f"{out}/slab_amr"
    run(binary, f"{prm_folder}/plate_transient-3d.prm", amr,
        "Mesh/Element type=quadrilaterals", "Adaptive refinement/Enable=true",
        "Adaptive refinement/Interval=5", "Adaptive refinement/Refine fraction=0.5",
        "Adaptive refinement/Coarsen fraction=0.05", "Adaptive refinement/Maximum level=1",
        "Time stepping/End time=10", "Output/Times=2, 10", "Output/Write vtu=false")
    ok &= profile_errors(amr, (2.0, 10.0), slab_exact, 0.5,
                         "slab (hexahedra + AMR): ")
    s = summary(amr)
    ok &= check(s["heat"]["relative_imbalance"] < 1e-5,
                f"slab AMR heat balance (solution transfer included): relative imbalance "
                f"{s['heat']['relative_imbalance']:.1e} < 1e-5")

if "file" in cases:
    import os
    mesh = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data",
                        "cube_tetrahedra.msh")
    folder = f"{out}/file"
    run(binary, f"{prm_folder}/spherical_shell_steady.prm", folder,
        "Mesh/Source=file", f"Mesh/File name={os.path.abspath(mesh)}", "Mesh/Expected area=1",
        "Heat solver/Polynomial degree=1",
        "Thermal boundary conditions/Condition 1/Boundary ids=1",
        "Thermal boundary conditions/Condition 1/Temperature=0",
        "Thermal boundary conditions/Condition 2/Boundary ids=2",
        "Thermal boundary conditions/Condition 2/Temperature=100",
        "Monitors/Lines=diagonal: 0, 0, 0, 1, 1, 1, 41", "Output/Write vtu=false")
    lines = read_csv_xyz(f"{folder}/lines.csv")
    t_end = sorted(lines["diagonal"].keys())[-1]
    points, fields = lines["diagonal"][t_end]
    error = np.abs(fields["T"] - 100 * points[:, 0]).max()
    ok &= check(error <= 1e-6, f"file: gmsh tetrahedra, max |T - 100 x| = {error:.2e} C <= 1e-6 C")
    q = -summary(folder)["heat"]["boundary_heat_in"]["1"]
    ok &= check(abs(q - 300.0) <= 300.0 * 1e-6,
                f"file: heat flow out at x = 0 {q:.9f} W vs k dT A / L = 300 W (bound 1e-6 relative)")

sys.exit(0 if ok else 1)
