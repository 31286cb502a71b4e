#!/usr/bin/env python3
"""The Brazilian test in 3D (prm/brazilian_cylinder-3d.prm).

A rock cylinder, D = 50 mm, t = 10 mm (f_t = 5 MPa, G_I = 5 J/m^2), is
compressed across a diameter between steel jaws with circular seats
(2 alpha = 15 degrees); half of its thickness is modelled, the mid plane
being a plane of symmetry. The indirect tensile strength relation
f_t = 2 P / (pi D t) gives the peak load of the whole cylinder,

    P = pi D t f_t / 2 = 3927 N,

and the model (half the thickness) carries P / 2. Checked, bounds fixed
before the run (the 2D case's, verify_discrete_dynamics.py brazilian):
  - the peak load, 2 x the mean of the jaws' reactions (which cancels the
    cylinder's inertia force), is P within 15 %;
  - the first 10 joints to break do so in Mode I near the centre
    (|x| < 0.1 D, |y| < 0.3 D);
  - the cylinder splits on the loaded plane: the joint faces on the plane
    x = 0 (embedded in the mesh) that are broken at the end cover more than
    70 % of its area D x t / 2, and the load falls below half its peak;
  - the energy balance closes to 1 % of the external work.

usage: verify_discrete_brazilian_3d.py TMFDEM OUT [extra --set overrides]
"""
import csv
import glob
import math
import os
import sys

from common import run, summary, check

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
prm = os.path.join(ROOT, "prm", "brazilian_cylinder-3d.prm")

# the prm's and the .geo's values (scripts/plot_discrete_case.py imports
# them): diameter, full thickness, tensile strength, seat half angle
D, t, f_t, alpha = 0.05, 0.01, 5e6, math.radians(7.5)


def reference_load():
    """Peak load of the whole cylinder from f_t = 2 P / (pi D t) [N]."""
    return math.pi * D * t * f_t / 2.0


def load_history(folder):
    """(time [s], load of the whole cylinder [N]): twice the mean of the
    jaws' reactions in y (the model is half the thickness)."""
    with open(os.path.join(folder, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    time = [float(r["time"]) for r in rows]
    load = [-float(r["body1_fy"]) + float(r["body2_fy"]) for r in rows]
    return time, load


def broken_faces(folder):
    """Centroids, unit normals, areas, break times and failure modes of the
    broken joint faces of the last cracks_*.vtu."""
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import numpy as np
    from plot_vtu import grid_arrays, read_grid
    last = sorted(glob.glob(os.path.join(folder, "cracks_*.vtu")))[-1]
    points, conn, offsets, types, _, cell_data = grid_arrays(read_grid(last))
    triangles = [conn[s:e] for s, e, k in zip(offsets[:-1], offsets[1:], types) if k == 5]
    keep = [i for i, k in enumerate(types) if k == 5]
    if not triangles:
        return (np.zeros((0, 3)),) * 2 + (np.zeros(0),) * 3
    corners = points[np.array(triangles)]
    centroid = corners.mean(axis=1)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    normal = cross / (2.0 * area[:, None])
    return (centroid, normal, area, cell_data["break_time"][keep].astype(float),
            cell_data["failure_mode"][keep].astype(int))


def on_loaded_plane(centroid, normal):
    """Which broken faces are faces of the loaded plane x = 0. cracks_*.vtu
    draws a broken face where its two sides are now, so the plane's faces
    have moved with the halves: within a quarter of the mesh size there
    (0.5 mm) and facing x within 8 degrees."""
    import numpy as np
    return (np.abs(centroid[:, 0]) < 5e-4) & (np.abs(normal[:, 0]) > 0.99)


def main():
    import numpy as np
    binary, out = sys.argv[1], sys.argv[2]
    folder = os.path.join(out, "cylinder")
    run(binary, prm, folder, *sys.argv[3:])
    s = summary(folder)
    time, load = load_history(folder)
    P = reference_load()
    i = int(np.argmax(load))
    peak = load[i]
    error = peak / P - 1.0
    ok = check(abs(error) < 0.15,
               f"peak load {peak:.1f} N at {1e3 * time[i]:.4f} ms against pi D t f_t / 2 = "
               f"{P:.1f} N: {100 * error:+.2f} % (bound 15 %)")
    centroid, normal, area, broken_at, mode = broken_faces(folder)
    order = np.argsort(broken_at)[:10]
    first = centroid[order]
    ok &= check(len(order) == 10 and np.all(np.abs(first[:, 0]) < 0.1 * D)
                and np.all(np.abs(first[:, 1]) < 0.3 * D) and np.all(mode[order] == 1),
                "the first 10 joints break in Mode I near the centre (|x| < 0.1 D, "
                f"|y| < 0.3 D): x in [{first[:, 0].min():.2e}, {first[:, 0].max():.2e}] m, "
                f"y in [{first[:, 1].min():.2e}, {first[:, 1].max():.2e}] m, "
                f"modes {sorted(set(mode[order].tolist()))}")
    on_plane = on_loaded_plane(centroid, normal)
    fraction = area[on_plane].sum() / (D * t / 2.0)
    ok &= check(fraction > 0.7,
                f"the split: broken faces cover {100 * fraction:.1f} % of the loaded plane "
                f"x = 0 (> 70 %); {len(area)} broken faces in all, {on_plane.sum()} on it")
    ok &= check(load[-1] < 0.5 * peak,
                f"the load falls to {load[-1]:.1f} N at {1e3 * time[-1]:.3f} ms "
                f"(< half the peak)")
    external = s["energy"]["external_work"]
    balance = abs(s["energy"]["balance_error"]) / abs(external)
    ok &= check(balance < 0.01, f"energy balance error {balance:.2e} of the external work "
                f"{external:.4e} J (bound 1 %)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
