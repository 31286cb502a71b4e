#!/usr/bin/python3
"""Render one scalar field of a 2D deal.II VTU (or PVD/PVTU) file to a PNG.

    plot_vtu.py input.vtu|input.pvtu|input.pvd output.png [--field T]
                [--title "..."] [--cmap inferno] [--label "T [C]"] [--edges]

A .pvd is resolved to its last DataSet (relative to the .pvd's folder); a
.pvtu is resolved to all its Piece sources. Files are read by VTK's own XML
reader (`vtkmodules`: Debian python3-paraview or python3-vtk9), so every encoding VTK writes or reads works: ascii,
binary (zlib-compressed or not), appended. Cells must be triangles (VTK
type 5) or quads (type 9; deal.II writes higher-order patches as subdivided
quads); Lagrange cells (types 69, 70) are drawn through their corner
vertices; lines (type 3, the crack files) are returned as pairs; the
placeholder of a crack file without cracks (a poly-vertex of no points,
type 2) is left out, and so are its cell data. Point data
is drawn with Gouraud shading, cell data flat.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

# VTK cell type -> number of corner vertices used for drawing (3: line)
CORNERS = {3: 2, 5: 3, 9: 4, 69: 3, 70: 4}
# the placeholder cell of a crack file without cracks: a poly-vertex of no
# points (meshio reads no vtu without cells)
PLACEHOLDER = 2


def read_grid(path):
    """The vtkUnstructuredGrid of a .vtu file, or of all pieces of a .pvtu,
    read by VTK's XML readers (vtkmodules)."""
    try:
        from vtkmodules.vtkIOXML import (vtkXMLPUnstructuredGridReader,
                                         vtkXMLUnstructuredGridReader)
    except ImportError:
        sys.exit("reading vtu files needs VTK's Python module (vtkmodules): apt-get install "
                 "python3-paraview, or python3-vtk9 (the two conflict; "
                 "scripts/install-dependencies.sh installs the first)")
    if not os.path.isfile(path):
        sys.exit(f"{path}: no such file")
    reader = (vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu")
              else vtkXMLUnstructuredGridReader())
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        sys.exit(f"{path}: VTK could not read it")
    return reader.GetOutput()


def grid_arrays(grid):
    """(points (n,3), connectivity, offsets (n_cells + 1), types, point
    data, cell data) of a vtkUnstructuredGrid as numpy arrays; the data as
    {name: flat array}."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    def flat(array):
        return np.zeros(0) if array is None else vtk_to_numpy(array).ravel().copy()
    points = (vtk_to_numpy(grid.GetPoints().GetData()).reshape(-1, 3)
              if grid.GetPoints() is not None else np.zeros((0, 3)))
    cells = grid.GetCells()
    conn = (flat(cells.GetConnectivityArray()) if cells is not None else np.zeros(0)).astype(np.int64)
    offs = (flat(cells.GetOffsetsArray()) if cells is not None else np.zeros(1)).astype(np.int64)
    if len(offs) == 0:
        offs = np.zeros(1, np.int64)
    types = (flat(grid.GetCellTypesArray()) if grid.GetCellTypesArray() is not None
             else np.zeros(0)).astype(np.int64)
    data = []
    for attributes in (grid.GetPointData(), grid.GetCellData()):
        data.append({attributes.GetArrayName(i): flat(attributes.GetArray(i))
                     for i in range(attributes.GetNumberOfArrays())})
    return points, conn, offs, types, data[0], data[1]


def read_vtu(path, field):
    """Return (points (n,2), polygons as list of index arrays, values, is_point_data).
    A .pvtu (one piece per MPI rank) or .pvd (its last output) is read as
    the union of its pieces."""
    if path.endswith(".pvd"):
        parts = [read_vtu(p, field) for p in resolve(path)]
        offsets = np.cumsum([0] + [len(p[0]) for p in parts])
        return (np.vstack([p[0] for p in parts]),
                [c + o for p, o in zip(parts, offsets) for c in p[1]],
                np.concatenate([p[2] for p in parts]), parts[0][3])
    points, conn, offs, types, point_data, cell_data = grid_arrays(read_grid(path))
    cells = []
    for s, t in zip(offs[:-1], types):
        if t not in CORNERS and t != PLACEHOLDER:
            sys.exit(f"{path}: unsupported VTK cell type {t}")
        if t != PLACEHOLDER:
            cells.append(conn[s:s + CORNERS[t]])
    if field in point_data:
        values, point = point_data[field], True
    elif field in cell_data:
        # the placeholder cell of a crack file without cracks left out
        values, point = cell_data[field], False
        if len(types):
            values = values.reshape(len(types), -1)[types != PLACEHOLDER].ravel()
    else:
        sys.exit(f"{path}: no field '{field}' (have: {', '.join(list(point_data) + list(cell_data))})")
    return points[:, :2].astype(float), cells, values.astype(float), point


def mesh_vertices(reference, tolerance):
    """One id per mesh vertex for the copies of it that the discrete layer's
    elements own: points whose reference positions (n x 3) [m] lie within
    @p tolerance [m] of each other share an id (connected groups, not a
    rounding grid, whose cell boundaries could split two copies)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree
    pairs = cKDTree(reference).query_pairs(tolerance, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])),
                       shape=(len(reference),) * 2)
    return connected_components(graph, directed=False)[1]


