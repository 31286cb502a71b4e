#!/usr/bin/env python3
"""Rock heap in 3D (paper Sec. 5.2 with its third dimension;
prm/rock_heap-3d.prm, prm/rock_heap-heat-3d.prm), shortened
(verify_discrete_rock_heap_3d.py BINARY OUT [--settled FOLDER]: with
--settled, the settling checks on FOLDER, a run of the prm itself, and 2 h of
heating of its heap):
  generator:  Mesh/Source = block heap with Dimension = 3 is deterministic
              (the same seed gives a byte-identical mesh, another seed
              another mesh) and makes the requested number of blocks
              (connected sets of material-1 tetrahedra) and the container's
              five parts;
  settle:     a heap of fewer blocks dropped under gravity settles (kinetic
              energy < 1e-3 of the gravity work, energy balance within 1 % of
              it, the gravity work m g times the fall of the blocks' centre
              of mass within 1 %), every block vertex stays inside the
              container up to the depth a block corner sinks into it under
              the whole heap's weight m g (contact energy p int phi dV with
              phi = 4 lambda ~ 4 d / h_t: a corner d deep takes a force
              ~ 4 p d^3 / h_t, so d = (m g h_t / (4 p))^(1/3) with p = 10 E,
              h_t = the container's 0.03 m), the heap fell, and at rest the
              container carries the blocks' weight: its reaction less its
              own weight, averaged over the last 0.1 s, is m_blocks g within
              1 %;
  heat:       the settled heap heated from the base (100 C, walls 0 C) keeps
              the heat balance (heat in - heat out = stored) to 1e-6
              relative, and the blocks' mean temperature falls with height
              (bottom-up heating through the contacts)."""
import os
import sys

import numpy as np

from common import run, summary, check
from heap_mesh import bodies, generate, read_msh

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import vtu_pieces  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
# --settled FOLDER: the settling checks on a run of the prm itself (40
# blocks, W = 0.3 m; the case page's numbers), then its 2 h of heating
settled_run = sys.argv[4] if len(sys.argv) > 4 and sys.argv[3] == "--settled" else None
settle_prm = os.path.join(ROOT, "prm", "rock_heap-3d.prm")
heat_prm = os.path.join(ROOT, "prm", "rock_heap-heat-3d.prm")
ok = True
H, s_mean, drop = 0.35, 0.07, 0.02
rho, g = 2500.0, 9.81


def volume(nodes, tetrahedra, material):
    v = 0.0
    for t in tetrahedra:
        if t[0] == material:
            a, b, c, d = (np.array(nodes[k]) for k in t[1:])
            v += abs(np.dot(np.cross(b - a, c - a), d - a)) / 6
    return v


def centre_height(nodes, tetrahedra, material):
    """The volume-weighted mean height of the tetrahedra of a material [m]."""
    v_sum = vz = 0.0
    for t in tetrahedra:
        if t[0] == material:
            a, b, c, d = (np.array(nodes[k]) for k in t[1:])
            v = abs(np.dot(np.cross(b - a, c - a), d - a)) / 6
            v_sum += v
            vz += v * (a[2] + b[2] + c[2] + d[2]) / 4
    return vz / v_sum


# ---------------------------------------------------------------- generator
if settled_run is None:
    # two folders whose names differ in length: a mesher whose result depends
    # on the memory layout (gmsh's HXT does) gives two meshes here
    a = generate(binary, settle_prm, os.path.join(out, "seed1"))
    b = generate(binary, settle_prm, os.path.join(out, "seed1_again_in_another_folder"))
    c = generate(binary, settle_prm, os.path.join(out, "seed2"), "Mesh/Block heap/Seed=2")
    ok &= check(a == b, "the same seed gives a byte-identical mesh")
    ok &= check(a != c, "another seed gives another mesh")
    nodes, tetrahedra, _ = read_msh(os.path.join(out, "seed1", "mesh.msh"), 3)
    n_blocks = len(bodies(tetrahedra, 1))  # the prm's 40 blocks, W = 0.3 m
    ok &= check(n_blocks == 40, f"{n_blocks} blocks generated (40 requested)")
    n_parts = len(bodies(tetrahedra, 2))
    ok &= check(n_parts == 5, f"container: {n_parts} parts (base plate and four walls)")

# ------------------------------------------------------------------- settle
# 8 blocks in a container half as wide: a heap of two to three layers
if settled_run is None:
    folder = os.path.join(out, "settle")
    n_settle, t_settle, W = 8, 0.5, 0.15
    run(binary, settle_prm, folder, f"Mesh/Block heap/Number of blocks={n_settle}",
        f"Mesh/Block heap/Container width={W}", f"Time stepping/End time={t_settle}",
        "Output/Write vtu=false", "Output/Interval=0")
else:
    folder, n_settle, W = settled_run, 40, 0.3
    t_settle = summary(folder)["time"]
