#!/usr/bin/env python3
"""The thick-walled sphere in the discrete layer in 3D (tetrahedra, face
joints, joint compliance compensation), quasi-static.

tests/data/discrete/shell_steady-3d.prm: a = 0.075 m, b = 0.15 m, E = 20
GPa, nu = 0.2, alpha = 1.8e-5 1/K, 100 C held at r = a and 0 C at r = b,
one backward Euler step of 1e6 s to the steady state, then the
quasi-static relaxation (free surfaces, no restraint). References, fixed
before the runs:

1. the temperature at every node the boundary conditions do not hold
   against the steady radial conduction T = T_b + (T_a - T_b) (1/r - 1/b) /
   (1/a - 1/b), within 1 C (1 % of the range: the element-wise linear field
   with joints of finite conductance); the held nodes carry T_a and T_b
   exactly, some of them (the face centres of the split hexahedra) inside
   the polyhedral inner surface, r < a, where the closed form does not
   apply;
2. the thermal stresses of Timoshenko and Goodier (analytic.
   spherical_shell_stress): the radial and the hoop stress of the
   tetrahedra (sigma_rr = e_r . sigma . e_r at the centroid, the hoop
   stress the mean of the two tangential normal stresses), averaged over
   shells of tetrahedra (8 bins in r) against the closed form averaged over
   the same tetrahedra, within 3 % of the largest hoop stress (the bound of
   the 2D thick cylinder, verify.discrete_thick_cylinder); the relaxation
   converged (no relaxation at its cap). The 3 % target is NOT met on the
   prm's mesh (36 864 tetrahedra: 5.2 % in the shell next to the inner
   surface, where sigma_r rises from 0 over less than one element;
   doc/verification.md, "Targets not met"): printed, not asserted;
3. the same on the mesh of the next coarser size (Element size 0.06,
   4608 tetrahedra: h twice the prm's): asserted, the stress error falls at
   least 1.5 times from it to the prm's mesh (first order in h: 2);
4. the prm's mesh relaxed with kinetic damping (Relaxation damping =
   kinetic: velocity resets at the peaks of the kinetic energy, as in 2D)
   instead of the mass damping: it converges, resets at least once, and
   reaches the same equilibrium: the shell means of sigma_r and sigma_t
   within 1 % of the largest hoop stress of those of the mass-damped run
   (both stop at Relaxation force tolerance = 1e-3 of the internal forces).

usage: verify_discrete_sphere_3d.py TMFDEM OUT
"""
import os
import re
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
sys.path.insert(0, os.path.join(here, "..", "..", "scripts"))
from common import run, summary, check  # noqa: E402
import analytic  # noqa: E402
import vtu_pieces  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(here, "..", "data", "discrete", "shell_steady-3d.prm")
a, b, t_a, t_b = 0.075, 0.15, 100.0, 0.0
E, nu, alpha = 20e9, 0.2, 1.8e-5
ok = True


def last_output(folder):
    with open(os.path.join(folder, "solution.pvd")) as f:
        name = re.findall(r'file="([^"]+)"', f.read())[-1]
    arrays = {}
    for section, attributes, values in vtu_pieces.read_arrays(
            os.path.join(folder, name)):
        arrays[(section, vtu_pieces._attribute(attributes, "Name"))] = values
    return arrays


