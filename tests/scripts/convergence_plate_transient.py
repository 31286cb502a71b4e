#!/usr/bin/python3
"""Refinement study on paper 5.1 (continuum heat solver).
Space: P1 triangles at h = 0.05, 0.025, 0.0125 m (uniform refinement), CN
with a small step: the max error on 'midline' at t = 2 s against the series
falls at second order; at the paper's h = 0.05 m it is 0.69 C, the P1 limit
of that mesh (1.36 C when the Dirichlet nodes started at the boundary value;
doc/cases/plate_transient-continuum.md). Rannacher start: at dt = 0.05 s the
Crank-Nicolson time error at t = 2 s is 0.006 C with four backward Euler
half steps first, 0.3 C without. Time: on the h = 0.05 mesh, errors against
a run with a 100x smaller step on the same mesh (this isolates the time
error) at t = 10 s: first order for backward Euler, second for
Crank-Nicolson."""
import math
import sys
import numpy as np
from common import run, check
from analytic import plate_transient, read_csv

binary, prm, out = sys.argv[1:4]
ok = True


def midline(folder, t):
    x, y, f = read_csv(f"{folder}/lines.csv")["midline"][t]
    return x, f["T"]


print("== space (P1, Crank-Nicolson, dt = 0.005 s, t = 2 s)")
errors = []
for k in range(3):
    folder = f"{out}/space{k}"
    run(binary, prm, folder, "Heat solver/Polynomial degree=1", f"Mesh/Global refinements={k}",
        "Time stepping/Time step=0.005", "Time stepping/End time=2", "Output/Times=",
        "Output/Write vtu=false")
    x, T = midline(folder, 2.0)
    errors.append(abs(T - plate_transient(x, 2.0)).max())
for k in range(3):
    rate = "" if k == 0 else f"  order {math.log2(errors[k-1]/errors[k]):.2f}"
    print(f"  h = {0.05/2**k:.4f} m  max error {errors[k]:.5f} C{rate}")
ok &= check(errors[0] <= 0.72, f"space: P1 at h = 0.05 m, t = 2 s: max error {errors[0]:.4f} C "
            "<= 0.72 C (P1 limit of the paper's mesh)")
order = math.log2(errors[1] / errors[2])
ok &= check(1.8 < order < 2.6, f"space: observed order {order:.2f} is about 2")

print("== Rannacher start (P1, Crank-Nicolson, dt = 0.05 s, h = 0.05 m, t = 2 s)")
# the Dirichlet step at the hot edge is non-smooth data: Crank-Nicolson alone
# carries its stiff modes undamped; four backward Euler half steps damp them
_, T_ref = midline(f"{out}/space0", 2.0)
time_errors = {}
for steps in (0, 4):
    folder = f"{out}/rannacher{steps}"
    run(binary, prm, folder, "Heat solver/Polynomial degree=1", f"Time stepping/Rannacher steps={steps}",
        "Time stepping/Time step=0.05", "Time stepping/End time=2", "Output/Times=",
        "Output/Write vtu=false")
    _, T = midline(folder, 2.0)
    time_errors[steps] = abs(T - T_ref).max()
    print(f"  Rannacher steps = {steps}: max |T - T(dt = 0.005 s)| = {time_errors[steps]:.5f} C")
ok &= check(time_errors[4] < 0.01 and time_errors[0] > 0.1,
            f"Rannacher start: time error {time_errors[4]:.4f} C (< 0.01 C) against "
            f"{time_errors[0]:.3f} C without (> 0.1 C)")

for method, expected in (("backward Euler", 1.0), ("Crank-Nicolson", 2.0)):
    print(f"== time ({method}, P1, h = 0.05 m, t = 10 s)")
    ref_folder = f"{out}/time_ref"
    run(binary, prm, ref_folder, "Heat solver/Polynomial degree=1", f"Time stepping/Method={method}",
        "Time stepping/Time step=0.004", "Time stepping/End time=10", "Output/Times=",
        "Output/Write vtu=false")
    _, T_ref = midline(ref_folder, 10.0)
    errors = []
    for dt in (0.4, 0.2, 0.1):
        folder = f"{out}/time_{dt}"
        run(binary, prm, folder, "Heat solver/Polynomial degree=1", f"Time stepping/Method={method}",
            f"Time stepping/Time step={dt}", "Time stepping/End time=10", "Output/Times=",
            "Output/Write vtu=false")
        _, T = midline(folder, 10.0)
        errors.append(abs(T - T_ref).max())
    for i, dt in enumerate((0.4, 0.2, 0.1)):
        rate = "" if i == 0 else f"  order {math.log2(errors[i-1]/errors[i]):.2f}"
        print(f"  dt = {dt:4.2f} s  max error {errors[i]:.6f} C{rate}")
    order = math.log2(errors[1] / errors[2])
    ok &= check(abs(order - expected) < 0.25, f"time, {method}: observed order {order:.2f} is about {expected:.0f}")
sys.exit(0 if ok else 1)
