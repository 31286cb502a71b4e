#!/usr/bin/env python3
"""The discrete layer's vtu outputs on several MPI ranks, put back together.

On P > 1 ranks every output of the discrete layer is one piece per rank
(`solution_NNNNN.RRRR.vtu`: the rank's triangles and their nodes, in index
order; `cracks_NNNNN.RRRR.vtu`: its broken joints) and a
`solution_NNNNN.pvtu` record that the pvd lists. merge_pvtu() rebuilds from
the pieces the single `solution_NNNNN.vtu` that one rank writes, token by
token in tmfdem's ascii layout (9 values per line), so that outputs of
runs on different rank counts can be compared bitwise
(scripts/rank_independence.py, tests/scripts/mpi_resume_other_ranks.py).

    vtu_pieces.py OUTPUT_FOLDER MERGED_FOLDER   writes the merged view
"""
import glob
import os
import re
import shutil
import sys
import xml.etree.ElementTree as ET

ARRAY = re.compile(r'<DataArray ([^>]*)>\n(.*?)</DataArray>\n', re.S)
PIECE = re.compile(r'\.\d{4}\.vtu$')


def _arrays(text, start, end):
    """(attributes, tokens) of the DataArrays between two markers."""
    i, j = text.index(start), text.index(end)
    return [(m.group(1), m.group(2).split()) for m in ARRAY.finditer(text, i, j)]


def _data_array(attributes, tokens):
    body = "".join(t + ("\n" if (k + 1) % 9 == 0 else " ") for k, t in enumerate(tokens))
    return f"<DataArray {attributes}>\n{body}\n</DataArray>\n"


def merge_pvtu(path):
    """The text of the one-rank vtu equal to the pieces of the pvtu @p path."""
    folder = os.path.dirname(path)
    sources = [p.get("Source") for p in ET.parse(path).getroot().iter("Piece")]
    points, cells, point_data, cell_data = [], {}, {}, {}
    conn_offset = point_offset = 0
    order_point, order_cell = [], []
    for source in sources:
        with open(os.path.join(folder, source)) as f:
            text = f.read()
        (attr_points, pts), = _arrays(text, "<Points>", "</Points>")
        n_points = len(pts) // 3
        points += pts
        cell_arrays = {re.search(r'Name="([^"]*)"', a).group(1): (a, t)
                       for a, t in _arrays(text, "<Cells>", "</Cells>")}
        conn = [str(int(v) + point_offset) for v in cell_arrays["connectivity"][1]]
        offs = [str(int(v) + conn_offset) for v in cell_arrays["offsets"][1]]
        for name, values in (("connectivity", conn), ("offsets", offs),
                             ("types", cell_arrays["types"][1])):
            cells.setdefault(name, (cell_arrays[name][0], []))[1].extend(values)
        for target, order, start, end in ((point_data, order_point, "<PointData>", "</PointData>"),
                                          (cell_data, order_cell, "<CellData>", "</CellData>")):
            for a, t in _arrays(text, start, end):
                if a not in target:
                    target[a] = []
                    order.append(a)
                target[a].extend(t)
        point_offset += n_points
        conn_offset += len(cell_arrays["connectivity"][1])
    n_cells = len(cells["types"][1])
    out = ['<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" '
           'byte_order="LittleEndian">\n<UnstructuredGrid>\n'
           f'<Piece NumberOfPoints="{len(points) // 3}" NumberOfCells="{n_cells}">\n'
           '<Points>\n<DataArray type="Float64" NumberOfComponents="3" format="ascii">\n']
    out += [f"{points[3 * i]} {points[3 * i + 1]} {points[3 * i + 2]}\n"
            for i in range(len(points) // 3)]
    out.append("</DataArray>\n</Points>\n<Cells>\n")
    out += [_data_array(*cells[name]) for name in ("connectivity", "offsets", "types")]
    out.append("</Cells>\n<PointData>\n")
    out += [_data_array(a, point_data[a]) for a in order_point]
    out.append("</PointData>\n<CellData>\n")
    out += [_data_array(a, cell_data[a]) for a in order_cell]
    out.append("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
    return "".join(out)


def merged_view(folder, merged):
    """A copy of @p folder with every pvtu merged into its one-rank vtu, the
    pvd files pointing at those and the pieces left out; returns the number
    of pvtu records merged (0: @p folder has none, nothing is written)."""
    records = sorted(glob.glob(os.path.join(folder, "**", "*.pvtu"), recursive=True))
    if not records:
        return 0
    shutil.rmtree(merged, ignore_errors=True)
    for path in glob.glob(os.path.join(folder, "**", "*"), recursive=True):
        if not os.path.isfile(path) or PIECE.search(path):
            continue
        target = os.path.join(merged, os.path.relpath(path, folder))
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if path.endswith(".pvtu"):
            with open(target[:-len(".pvtu")] + ".vtu", "w") as f:
                f.write(merge_pvtu(path))
        elif path.endswith(".pvd"):
            with open(path) as f:
                text = f.read()
            with open(target, "w") as f:
                f.write(text.replace('.pvtu"', '.vtu"'))
        else:
            shutil.copy2(path, target)
    return len(records)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    n = merged_view(sys.argv[1], sys.argv[2])
    print(f"{n} pvtu records merged into {sys.argv[2]}")