def measure(folder):
    arrays = last_output(folder)
    X = (arrays[("Points", None)].reshape(-1, 3)
         - arrays[("PointData", "displacement")].reshape(-1, 3))
    r_nodes = np.linalg.norm(X, axis=1)
    T = arrays[("PointData", "T")]
    free = (T != t_a) & (T != t_b)  # not held by the boundary conditions
    T_error = np.max(np.abs(T[free] - analytic.spherical_shell_temperature(
        r_nodes[free], a, b, t_a, t_b)))
    centroids = X.reshape(-1, 4, 3).mean(axis=1)
    r = np.linalg.norm(centroids, axis=1)
    e = centroids / r[:, None]
    s = {c: arrays[("CellData", c)] for c in ("sxx", "syy", "szz", "sxy", "syz", "sxz")}
    sigma = np.empty((len(r), 3, 3))
    sigma[:, 0, 0], sigma[:, 1, 1], sigma[:, 2, 2] = s["sxx"], s["syy"], s["szz"]
    sigma[:, 0, 1] = sigma[:, 1, 0] = s["sxy"]
    sigma[:, 1, 2] = sigma[:, 2, 1] = s["syz"]
    sigma[:, 0, 2] = sigma[:, 2, 0] = s["sxz"]
    s_rr = np.einsum("ei,eij,ej->e", e, sigma, e)
    s_tt = 0.5 * (np.trace(sigma, axis1=1, axis2=2) - s_rr)
    ref_r, ref_t = analytic.spherical_shell_stress(r, E, nu, alpha, a, b, t_a, t_b)
    scale = np.max(np.abs(analytic.spherical_shell_stress(
        np.linspace(a, b, 1001), E, nu, alpha, a, b, t_a, t_b)[1]))
    edges = np.linspace(a, b, 9)
    rows, worst = [], 0.0
    for k in range(8):
        cells = (r >= edges[k]) & (r < edges[k + 1])
        d_r = (np.mean(s_rr[cells]) - np.mean(ref_r[cells])) / scale
        d_t = (np.mean(s_tt[cells]) - np.mean(ref_t[cells])) / scale
        worst = max(worst, abs(d_r), abs(d_t))
        rows.append((np.mean(r[cells]), np.count_nonzero(cells), np.mean(s_rr[cells]),
                     np.mean(ref_r[cells]), np.mean(s_tt[cells]), np.mean(ref_t[cells]),
                     d_r, d_t))
    return T_error, worst, scale, rows


results = {}
for size in ("0.04", "0.06", "0.04 kinetic"):
    folder = os.path.join(out, "shell_h" + size.replace(" ", "_"))
    run(binary, prm, folder, f"Mesh/Element size={size.split()[0]}",
        *(["Discrete heat/Relaxation damping=kinetic"] if "kinetic" in size else []))
    su = summary(folder)
    T_error, worst, scale, rows = measure(folder)
    results[size] = (T_error, worst, su, rows)
    print(f"Element size {size}: {su['elements']} tetrahedra, {su['steps']} "
          f"relaxation steps, relaxations at the cap {su['relaxations_at_cap']}, "
          f"compensation capped in {su['compensation_capped_elements']}")
    print("   r [m]   cells  sigma_r [MPa] (closed form)  sigma_t [MPa] (closed form)"
          "  errors / max |sigma_t|")
    for r_mean, n, sr, rr, st, rt, dr, dt in rows:
        print(f"  {r_mean:.4f} {n:6d}  {sr / 1e6:8.3f} ({rr / 1e6:8.3f})   "
              f"{st / 1e6:8.3f} ({rt / 1e6:8.3f})   {100 * dr:+.2f} % {100 * dt:+.2f} %")
    print(f"  T: largest error at the nodes {T_error:.4f} C; stresses: worst bin "
          f"{100 * worst:.2f} % of {scale / 1e6:.3f} MPa; energy balance error "
          f"{su['energy']['balance_error']:.4g} J of the thermal work "
          f"{su['energy']['thermal_work']:.4g} J", flush=True)

T_error, worst, su, rows = results["0.04"]
ok &= check(T_error <= 1.0, f"steady temperature at every node not held within "
            f"{T_error:.3f} C of the radial conduction (1 C)")
ok &= check(su["relaxations_at_cap"] == 0 and results["0.06"][2]["relaxations_at_cap"] == 0,
            "the relaxations converged")
print(("target met" if worst <= 0.03 else "TARGET NOT MET") +
      f": thick-walled sphere, sigma_r and sigma_t by shells of tetrahedra within "
      f"{100 * worst:.2f} % of the largest hoop stress of Timoshenko-Goodier (3 %)",
      flush=True)
ratio = results["0.06"][1] / worst
ok &= check(ratio >= 1.5, f"the stress error falls with h: {100 * results['0.06'][1]:.2f} % "
            f"(Element size 0.06) -> {100 * worst:.2f} % (0.04), {ratio:.2f} times (>= 1.5)")
kinetic = results["0.04 kinetic"]
difference = max(max(abs(a[2] - b[2]), abs(a[4] - b[4]))
                 for a, b in zip(rows, kinetic[3])) / scale
ok &= check(kinetic[2]["relaxations_at_cap"] == 0 and kinetic[2]["velocity_resets"] > 0,
            f"kinetic damping: the relaxation converged in {kinetic[2]['steps']} steps "
            f"with {kinetic[2]['velocity_resets']} velocity resets")
ok &= check(difference <= 0.01, f"kinetic and mass damping reach the same equilibrium: "
            f"shell means within {100 * difference:.2f} % of the largest hoop stress (1 %)")
sys.exit(0 if ok else 1)
