#!/usr/bin/env python3
"""A sphere dropped on a plate: Hertz's impact (prm/sphere_drop-3d.prm).

A quarter of an elastic sphere (R = 0.05 m, E = 50 GPa, nu = 0.25,
rho = 2700 kg/m^3, cut by two symmetry planes held by rollers) hits a fixed
plate at v = 20 m/s, frictionless, unbreakable, undamped, with the shipped
contact penalty (10 E). Hertz's quasi-static impact of a sphere on a rigid
half-space (Johnson, Contact Mechanics, 11.1), with E* = E / (1 - nu^2) and
m the whole sphere's mass (the quarter carries a quarter of the mass and
of the force):
  delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),
  F_max     = 4/3 E* sqrt(R) delta_max^(3/2),
  t_c       = 2 delta_max / v int_0^1 dx / sqrt(1 - x^(5/2))
            = 2.9432 delta_max / v.
Checked, bounds fixed before the run:
  - the contact lasts t_c within 5 % (the plate's reaction is non-zero from
    the touch to the rebound);
  - the peak force, 4 times the quarter's reaction, is F_max within 10 %
    (linear tetrahedra, a / h of about 6 under the contact);
  - the impact gains no energy: the energy balance closes to 1 % of the
    initial kinetic energy, and the centre of mass rebounds no faster than
    it came (restitution <= 1), and not below 0.9 (the elastic impact loses
    only what is left ringing in the sphere).

usage: verify_discrete_sphere_drop_3d.py TMFDEM OUT [extra --set overrides]
"""
import csv
import math
import os
import sys

from common import run, summary, check

prm = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                   "prm", "sphere_drop-3d.prm")

# the prm's values (scripts/plot_discrete_case.py imports them)
R, E, nu, rho, v, gap = 0.05, 5e10, 0.25, 2700.0, 20.0, 0.0005


def hertz():
    """delta_max [m], F_max [N], t_c [s] of the whole sphere."""
    m = 4.0 / 3.0 * math.pi * R**3 * rho
    E_star = E / (1.0 - nu * nu)
    delta = (15.0 * m * v * v / (16.0 * E_star * math.sqrt(R)))**0.4
    force = 4.0 / 3.0 * E_star * math.sqrt(R) * delta**1.5
    # int_0^1 dx / sqrt(1 - x^(5/2)): x = 1 - s^2 removes the end's
    # singularity, midpoint rule in s
    n = 200000
    integral = 0.0
    for i in range(n):
        s = (i + 0.5) / n
        x = 1.0 - s * s
        integral += 2.0 * s / math.sqrt(1.0 - x**2.5) / n
    return delta, force, 2.0 * delta / v * integral, m


def main():
    binary, out = sys.argv[1], sys.argv[2]
    settings = sys.argv[3:]
    ok = True
    delta, F_max, t_c, m = hertz()
    print(f"Hertz: delta_max = {delta:.6e} m, F_max = {F_max:.6e} N, "
          f"t_c = {t_c:.6e} s, contact radius {math.sqrt(R * delta):.4e} m")
    folder = os.path.join(out, "drop")
    run(binary, prm, folder, *settings)
    s = summary(folder)
    with open(os.path.join(folder, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["time"]) for r in rows]
    F = [4.0 * abs(float(r["body2_fz"])) for r in rows]
    uz = [float(r["body1_uz"]) for r in rows]
    # in contact: a reaction above 1e-6 of Hertz's peak (the fixed plate's
    # own joints leave round-off in it before the touch)
    touching = [i for i, f in enumerate(F) if f > 1e-6 * F_max]
    ok &= check(touching and touching[-1] < len(F) - 1,
                "the sphere touches the plate and leaves it again")
    if not ok:
        return 1
    first, last = touching[0], touching[-1]
    ok &= check(first > 0 and all(F[i] > 1e-6 * F_max
                                  for i in range(first, last + 1)),
                "one contact, from the touch to the rebound")
    # the touch and the rebound between history rows: the row before the
    # first non-zero force and the row after the last
    start = 0.5 * (t[first - 1] + t[first])
    end = 0.5 * (t[last] + t[last + 1])
    resolution = t[1] - t[0]
    duration = end - start
    err_t = duration / t_c - 1.0
    ok &= check(abs(err_t) <= 0.05,
                f"contact time {duration:.6e} s against Hertz's "
                f"{t_c:.6e} s: {100 * err_t:+.2f} % (bound 5 %; the history "
                f"rows are {resolution:.2e} s apart); touch at "
                f"{start:.4e} s, free flight gap / v = {gap / v:.4e} s")
    peak = max(F)
    err_F = peak / F_max - 1.0
    ok &= check(abs(err_F) <= 0.10,
                f"peak force {peak:.6e} N against Hertz's {F_max:.6e} N: "
                f"{100 * err_F:+.2f} % (bound 10 %)")
    kinetic0 = 0.5 * (m / 4.0) * v * v
    balance = abs(s["energy"]["balance_error"]) / kinetic0
    ok &= check(balance <= 0.01,
                f"energy balance error {balance:.3e} of the initial kinetic "
                f"energy (bound 1 %)")
    # the centre of mass's speed after the rebound, fitted over the rows
    # after the contact
    after = [i for i in range(last + 1, len(t))]
    ok &= check(len(after) >= 10, f"{len(after)} rows after the rebound")
    if len(after) >= 10:
        n = len(after)
        tm = sum(t[i] for i in after) / n
        um = sum(uz[i] for i in after) / n
        slope = sum((t[i] - tm) * (uz[i] - um) for i in after) / sum(
            (t[i] - tm)**2 for i in after)
        restitution = slope / v
        ok &= check(0.9 <= restitution <= 1.0,
                    f"restitution {restitution:.5f} (rebound {slope:.4f} m/s "
                    f"against {v} m/s): within [0.9, 1]")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
