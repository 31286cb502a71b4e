#!/usr/bin/python3
"""Throughput of the continuum heat solver (paper 5.1 plate, P1 triangles,
backward Euler, 200 steps of 0.05 s) at growing mesh sizes, and the
cost of the AMR thick cylinder against uniform refinement at equal accuracy.
usage: benchmarks/continuum_heat_throughput.py [path/to/tmfdem]
Prints DoFs, steps, wall time and DoF-steps per second (from summary.json)."""
import json
import os
import subprocess
import sys
from bench_common import help_requested, tmfdem, work_folder

here = os.path.dirname(os.path.abspath(__file__))
help_requested(__doc__)
binary = tmfdem(sys.argv[1] if len(sys.argv) > 1 else None)
prm_dir = os.path.join(here, "..", "prm")
out = work_folder("tmfdem-bench-")


def run(prm, *settings):
    cmd = [binary, os.path.join(prm_dir, prm), "--set", f"Output/Directory={out}",
           "--set", "Output/Write vtu=false", "--set", "Output/Progress interval=0"]
    for s in settings:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, capture_output=True)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


print("plate, P1 triangles, backward Euler, 200 steps")
print(f"{'refinements':>11} {'cells':>8} {'DoFs':>8} {'wall [s]':>9} {'DoF-steps/s':>12} {'cell-steps/s':>13}")
for k in range(5):
    s = run("plate_transient-continuum.prm", "Heat solver/Polynomial degree=1",
            "Time stepping/Method=backward Euler", f"Mesh/Global refinements={k}",
            "Time stepping/End time=10", "Output/Times=")
    print(f"{k:>11} {s['cells']:>8} {s['dofs']:>8} {s['wall_time']:>9.3f} "
          f"{s['dofs'] * s['steps'] / s['wall_time']:>12.3e} {s['element_steps_per_second']:>13.3e}")
s = run("plate_transient-continuum.prm", "Heat solver/Polynomial degree=1",
        "Time stepping/Method=backward Euler", "Mesh/Global refinements=4",
        "Time stepping/End time=10", "Output/Times=", "Monitors/Probes=", "Monitors/Lines=")
print(f"{'4, no monitors':>11} {s['cells']:>8} {s['dofs']:>8} {s['wall_time']:>9.3f} "
      f"{s['dofs'] * s['steps'] / s['wall_time']:>12.3e} {s['element_steps_per_second']:>13.3e}")
print("\nthick cylinder, steady, Q1: adaptive against uniform")
s = run("thick_cylinder-continuum.prm")
print(f"  adaptive (7 cycles): {s['dofs']} DoFs, wall {s['wall_time']:.3f} s (all cycles)")
for k in (3, 4):
    s = run("thick_cylinder-continuum.prm", "Adaptive refinement/Enable=false", f"Mesh/Global refinements={k}")
    print(f"  uniform, {k} refinements: {s['dofs']} DoFs, wall {s['wall_time']:.3f} s")
