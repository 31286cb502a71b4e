#!/usr/bin/python3
"""Where and when a hollow cylinder heated on its inner wall by a ramp first
fails, and how much stress it keeps once a crack has cut it along a radius.

    hollow_cylinder_heating_rate.py [RATE ...] [--check]

RATE: heating rates of the inner wall [C/s] (T_a = RATE t, outer wall at
0 C; default: a sweep from 1e-4 to 0.12). The material and the geometry are
those of prm/hollow_cylinder_cracking.prm (a = 0.03 m, b = 0.15 m, E = 20
GPa, nu = 0.25, alpha = 1.8e-5 1/K, k = 3 W/(m K), rho c_p = 2e6 J/(m^3 K),
f_t = 10 MPa, plane strain). Per rate it prints

- the time and the inner-wall temperature at which the largest hoop stress
  of the intact ring reaches f_t, and the radius where it does (b: the
  outer rim, as in the paper's Fig. 13; inside the wall: ahead of the heat
  front);
- the largest hoop stress of the same ring cut along one radius, at that
  time and over the three times as long heating that follows.

The temperature is the radial heat equation (backward Euler, 481 points);
the intact ring's hoop stress the plane-strain thermoelastic formula of a
ring with traction-free walls (Timoshenko and Goodier, Sec. 151),

    sigma_theta = E alpha / (1 - nu) [ (1/r^2) int_a^r T r dr
                  + (r^2 + a^2) / (r^2 (b^2 - a^2)) int_a^b T r dr - T ].

A radial cut frees the ring's moment on the section: far from the cut (Saint-
Venant) the cut ring's stress is the intact one minus the multiple of the
log profile's stress (a wedge disclination, doc/cases/
hollow_cylinder_cracking.md) that makes int sigma_theta r dr vanish. A log
profile therefore leaves the cut ring stress-free; a transient profile
leaves what this script prints. --check asserts both limits (a slow ramp,
1e-4 C/s, first fails at the rim within 0.2 % of the steady 77.45 C; the
cut ring under a log profile is free of stress) and exits with 1 if either
fails. Needs only numpy.
"""
import argparse
import sys

import numpy as np

A, B = 0.03, 0.15             # radii [m]
E, NU, ALPHA = 20e9, 0.25, 1.8e-5
KAPPA = 3.0 / (2500 * 800)    # thermal diffusivity [m^2/s]
F_T = 10e6                    # tensile strength [Pa]
R = np.linspace(A, B, 481)
DR = R[1] - R[0]


def hoop_stress(T):
    """Hoop stress [Pa] of the intact ring at R for the temperature T [C]."""
    tr = T * R
    inner = np.concatenate([[0.0], np.cumsum(0.5 * (tr[1:] + tr[:-1]) * DR)])
    return E * ALPHA / (1 - NU) * (inner / R**2 + (R**2 + A**2) /
                                   (R**2 * (B**2 - A**2)) * inner[-1] - T)


LOG_STRESS = hoop_stress(np.log(B / R) / np.log(B / A))


def cut_ring_hoop_stress(T):
    """Hoop stress [Pa] of the ring cut along one radius, far from the cut."""
    s = hoop_stress(T)
    moment = np.trapz(s * R, R) / np.trapz(LOG_STRESS * R, R)
    return s - moment * LOG_STRESS


def heating(rate, dt):
    """Generator of (t, T) for the ramp T_a = rate t from 0 C, step dt [s]."""
    n = len(R)
    lhs = np.eye(n)
    for i in range(1, n - 1):
        plus, minus = R[i] + DR / 2, R[i] - DR / 2
        c = KAPPA * dt / (R[i] * DR**2)
        lhs[i, i - 1] -= c * minus
        lhs[i, i + 1] -= c * plus
        lhs[i, i] += c * (plus + minus)
    lhs[0, :], lhs[-1, :] = 0.0, 0.0
    lhs[0, 0] = lhs[-1, -1] = 1.0
    inverse = np.linalg.inv(lhs)
    T, t = np.zeros(n), 0.0
    while True:
        t += dt
        rhs = T.copy()
        rhs[0], rhs[-1] = rate * t, 0.0
        T = inverse @ rhs
        yield t, T


def first_failure(rate):
    """(t_f [s], T_a [C], radius of the largest hoop stress [m], cut-ring
    maximum at t_f [Pa], cut-ring maximum up to 4 t_f [Pa])."""
    dt = min(100.0, 0.5 / rate)   # 0.5 C of the inner wall per step
    steps = heating(rate, dt)
    for t, T in steps:
        s = hoop_stress(T)
        if s.max() >= F_T:
            break
    at_failure = cut_ring_hoop_stress(T).max()
    later = at_failure
    for t_later, T in steps:
        later = max(later, cut_ring_hoop_stress(T).max())
        if t_later >= 4 * t:
            break
    return t, rate * t, R[np.argmax(s)], at_failure, later


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("rates", nargs="*", type=float,
                        default=[1e-4, 1e-3, 1e-2, 3e-2, 5e-2, 8e-2, 0.1, 0.12])
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    print("rate [C/s]  t_f [s]   T_a [C]  r of max [m]  cut ring: at t_f  up to 4 t_f [MPa]")
    results = {}
    for rate in args.rates:
        results[rate] = first_failure(rate)
        t, t_a, r_max, at, later = results[rate]
        print(f"{rate:10.4g}  {t:8.0f}  {t_a:7.2f}  {r_max:12.4f}  "
              f"{at / 1e6:16.2f}  {later / 1e6:11.2f}")
    if args.check:
        ok = True
        per_degree = hoop_stress(np.log(B / R) / np.log(B / A))[-1]  # [Pa/C]
        expected = F_T / per_degree  # 77.45 C
        t, t_a, r_max, _, _ = first_failure(1e-4)
        log_cut = np.abs(cut_ring_hoop_stress(100 * np.log(B / R) / np.log(B / A))).max()
        for name, good in [(f"slow ramp fails at {t_a:.2f} C, steady {expected:.2f} C",
                            abs(t_a / expected - 1) < 2e-3),
                           (f"slow ramp fails at r = {r_max:.4f} m", r_max == B),
                           (f"cut ring under a log profile: {log_cut:.3g} Pa", log_cut < 1.0)]:
            print(("ok   " if good else "FAIL ") + name)
            ok &= good
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