def resolve(path):
    """Map a .pvd to its last DataSet and a .pvtu to its pieces: list of .vtu files."""
    folder = os.path.dirname(path)
    if path.endswith(".pvd"):
        datasets = list(ET.parse(path).getroot().iter("DataSet"))
        if not datasets:
            sys.exit(f"{path}: no DataSet")
        return resolve(os.path.join(folder, datasets[-1].get("file")))
    if path.endswith(".pvtu"):
        return [os.path.join(folder, p.get("Source"))
                for p in ET.parse(path).getroot().iter("Piece")]
    return [path]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input", help=".vtu, .pvtu or .pvd file")
    ap.add_argument("output", help="PNG file to write")
    ap.add_argument("--field", default="T")
    ap.add_argument("--title", default=None)
    ap.add_argument("--cmap", default="inferno")
    ap.add_argument("--label", default=None, help="colorbar label (default: field name)")
    ap.add_argument("--edges", action="store_true", help="draw thin cell edges")
    args = ap.parse_args()

    pts, cells, vals = [], [], []
    point_data, offset = True, 0
    for f in resolve(args.input):
        p, c, v, point_data = read_vtu(f, args.field)
        pts.append(p)
        cells += [cell + offset for cell in c]
        vals.append(v)
        offset += len(p)
    pts, vals = np.vstack(pts), np.concatenate(vals)

    # split every quad (0,1,2,3) into triangles (0,1,2) and (0,2,3)
    tris, owner = [], []
    for i, c in enumerate(cells):
        tris.append(c[:3])
        owner.append(i)
        if len(c) == 4:
            tris.append(c[[0, 2, 3]])
            owner.append(i)
    tri = Triangulation(pts[:, 0], pts[:, 1], np.array(tris))

    span = np.ptp(pts, axis=0)
    fig, ax = plt.subplots(figsize=(7, min(7, max(2.5, 6 * span[1] / max(span[0], 1e-300) + 1.2))),
                           dpi=150)
    if point_data:
        im = ax.tripcolor(tri, vals, shading="gouraud", cmap=args.cmap)
    else:
        im = ax.tripcolor(tri, facecolors=vals[np.array(owner)], shading="flat", cmap=args.cmap)
    if args.edges:
        ax.add_collection(PolyCollection([pts[c] for c in cells], facecolors="none",
                                         edgecolors="k", linewidths=0.15, alpha=0.5))
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title(args.title if args.title is not None else f"{args.field}: {os.path.basename(args.input)}")
    cax = make_axes_locatable(ax).append_axes("right", size=0.15, pad=0.1)
    fig.colorbar(im, cax=cax, label=args.label or args.field)
    fig.tight_layout()
    fig.savefig(args.output)
    print(f"wrote {args.output}: {args.field} in [{vals.min():.6g}, {vals.max():.6g}], "
          f"{len(cells)} cells, {len(pts)} points")


if __name__ == "__main__":
    main()
