#!/usr/bin/python3
"""Opening of the cracks of a discrete run at the mesh vertices, from a
solution_*.vtu of the exploded mesh (every triangle has its own nodes).

    crack_opening.py OUTPUT_FOLDER [--time SECONDS] [--threshold METRES]

The nodes of the triangles that share a mesh vertex are grouped by their
reference position (current position minus displacement); the opening at the
vertex is the largest distance between two of its nodes [m]. Intact joints
keep it at the penalty's elastic gap (nanometres); a vertex on a crack face
pair opens by the crack's opening there. Prints the vertices whose opening
exceeds --threshold (default 1e-6 m) with their reference radius [m] from
the origin, polar angle [deg] and opening [mm], and the elastic gap (median
over all shared vertices). --time picks the solution written nearest that
time [s] instead of the last one. Needs only numpy. Float32 files
(Output/Vtu precision = single, the default) hold the positions to about
1e-7 of the coordinates: openings (and elastic gaps) smaller than that are
not resolved there; write Vtu precision = double for them.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import read_vtu  # noqa: E402
from count_radial_cracks import series_entry  # noqa: E402


def solution_file(folder, time=None):
    """(time [s], path) of the last solution_*.vtu, or of the one written
    nearest time [s]."""
    return series_entry(folder, "solution", time)


def vertex_groups(reference):
    """The vertex of each node (0, 1, ...): nodes whose reference positions
    (n, 2) [m] agree to within a tolerance are one. They agree to round-off
    of the file's values: about 1e-8 of the coordinates in a Float32 file
    (Output/Vtu precision = single), 1e-16 in a Float64 one; the tolerance,
    1e-6 of the largest coordinate and at least 1e-7 m, is far above that
    and far below the distance between two vertices of a mesh. Nodes are
    chained along x (sorted, split where consecutive x differ by more than
    the tolerance), then each chain along y, so that no grid line can
    separate the copies of one vertex."""
    tolerance = max(1e-7, 1e-6 * np.abs(reference).max(initial=0.0))
    n = len(reference)
    by_x = np.argsort(reference[:, 0], kind="stable")
    chain = np.empty(n, np.int64)
    chain[by_x] = np.cumsum(np.concatenate(
        [[True], np.diff(reference[by_x, 0]) > tolerance])) - 1
    by_y = np.lexsort((reference[:, 1], chain))
    vertex = np.empty(n, np.int64)
    vertex[by_y] = np.cumsum(np.concatenate(
        [[True], (np.diff(chain[by_y]) != 0) |
         (np.diff(reference[by_y, 1]) > tolerance)])) - 1
    return vertex


def vertex_openings(vtu):
    """Per mesh vertex shared by two or more nodes: (reference radius [m],
    polar angle [deg], opening [m]), as three arrays."""
    pts, _, u, _ = read_vtu(vtu, "displacement")
    u = np.asarray(u).reshape(len(pts), -1)[:, :2]
    reference = pts - u
    vertex = vertex_groups(reference)
    counts = np.bincount(vertex)
    order = np.argsort(vertex, kind="stable")
    starts = np.concatenate([[0], np.cumsum(counts)])
    r, angle, opening = [], [], []
    for v in np.nonzero(counts >= 2)[0]:
        nodes = order[starts[v]:starts[v + 1]]
        p = pts[nodes]
        gap = np.max(np.linalg.norm(p[:, None, :] - p[None, :, :], axis=2))
        x, y = reference[nodes[0]]
        r.append(np.hypot(x, y))
        angle.append(np.degrees(np.arctan2(y, x)) % 360.)
        opening.append(gap)
    return np.array(r), np.array(angle), np.array(opening)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--time", type=float, default=None)
    parser.add_argument("--threshold", type=float, default=1e-6)
    args = parser.parse_args()
    t, vtu = solution_file(args.folder, args.time)
    r, angle, opening = vertex_openings(vtu)
    print(f"{vtu}: t = {t:g} s; elastic gap (median over {len(r)} shared vertices) "
          f"{np.median(opening):.2e} m")
    print("      r [m]  angle [deg]  opening [mm]  opening / r")
    for k in np.argsort(r):
        if opening[k] > args.threshold:
            print(f"{r[k]:11.4f} {angle[k]:12.1f} {1e3 * opening[k]:13.4f} "
                  f"{opening[k] / r[k]:12.4e}")


if __name__ == "__main__":
    main()
