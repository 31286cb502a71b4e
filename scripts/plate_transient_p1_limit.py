#!/usr/bin/python3
"""The P1 limit of paper 5.1 at t = 2 s on the paper's 0.05 m mesh.

    scripts/plate_transient_p1_limit.py [ELEMENT_SIZE]

Meshes the 1 x 0.25 m plate with gmsh exactly as tmfdem does (the .geo of
source/mesh/mesh_generator.cc: Frontal-Delaunay, size h, seed 1) and, with
P1 triangles in numpy/scipy (kappa = 0.005 m^2/s, 0 C / 100 C ends, T0 = 0),
prints the max abs error along the midline y = 0.125 (101 points) at t = 2 s:
  - of the P1 interpolant of the exact solution (what any nodally exact P1
    field errs by between the nodes);
  - of the semi-discrete P1 solution (backward Euler, dt = 5e-4 s, time error
    < 0.01 C) with the consistent or lumped capacity, the Dirichlet nodes
    starting at 100 C (held at t = 0) or at the initial 0 C (the boundary
    value from the first step on: for backward Euler the L2 projection of
    the initial data onto the constrained space);
  - of backward Euler with dt = 0.05 s (the case's step).
See doc/cases/plate_transient-continuum.md.
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from matplotlib.tri import LinearTriInterpolator, Triangulation

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "scripts"))
sys.dont_write_bytecode = True
from analytic import plate_transient  # noqa: E402

KAPPA = 0.005  # m^2/s


def mesh(h):
    """Nodes (n x 2) and triangles (m x 3) of gmsh's mesh of the plate."""
    geo = f"""h = {h};
Point(1) = {{0, 0, 0, h}};
Point(2) = {{1, 0, 0, h}};
Point(3) = {{1, 0.25, 0, h}};
Point(4) = {{0, 0.25, 0, h}};
Line(1) = {{1, 2}};
Line(2) = {{2, 3}};
Line(3) = {{3, 4}};
Line(4) = {{4, 1}};
Curve Loop(1) = {{1, 2, 3, 4}};
Plane Surface(1) = {{1}};
Physical Curve(1) = {{2}};
Physical Curve(2) = {{1}};
Physical Curve(3) = {{3}};
Physical Surface(1) = {{1}};
Mesh.Algorithm = 6;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.RandomSeed = 1;
"""
    with tempfile.TemporaryDirectory() as folder:
        with open(f"{folder}/plate.geo", "w") as f:
            f.write(geo)
        subprocess.run(["gmsh", f"{folder}/plate.geo", "-2", "-format", "msh22", "-nt", "1", "-v", "0",
                        "-o", f"{folder}/plate.msh"], check=True)
        lines = open(f"{folder}/plate.msh").read().split("\n")
    i = lines.index("$Nodes")
    nodes = np.array([[float(v) for v in lines[i + 2 + k].split()[1:3]] for k in range(int(lines[i + 1]))])
    i = lines.index("$Elements")
    triangles = []
    for k in range(int(lines[i + 1])):
        v = [int(a) for a in lines[i + 2 + k].split()]
        if v[1] == 2:
            triangles.append([a - 1 for a in v[-3:]])
    triangles = np.array(triangles)
    used = np.unique(triangles)
    renumber = -np.ones(len(nodes), int)
    renumber[used] = np.arange(len(used))
    return nodes[used], renumber[triangles]


def matrices(nodes, triangles):
    """Conductivity K (kappa grad.grad), consistent and lumped capacity."""
    rows, cols, k, m, lumped = [], [], [], [], []
    for t in triangles:
        x, y = nodes[t, 0], nodes[t, 1]
        area = 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]))
        g = np.array([[y[1] - y[2], x[2] - x[1]], [y[2] - y[0], x[0] - x[2]],
                      [y[0] - y[1], x[1] - x[0]]]) / (2 * area)
        area = abs(area)
        ke = KAPPA * area * g @ g.T
        me = area / 12 * (np.ones((3, 3)) + np.eye(3))
        for a in range(3):
            for b in range(3):
                rows.append(t[a])
                cols.append(t[b])
                k.append(ke[a, b])
                m.append(me[a, b])
                lumped.append(area / 3 if a == b else 0.)
    n = len(nodes)
    return [sp.csr_matrix((v, (rows, cols)), (n, n)) for v in (k, m, lumped)]


def backward_euler(nodes, K, M, dt, t_end, hold_dirichlet_at_start):
    hot = np.abs(nodes[:, 0] - 1) < 1e-9
    held = hot | (np.abs(nodes[:, 0]) < 1e-9)
    free = ~held
    g = np.where(hot, 100., 0.)
    T = g.copy() if hold_dirichlet_at_start else np.zeros(len(nodes))
    A = (M + dt * K).tocsr()
    lu = spl.splu(A[free][:, free].tocsc())
    coupling = A[free][:, held]
    for _ in range(int(round(t_end / dt))):
        new = g.copy()
        new[free] = lu.solve((M @ T)[free] - coupling @ g[held])
        T = new
    return T


def midline_error(nodes, triangles, T, t):
    xs = np.linspace(0, 1, 101)
    field = LinearTriInterpolator(Triangulation(nodes[:, 0], nodes[:, 1], triangles), T)
    error = np.abs(field(xs, np.full(101, 0.125)) - plate_transient(xs, t))
    return error.max(), xs[error.argmax()]


if __name__ == "__main__":
    h = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
    nodes, triangles = mesh(h)
    K, M, lumped = matrices(nodes, triangles)
    print(f"h = {h} m: {len(nodes)} nodes, {len(triangles)} triangles; max abs error on the midline at t = 2 s")
    e, x = midline_error(nodes, triangles, plate_transient(nodes[:, 0], 2.0), 2.0)
    print(f"  P1 interpolant of the exact solution:                 {e:.3f} C at x = {x:.2f} m")
    for dt in (5e-4, 0.05):
        for capacity, C in (("consistent", M), ("lumped", lumped)):
            for hold in (True, False):
                T = backward_euler(nodes, K, C, dt, 2.0, hold)
                e, x = midline_error(nodes, triangles, T, 2.0)
                start = "100 C (held)" if hold else "0 C (initial)"
                print(f"  backward Euler dt = {dt:<6g} s, {capacity:10s} capacity, Dirichlet nodes "
                      f"start at {start:13s}: {e:.3f} C at x = {x:.2f} m")
