#!/usr/bin/python3
"""Render one scalar field of a 2D deal.II VTU (or PVD/PVTU) file to a PNG.

    plot_vtu.py input.vtu|input.pvtu|input.pvd output.png [--field T]
                [--title "..."] [--cmap inferno] [--label "T [C]"] [--edges]

A .pvd is resolved to its last DataSet (relative to the .pvd's folder); a
.pvtu is resolved to all its Piece sources. DataArrays may be ascii, base64
binary, or base64 binary compressed with zlib (vtkZLibDataCompressor), with
UInt32 or UInt64 headers. Cells must be triangles (VTK type 5) or quads
(type 9; deal.II writes higher-order patches as subdivided quads); Lagrange
cells (types 69, 70) are drawn through their corner vertices. Point data is
drawn with Gouraud shading, cell data flat. Needs only numpy and matplotlib.
"""
import argparse
import base64
import os
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

VTK_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2",
             "Int32": "i4", "UInt32": "u4", "Int64": "i8", "UInt64": "u8",
             "Float32": "f4", "Float64": "f8"}
# VTK cell type -> number of corner vertices used for drawing (3: line)
CORNERS = {3: 2, 5: 3, 9: 4, 69: 3, 70: 4}


def _split_b64(text, n_header_bytes):
    """Decode a header of n_header_bytes and the data that follows it. The
    two may be base64-encoded separately (deal.II, VTK) or as one stream."""
    n_chars = -(-n_header_bytes // 3) * 4
    if n_header_bytes % 3 and not text[:n_chars].endswith("="):
        raw = base64.b64decode(text)  # one stream: split the bytes
        return raw[:n_header_bytes], raw[n_header_bytes:]
    return base64.b64decode(text[:n_chars])[:n_header_bytes], base64.b64decode(text[n_chars:])


def read_dataarray(elem, compressed, header, order):
    """Return the DataArray element's values as a flat numpy array."""
    dtype = np.dtype(order + VTK_TYPES[elem.get("type")])
    text = "".join((elem.text or "").split())
    fmt = elem.get("format", "ascii")
    if fmt == "ascii":
        return np.array((elem.text or "").split(), dtype=dtype)
    if fmt != "binary":
        sys.exit(f"unsupported DataArray format '{fmt}' (appended data is not handled)")
    hsize = header.itemsize
    if compressed:
        # header: [n_blocks, block_size, last_block_size, comp_size_1 .. comp_size_n]
        first = base64.b64decode(text[:-(-hsize // 3) * 4])[:hsize]
        n_blocks = int(np.frombuffer(first, header)[0])
        head, data = _split_b64(text, (3 + n_blocks) * hsize)
        sizes = np.frombuffer(head, header)[3:]
        blocks, pos = [], 0
        for size in sizes:
            blocks.append(zlib.decompress(data[pos:pos + int(size)]))
            pos += int(size)
        raw = b"".join(blocks)
    else:
        head, raw = _split_b64(text, hsize)
        raw = raw[:int(np.frombuffer(head, header)[0])]
    return np.frombuffer(raw, dtype)


def read_vtu(path, field):
    """Return (points (n,2), polygons as list of index arrays, values, is_point_data).
    A .pvtu (one piece per MPI rank) or .pvd (its last output) is read as
    the union of its pieces."""
    if path.endswith(".pvtu") or path.endswith(".pvd"):
        parts = [read_vtu(p, field) for p in resolve(path)]
        offsets = np.cumsum([0] + [len(p[0]) for p in parts])
        return (np.vstack([p[0] for p in parts]),
                [c + o for p, o in zip(parts, offsets) for c in p[1]],
                np.concatenate([p[2] for p in parts]), parts[0][3])
    root = ET.parse(path).getroot()
    compressed = root.get("compressor") is not None
    header = np.dtype(VTK_TYPES[root.get("header_type", "UInt32")])
    order = ">" if root.get("byte_order", "LittleEndian") == "BigEndian" else "<"
    header = header.newbyteorder(order)
    pts_all, cells_all, vals_all, point_data = [], [], [], True
    offset = 0
    for piece in root.iter("Piece"):
        def arr(e):
            return read_dataarray(e, compressed, header, order)
        pts = arr(piece.find("Points/DataArray")).astype(float).reshape(-1, 3)[:, :2]
        cell_arrays = {e.get("Name"): arr(e) for e in piece.find("Cells")}
        conn, offs, types = (cell_arrays[k].astype(np.int64)
                             for k in ("connectivity", "offsets", "types"))
        starts = np.concatenate(([0], offs[:-1]))
        for s, t in zip(starts, types):
            if t not in CORNERS:
                sys.exit(f"{path}: unsupported VTK cell type {t}")
            cells_all.append(conn[s:s + CORNERS[t]] + offset)
        found = None
        for section, is_point in (("PointData", True), ("CellData", False)):
            for e in piece.findall(f"{section}/DataArray"):
                if e.get("Name") == field:
                    found, point_data = arr(e).astype(float), is_point
        if found is None:
            names = [e.get("Name") for sec in ("PointData", "CellData")
                     for e in piece.findall(f"{sec}/DataArray")]
            sys.exit(f"{path}: no field '{field}' (have: {', '.join(names)})")
        pts_all.append(pts)
        vals_all.append(found)
        offset += len(pts)
    return np.vstack(pts_all), cells_all, np.concatenate(vals_all), point_data


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
