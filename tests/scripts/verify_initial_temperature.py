#!/usr/bin/env python3
"""Per-material and per-body initial temperature, checked exactly (to the
12 digits of the csv) at t = 0.

discrete (prm/contact_conduction.prm: block 1 material 1, block 2
  material 2, overlapping by 10 um at y = 0.1): every triangle owns its
  nodes, so the initial field is the entry of the triangle's material:
  - Materials/Material 1/Initial temperature = 100, Material 2 = 0: every
    sample of the axis line in block 1 (y < 0.1 - 1e-5) is 100, every one in
    block 2 (y > 0.1) is 0 (a threshold in y, the former
    `y < 0.1 - 1e-5 ? 100 : 0`, set block 1's top-face nodes to 0);
  - precedence body > global, material > global: Discrete bodies/Body 1
    (material 1) = 100 + 100 * y, Initial conditions/Temperature = 50:
    block 1 is 100 + 100 y, block 2 (no entry of its own) 50.
continuum (tests/data/two_triangles.msh: the unit square cut along the
  diagonal (0,0)-(1,1), material 2 below it, material 3 above), Material 2 =
  100 + x, Material 3 = 20 + y: a node of one material takes its value, a
  node on the interface the mean of the two materials' values there:
  P1: (1,0) 101, (0,1) 21, (0,0) 60, (1,1) 61; inside, the P1 interpolant:
  (0.75, 0.25) 80.75, (0.25, 0.75) 40.75;
  P2: the same vertices, the interface midpoint (0.5, 0.5) 60.5, the edge
  midpoints (0.5, 0) 100.5 and (0, 0.5) 20.5;
  P1 after 3 global refinements, serial and (with mpirun given as the third
  argument) on 2 MPI ranks, where interface nodes owned by one rank touch
  cells of the other: (t, t) on the interface 60 + t, (0.75, 0.25) 100.75,
  (0.25, 0.75) 20.75.
usage: verify_initial_temperature.py TMFDEM OUTPUT_FOLDER [MPIRUN]"""
import os
import sys

import numpy as np

from analytic import read_csv
from common import run, check

binary, out = sys.argv[1], sys.argv[2]
mpirun = sys.argv[3] if len(sys.argv) > 3 else None
here = os.path.dirname(os.path.abspath(__file__))
ok = True
tolerance = 1e-10  # C: the csv's 12 significant digits on values <= 101

contact = os.path.join(here, "..", "..", "prm", "contact_conduction.prm")
common = ["Time stepping/End time=1", "Time stepping/Time step=1",
          "Output/Interval=1", "Output/Write vtu=false"]
runs = {
    "per_material": (["Materials/Material 1/Initial temperature=100",
                      "Materials/Material 2/Initial temperature=0"],
                     lambda y: 100.0 + 0.0 * y, lambda y: 0.0 * y),
    "per_body": (["Discrete bodies/Body 1/Material ids=1",
                  "Discrete bodies/Body 1/Initial temperature=100 + 100 * y",
                  "Initial conditions/Temperature=50"],
                 lambda y: 100.0 + 100.0 * y, lambda y: 50.0 + 0.0 * y),
}
for name, (settings, block1, block2) in runs.items():
    folder = os.path.join(out, "discrete_" + name)
    run(binary, contact, folder, *common, *settings)
    x, y, fields = read_csv(os.path.join(folder, "lines.csv"))["axis"][0.0]
    T = fields["T"]
    lower, upper = y < 0.1 - 1e-5, y > 0.1
    error1 = np.max(np.abs(T[lower] - block1(y[lower])))
    error2 = np.max(np.abs(T[upper] - block2(y[upper])))
    ok &= check(error1 < tolerance and error2 < tolerance,
                f"discrete, {name}: initial T on {lower.sum()} samples in block 1 and "
                f"{upper.sum()} in block 2 off by at most {max(error1, error2):.1e} C "
                f"(< {tolerance:g} C)")

prm = os.path.join(out, "two_materials.prm")
os.makedirs(out, exist_ok=True)
with open(prm, "w") as f:
    f.write(f"""set Model = continuum heat
subsection Mesh
  set Source    = file
  set File name = {os.path.join(here, '..', 'data', 'two_triangles.msh')}
end
subsection Materials
  subsection Material 2
    set Initial temperature = 100 + x
  end
  subsection Material 3
    set Initial temperature = 20 + y
  end
end
subsection Time stepping
  set End time  = 1e-6
  set Time step = 1e-6
end
subsection Output
  set Interval  = 1e-6
  set Write vtu = false
end
""")
vertices = {"p00": (0, 0, 60.0), "p10": (1, 0, 101.0), "p11": (1, 1, 61.0),
            "p01": (0, 1, 21.0)}
expected = {1: dict(vertices, inside_lower=(0.75, 0.25, 80.75),
                    inside_upper=(0.25, 0.75, 40.75)),
            2: dict(vertices, mid_diagonal=(0.5, 0.5, 60.5), mid_bottom=(0.5, 0, 100.5),
                    mid_left=(0, 0.5, 20.5))}
for degree, points in expected.items():
    folder = os.path.join(out, f"continuum_P{degree}")
    probes = "; ".join(f"{n}: {px}, {py}" for n, (px, py, _) in points.items())
    run(binary, prm, folder, f"Heat solver/Polynomial degree={degree}",
        f"Monitors/Probes={probes}")
    values = read_csv(os.path.join(folder, "probes.csv"))
    for n, (px, py, reference) in points.items():
        value = values[n][0.0][2]["T"][0]
        ok &= check(abs(value - reference) < tolerance,
                    f"continuum P{degree}: initial T at ({px}, {py}) = {value:.12g} C "
                    f"vs {reference} C")
refined = {"d1": (0.25, 0.25, 60.25), "d2": (0.625, 0.625, 60.625),
           "d3": (0.875, 0.875, 60.875), "lower": (0.75, 0.25, 100.75),
           "upper": (0.25, 0.75, 20.75)}
probes = "; ".join(f"{n}: {px}, {py}" for n, (px, py, _) in refined.items())
for ranks in ([1, 2] if mpirun else [1]):
    folder = os.path.join(out, f"continuum_refined_np{ranks}")
    run(binary, prm, folder, "Mesh/Global refinements=3", f"Monitors/Probes={probes}",
        mpirun=mpirun if ranks > 1 else None, np=ranks)
    values = read_csv(os.path.join(folder, "probes.csv"))
    for n, (px, py, reference) in refined.items():
        value = values[n][0.0][2]["T"][0]
        ok &= check(abs(value - reference) < tolerance,
                    f"continuum P1, 3 refinements, {ranks} rank(s): initial T at ({px}, {py}) "
                    f"= {value:.12g} C vs {reference} C")
sys.exit(0 if ok else 1)
