#!/usr/bin/python3
"""Crack pattern over the temperature field of a discrete thermo-mechanics run.

    plot_thermal_cracking.py OUTPUT_FOLDER out.png [--times t1,t2,...]
                             [--title "..."] [--zoom x0,x1,y0,y1]

Draws, for each requested output time (the nearest written one; default: the
last), the temperature on the exploded mesh (solution_*.vtu) with the broken
joints (cracks_*.vtu) as black lines over it, in the current configuration.

A 3D run (tetrahedra) is seen from +z: the temperature on the boundary faces
that face up, with the broken faces projected on the xy plane in black (a
crack through the thickness shows as its trace); a last panel shows the
crack surfaces of the last time in perspective inside the body's outline
(its boundary faces), coloured by the time each face broke.
Needs numpy, matplotlib and VTK's Python module (plot_vtu.read_grid).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import grid_arrays, mesh_vertices, read_grid, read_vtu  # noqa: E402


def datasets(folder, series):
    """[(time, path)] of a pvd series."""
    pvd = os.path.join(folder, series + ".pvd")
    if not os.path.exists(pvd):
        sys.exit(f"{pvd}: not found (is {folder} the output of a discrete run?)")
    return [(float(d.get("timestep")), os.path.join(folder, d.get("file")))
            for d in ET.parse(pvd).getroot().iter("DataSet")]


def nearest(items, t):
    return min(items, key=lambda item: abs(item[0] - t))


def finish_axes(ax, zoom):
    """Equal axes in mm, cropped to zoom = (x0, x1, y0, y1) [m], no ticks."""
    ax.set_aspect("equal")
    if zoom:
        ax.set_xlim(zoom[0] * 1e3, zoom[1] * 1e3)
        ax.set_ylim(zoom[2] * 1e3, zoom[3] * 1e3)
    ax.set_xticks([])
    ax.set_yticks([])


def draw(ax, solution_vtu, crack_vtu, t_range, zoom=None):
    pts, cells, T, _ = read_vtu(solution_vtu, "T")
    tri = Triangulation(pts[:, 0] * 1e3, pts[:, 1] * 1e3, np.array(cells))
    im = ax.tripcolor(tri, T, shading="gouraud", cmap="coolwarm",
                      vmin=t_range[0], vmax=t_range[1])
    cpts, lines, _, _ = read_vtu(crack_vtu, "break_time")
    if lines:
        segments = [cpts[line] * 1e3 for line in lines]
        ax.add_collection(LineCollection(segments, colors="k", linewidths=1.0))
    finish_axes(ax, zoom)
    return im, len(lines)


def tetrahedral(solution_vtu):
    """True if the output holds tetrahedra (a 3D run)."""
    types = grid_arrays(read_grid(solution_vtu))[3]
    return len(types) > 0 and int(types[0]) == 10


def boundary_faces(solution_vtu):
    """(faces (m x 3 point indices), outward unit normals (m x 3), points
    (current), T at the points) of a 3D output: the tetrahedra's faces that
    no other tetrahedron shares, matched on the reference position (the
    points less `displacement`: every tetrahedron owns its nodes)."""
    points, conn, offs, types, point_data, _ = grid_arrays(read_grid(solution_vtu))
    tets = conn.reshape(-1, 4)
    reference = points - point_data["displacement"].reshape(-1, 3)
    # copies within 1e-5 of the extent: the vtu's single-precision points
    vertex = mesh_vertices(reference, 1e-5 * np.ptp(reference, axis=0).max())
    local = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]])
    faces = tets[:, local].reshape(-1, 3)
    opposite = np.repeat(tets, 4, axis=0)[np.arange(len(faces)), np.tile([0, 1, 2, 3], len(tets))]
    ids = np.sort(vertex[faces], axis=1)
    _, first, count = np.unique(ids, axis=0, return_index=True, return_counts=True)
    outer = first[count == 1]
    faces, opposite = faces[outer], opposite[outer]
    x = points[faces]
    normal = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    # outward: away from the tetrahedron's fourth corner
    flip = np.einsum("ij,ij->i", normal, points[opposite] - x[:, 0]) > 0
    normal[flip] *= -1
    return faces, normal, points, point_data["T"]


def draw_3d(ax, solution_vtu, crack_vtu, t_range, zoom=None):
    """Top view of a 3D output: T on the faces that face +z, crack traces."""
    faces, normal, points, T = boundary_faces(solution_vtu)
    up = faces[normal[:, 2] > 0.9]
    tri = Triangulation(points[:, 0] * 1e3, points[:, 1] * 1e3, up)
    im = ax.tripcolor(tri, T, shading="gouraud", cmap="coolwarm",
                      vmin=t_range[0], vmax=t_range[1])
    # tetrahedra with a damaged (softening, unbroken) joint: grey dots at
    # their centroids
    points_all, conn, _, _, _, cell_data = grid_arrays(read_grid(solution_vtu))
    damaged = cell_data["joint_damage"] > 0
    if damaged.any():
        centroid = points_all[conn.reshape(-1, 4)[damaged]].mean(axis=1) * 1e3
        ax.scatter(centroid[:, 0], centroid[:, 1], s=1.5, c="0.35", linewidths=0)
    cpts, polygons, _, _ = read_vtu(crack_vtu, "break_time")
    if polygons:
        ax.add_collection(PolyCollection([cpts[p] * 1e3 for p in polygons], facecolors="k",
                                         edgecolors="k", linewidths=0.8))
    finish_axes(ax, zoom)
    return im, len(polygons), int(damaged.sum())


def draw_crack_surfaces(fig, position, solution_vtu, crack_vtu, t, scale, unit):
    """The crack surfaces of one 3D output in perspective, coloured by the
    time each face broke, inside the body's outline (boundary faces)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ax = fig.add_subplot(position, projection="3d")
    faces, _, points, _ = boundary_faces(solution_vtu)
    ax.add_collection3d(Poly3DCollection(points[faces] * 1e3, facecolors=(0.6, 0.6, 0.6, 0.06),
                                         edgecolors=(0.3, 0.3, 0.3, 0.05), linewidths=0.2))
    cpts, conn, offs, types, _, cell_data = grid_arrays(read_grid(crack_vtu))
    triangles = types == 5
    if triangles.any():
        corners = conn[np.concatenate([np.arange(offs[i], offs[i + 1])
                                       for i in np.flatnonzero(triangles)])].reshape(-1, 3)
        when = cell_data["break_time"][triangles] * scale
        norm = matplotlib.colors.Normalize(when.min(), max(when.max(), t * scale))
        ax.add_collection3d(Poly3DCollection(cpts[corners] * 1e3,
                                             facecolors=plt.cm.viridis(norm(when)),
                                             edgecolors="k", linewidths=0.1))
        mappable = plt.cm.ScalarMappable(norm=norm, cmap="viridis")
        fig.colorbar(mappable, ax=ax, shrink=0.6, pad=0.02, label=f"broken at [{unit}]")
    lo, hi = points.min(axis=0) * 1e3, points.max(axis=0) * 1e3
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=35, azim=-60)
    ax.set_axis_off()
    ax.set_title(f"crack surfaces at t = {t * scale:.4g} {unit}\n"
                 f"{int(triangles.sum())} broken faces", fontsize=9)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("output")
    ap.add_argument("--times", default=None,
                    help="comma-separated output times [s] (default: the last)")
    ap.add_argument("--time-unit", default="s", choices=["s", "ms", "h"])
    ap.add_argument("--title", default=None)
    ap.add_argument("--zoom", default=None, help="x0,x1,y0,y1 [m]")
    args = ap.parse_args()

    solutions = datasets(args.folder, "solution")
    cracks = datasets(args.folder, "cracks")
    if not solutions:
        sys.exit(f"{args.folder}/solution.pvd: no DataSet")
    wanted = ([float(t) for t in args.times.split(",")] if args.times
              else [solutions[-1][0]])
    picked = [(nearest(solutions, t), nearest(cracks, t)) for t in wanted]
    # one colour range for all panels: the initial and extreme temperatures
    lo, hi = np.inf, -np.inf
    for (_, s), _ in picked + [((0., solutions[0][1]), None)]:
        T = grid_arrays(read_grid(s))[4]["T"]
        lo, hi = min(lo, T.min()), max(hi, T.max())
    zoom = [float(v) for v in args.zoom.split(",")] if args.zoom else None
    scale = {"s": 1., "ms": 1e3, "h": 1. / 3600.}[args.time_unit]
    n = len(picked)
    three_d = tetrahedral(picked[0][0][1])
    fig = plt.figure(figsize=(3.2 * (n + 2 * three_d) + 0.8, 3.8), dpi=150)
    grid = fig.add_gridspec(1, n + three_d, width_ratios=[1] * n + [2] * three_d)
    axes = [fig.add_subplot(grid[0, i]) for i in range(n)]
    counts = []
    for ax, ((t, s), (_, c)) in zip(axes, picked):
        if three_d:
            im, n_broken, n_damaged = draw_3d(ax, s, c, (lo, hi), zoom)
            ax.set_title(f"t = {t * scale:.4g} {args.time_unit}, seen from +z\n"
                         f"{n_broken} broken faces, {n_damaged} tetrahedra\nwith a damaged "
                         "joint (grey)", fontsize=9)
        else:
            im, n_broken = draw(ax, s, c, (lo, hi), zoom)
            ax.set_title(f"t = {t * scale:.4g} {args.time_unit}\n{n_broken} broken joints",
                         fontsize=9)
        counts.append(n_broken)
    fig.colorbar(im, ax=axes, label="T [C]", shrink=0.85)
    if three_d:
        (t, s), (_, c) = picked[-1]
        draw_crack_surfaces(fig, grid[0, n], s, c, t, scale, args.time_unit)
    if args.title:
        fig.suptitle(args.title, fontsize=10, **({"y": 1.04} if three_d else {}))
    fig.savefig(args.output, bbox_inches="tight")
    print(f"wrote {args.output}: {n} panel(s), T in [{lo:.4g}, {hi:.4g}] C, broken "
          f"{'faces' if three_d else 'joints'} per panel: {', '.join(map(str, counts))}")


if __name__ == "__main__":
    main()
