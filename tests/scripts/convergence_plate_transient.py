#!/usr/bin/python3
"""Refinement study on paper 5.1 (continuum heat solver).
Space: P1 triangles at h = 0.05, 0.025, 0.0125 m (uniform refinement), CN
with a small step: the max error on 'midline' at t = 2 s against the series
falls at second order. Time: on the h = 0.05 mesh, errors against a run with
a 100x smaller step on the same mesh (this isolates the time error) at
t = 10 s: first order for backward Euler, second for Crank-Nicolson."""
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
order = math.log2(errors[1] / errors[2])
ok &= check(1.7 < order < 2.5, f"space: observed order {order:.2f} is about 2")

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