s = summary(folder)
e = s["energy"]
ratio = e["kinetic"] / e["external_work"]
ok &= check(ratio < 1e-3, f"settled: kinetic energy {e['kinetic']:.3e} J = {ratio:.1e} "
            f"of the gravity work {e['external_work']:.3e} J (< 1e-3)")
balance = abs(e["balance_error"]) / e["external_work"]
ok &= check(balance < 1e-2, f"energy balance error {e['balance_error']:.3e} J = {balance:.1e} "
            "of the gravity work (< 1e-2)")
ok &= check(s["broken_joints"] == 0, f"{s['broken_joints']} broken joints (none)")
settled = os.path.join(folder, "final_mesh.msh")
nodes, tetrahedra, triangles = read_msh(settled, 3)
blocks = bodies(tetrahedra, 1)
ok &= check(len(blocks) == n_settle, f"{len(blocks)} blocks in the settled mesh ({n_settle})")
xyz = np.array([nodes[n] for block in blocks for n in block])
nodes0, tetrahedra0, _ = read_msh(os.path.join(folder, "mesh.msh"), 3)
blocks_weight = rho * g * volume(nodes0, tetrahedra0, 1)  # the mass: reference volumes
tol = (blocks_weight * 0.03 / (4 * 10 * 1e6)) ** (1 / 3)
ok &= check(xyz[:, :2].min() > -tol and xyz[:, :2].max() < W + tol and xyz[:, 2].min() > -tol
            and xyz[:, 2].max() < H,
            f"blocks inside the container: x, y in [{xyz[:, :2].min():.5f}, "
            f"{xyz[:, :2].max():.5f}], z in [{xyz[:, 2].min():.5f}, {xyz[:, 2].max():.5f}] m "
            f"(0 <= x, y <= {W}, 0 <= z <= {H}, tolerance {tol:.4f} m)")
top = xyz[:, 2].max()
region_top = drop + n_settle * s_mean**3 / W**2
ok &= check(top < region_top, f"the heap fell: its top {top:.3f} m is below the initial "
            f"region's top {region_top:.3f} m")
fall = centre_height(nodes0, tetrahedra0, 1) - centre_height(nodes, tetrahedra, 1)
released = blocks_weight * fall
ok &= check(abs(e["external_work"] / released - 1) < 1e-2,
            f"gravity work {e['external_work']:.4f} J against m g times the fall of the blocks' "
            f"centre of mass ({1000 * fall:.2f} mm): {released:.4f} J "
            f"({(e['external_work'] / released - 1) * 100:+.3f} %, within 1 %)")
h = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
container_weight = rho * g * volume(nodes, tetrahedra, 2)
late = h["time"] >= t_settle - 0.1
carried = np.mean(h["body1_fz"][late]) - container_weight
ok &= check(abs(carried / blocks_weight - 1) < 1e-2,
            f"at rest the container carries the blocks: reaction {np.mean(h['body1_fz'][late]):.3f} N "
            f"less its own weight {container_weight:.3f} N = {carried:.3f} N against the blocks' "
            f"weight {blocks_weight:.3f} N ({(carried / blocks_weight - 1) * 100:+.2f} %, within 1 %)")

# --------------------------------------------------------------------- heat
folder_heat = os.path.join(out, "heat")
run(binary, heat_prm, folder_heat, f"Mesh/File name={settled}",
    "Time stepping/End time=7200", "Time stepping/Time step=600",
    "Output/Times=7200", "Output/Interval=0")
s = summary(folder_heat)
hb = s["heat_balance"]
rel = hb["relative_imbalance"]
q_in = hb["boundary_heat_in"]
ok &= check(rel < 1e-6, f"heat balance: in {q_in.get('1', 0):.6e}, walls {q_in.get('2', 0):.6e}, "
            f"stored {hb['stored_heat']:.6e} J; relative imbalance {rel:.1e} (< 1e-6)")
rel_in = abs(hb["imbalance"]) / q_in["1"]
ok &= check(q_in["1"] > 0 and hb["stored_heat"] > 0 and rel_in < 1e-6,
            f"heat enters through the base and is stored; in - out - stored = "
            f"{hb['imbalance']:.3e} J, {rel_in:.1e} of the heat in (< 1e-6)")
t_last, arrays = vtu_pieces.read_series(folder_heat)[-1]
z = arrays[("Points", None)].reshape(-1, 3)[:, 2]
material = np.repeat(arrays[("CellData", "material_id")], 4)  # nodes 4e..4e+3
T = arrays[("PointData", "T")]
z, Tb = z[material == 1], T[material == 1]
edges = np.linspace(0.0, top, 4)
means = [Tb[(z >= lo) & (z < hi)].mean() for lo, hi in zip(edges[:-1], edges[1:])]
ok &= check(all(means[i] > means[i + 1] for i in range(len(means) - 1)) and means[0] > 1.0,
            "bottom-up heating: the blocks' mean temperature in thirds of the heap's height "
            f"at t = {t_last:g} s falls with height: " + ", ".join(f"{v:.3f}" for v in means) + " C")
sys.exit(0 if ok else 1)
