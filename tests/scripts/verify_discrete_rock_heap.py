#!/usr/bin/env python3
"""Rock heap (paper Sec. 5.2; prm/rock_heap.prm, prm/rock_heap-heat.prm),
shortened:
  generator:  Mesh/Source = block heap is deterministic (the same seed gives
              a byte-identical mesh, another seed another mesh) and makes the
              requested number of blocks (connected sets of material-1 cells);
  settle:     a heap of fewer blocks dropped under gravity settles (kinetic
              energy < 1e-3 of the gravity work), every block vertex stays
              inside the container (0 <= x <= W, y >= 0 up to the contact
              overlap, 0.5 mm);
  heat:       the settled heap heated from the base (100 C, walls 0 C) keeps
              the heat balance (heat in - heat out = stored) to 1e-6
              relative, and the probes on the monitor line are ordered by
              height (bottom-up heating)."""
import os
import sys

import numpy as np

from analytic import read_csv
from common import run, summary, check
from heap_mesh import bodies, generate, read_msh

binary, out = sys.argv[1], sys.argv[2]
prm_dir = os.path.join(os.path.dirname(__file__), "..", "..", "prm")
settle_prm = os.path.join(prm_dir, "rock_heap.prm")
heat_prm = os.path.join(prm_dir, "rock_heap-heat.prm")
ok = True
W, H = 0.5, 0.7


# ---------------------------------------------------------------- generator
a = generate(binary, settle_prm, os.path.join(out, "seed1_a"))
b = generate(binary, settle_prm, os.path.join(out, "seed1_b"))
c = generate(binary, settle_prm, os.path.join(out, "seed2"), "Mesh/Block heap/Seed=2")
ok &= check(a == b, "the same seed gives a byte-identical mesh")
ok &= check(a != c, "another seed gives another mesh")
nodes, triangles, _ = read_msh(os.path.join(out, "seed1_a", "mesh.msh"), 2)
n_blocks = len(bodies(triangles, 1))
ok &= check(n_blocks == 61, f"{n_blocks} blocks generated (61 requested)")
ok &= check(len(bodies(triangles, 2)) == 3, "container: base plate and two walls")

# ------------------------------------------------------------------- settle
folder = os.path.join(out, "settle")
n_settle = 16
run(binary, settle_prm, folder, f"Mesh/Block heap/Number of blocks={n_settle}",
    "Time stepping/End time=0.8", "Output/Write vtu=false", "Output/Interval=0",
    "Discrete mechanics/Threads=1")
s = summary(folder)
e = s["energy"]
ratio = e["kinetic"] / e["external_work"]
ok &= check(ratio < 1e-3, f"settled: kinetic energy {e['kinetic']:.3e} J/m = {ratio:.1e} "
            f"of the gravity work {e['external_work']:.3e} J/m (< 1e-3)")
ok &= check(s["broken_joints"] == 0, f"{s['broken_joints']} broken joints (none)")
settled = os.path.join(folder, "final_mesh.msh")
nodes, triangles, segments = read_msh(settled, 2)
ok &= check(len(bodies(triangles, 1)) == n_settle,
            f"{len(bodies(triangles, 1))} blocks in the settled mesh ({n_settle})")
block_nodes = {n for t in triangles if t[0] == 1 for n in t[1:]}
xy = np.array([nodes[n] for n in block_nodes])
tol = 5e-4
ok &= check(xy[:, 0].min() > -tol and xy[:, 0].max() < W + tol and xy[:, 1].min() > -tol
            and xy[:, 1].max() < H,
            f"blocks inside the container: x in [{xy[:, 0].min():.5f}, {xy[:, 0].max():.5f}], "
            f"y in [{xy[:, 1].min():.5f}, {xy[:, 1].max():.5f}] m "
            f"(0 <= x <= {W}, 0 <= y <= {H}, tolerance {tol} m)")
top = xy[:, 1].max()
ok &= check(top < 0.02 + n_settle * 0.07**2 / W,
            f"the heap fell: its top {top:.3f} m is below the initial region's top "
            f"{0.02 + n_settle * 0.07**2 / W:.3f} m")

# --------------------------------------------------------------------- heat
folder_heat = os.path.join(out, "heat")
heights = [0.03, 0.08, 0.13]
probes = "; ".join(f"p{i + 1}: 0.195, {y}" for i, y in enumerate(heights))
run(binary, heat_prm, folder_heat, f"Mesh/File name={settled}",
    "Time stepping/End time=40000", "Time stepping/Time step=2000",
    "Output/Times=", "Output/Interval=0", "Output/Write vtu=false", f"Monitors/Probes={probes}",
    f"Monitors/Lines=monitor: 0.195, 0.001, 0.195, {top:.4f}, 41")
s = summary(folder_heat)
hb = s["heat_balance"]
rel = hb["relative_imbalance"]
q_in = hb["boundary_heat_in"]
ok &= check(rel < 1e-6, f"heat balance: in {q_in.get('1', 0):.6e}, walls {q_in.get('2', 0):.6e}, "
            f"stored {hb['stored_heat']:.6e} J/m; relative imbalance {rel:.1e} (< 1e-6)")
rel_in = abs(hb["imbalance"]) / q_in["1"]
ok &= check(q_in["1"] > 0 and hb["stored_heat"] > 0 and rel_in < 1e-6,
            f"heat enters through the base and is stored; in - out - stored = "
            f"{hb['imbalance']:.3e} J/m, {rel_in:.1e} of the heat in (< 1e-6)")
p = read_csv(os.path.join(folder_heat, "probes.csv"))
t_end = max(p["p1"])
T = [p[f"p{i + 1}"][t_end][2]["T"][0] for i in range(len(heights))]
ok &= check(all(T[i] > T[i + 1] for i in range(len(T) - 1)) and T[0] > 1.0,
            "bottom-up heating: probe temperatures at t = %g s fall with height: %s C"
            % (t_end, ", ".join(f"{v:.3f}" for v in T)))
sys.exit(0 if ok else 1)
