#!/usr/bin/env python3
"""The discrete layer's vtu outputs on several MPI ranks, put back together.

On P > 1 ranks every output of the discrete layer is one piece per rank
(`solution_NNNNN.RRRR.vtu`: the rank's triangles and their nodes, in index
order; `cracks_NNNNN.RRRR.vtu`: its broken joints) and a
`solution_NNNNN.pvtu` record that the pvd lists. merge_pvtu() rebuilds from
the pieces the single `solution_NNNNN.vtu` that one rank writes, byte for
byte in tmfdem's layout (Output/Vtu format: binary, VTK XML appended raw
data, every DataArray one zlib block at level ZLIB_LEVEL with a UInt64
header, in document order after `<AppendedData encoding="raw">` and its mark
`_`; ascii, the pieces' tokens 9 values a line; either precision, Output/Vtu
precision), so that outputs of runs on different rank counts can be compared
bitwise (scripts/rank_independence.py, tests/scripts/mpi_resume_other_ranks.py).
read_arrays() decodes every DataArray of a tmfdem vtu file (either format,
either precision) to numpy.

    vtu_pieces.py OUTPUT_FOLDER MERGED_FOLDER   writes the merged view
"""
import glob
import os
import re
import shutil
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

import numpy as np

# an ascii DataArray with its values, or a declaration of an appended one
ARRAY = re.compile(r'<DataArray ([^>]*?)(?:/>\n|>\n(.*?)\n?</DataArray>\n)', re.S)
PIECE = re.compile(r'\.\d{4}\.vtu$')
DTYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2",
          "Int32": "i4", "UInt32": "u4", "Int64": "i8", "UInt64": "u8",
          "Float32": "f4", "Float64": "f8"}
# what precedes the appended raw data of a binary file, and what follows it
APPENDED = b'<AppendedData encoding="raw">\n_'
TAIL = b"\n</AppendedData>\n</VTKFile>\n"
# zlib level of tmfdem's blocks (vtu_zlib_level, discrete_output.h)
ZLIB_LEVEL = 1


def _attribute(attributes, name):
    m = re.search(f'{name}="([^"]*)"', attributes)
    return m.group(1) if m else None


def _dtype(attributes):
    return np.dtype("<" + DTYPES[_attribute(attributes, "type")])


def _split(data):
    """(XML text, appended raw bytes or None) of a tmfdem vtu file's bytes."""
    at = data.find(APPENDED)
    if at < 0:
        return data.decode(), None
    if not data.endswith(TAIL):
        raise ValueError("appended raw data not followed by a line break, "
                         "</AppendedData> and </VTKFile>")
    return data[:at].decode(), data[at + len(APPENDED):len(data) - len(TAIL)]


def _decode(attributes, body, appended):
    """The values of one DataArray: a numpy array for an appended one (UInt64
    header, zlib blocks, as tmfdem writes), the text tokens for an ascii
    one."""
    if _attribute(attributes, "format") != "appended":
        return body.split()
    at = int(_attribute(attributes, "offset"))
    n_blocks = struct.unpack_from("<Q", appended, at)[0]
    header = struct.unpack_from(f"<{3 + n_blocks}Q", appended, at)
    at += 8 * (3 + n_blocks)
    raw = []
    for size in header[3:]:
        raw.append(zlib.decompress(appended[at:at + size]))
        at += size
    return np.frombuffer(b"".join(raw), _dtype(attributes))


def _block(attributes, values):
    """One DataArray's appended raw data: header and one zlib block."""
    raw = np.ascontiguousarray(values, _dtype(attributes)).tobytes()
    block = zlib.compress(raw, ZLIB_LEVEL)
    return struct.pack("<4Q", 1, len(raw), len(raw), len(block)) + block


def _arrays(text, appended, start, end):
    """(attributes without format and offset, values) of the DataArrays
    between two markers."""
    i, j = text.index(start), text.index(end)
    return [(re.sub(r' format="[^"]*"( offset="[^"]*")?', "", m.group(1)),
             _decode(m.group(1), m.group(2), appended))
            for m in ARRAY.finditer(text, i, j)]


def _read(path):
    """(XML text, appended raw bytes or None) of the file @p path."""
    with open(path, "rb") as f:
        return _split(f.read())


def read_arrays(path):
    """Every DataArray of the tmfdem vtu file @p path in document order:
    list of (section, attributes without format and offset, values as numpy
    array); section is Points, Cells, PointData or CellData."""
    text, appended = _read(path)
    out = []
    for section in ("Points", "Cells", "PointData", "CellData"):
        for attributes, values in _arrays(text, appended, f"<{section}>", f"</{section}>"):
            dtype = _dtype(attributes)
            if not isinstance(values, np.ndarray):
                # float32 tokens: the shortest text of the float, read as
                # the nearest double, then rounded to the float it names
                values = np.array(values, dtype=float if dtype.kind == "f" else int).astype(dtype)
            out.append((section, attributes, values))
    return out


def read_series(folder, name="solution"):
    """[(time, {(section, array name): values})] of every file <name>.pvd in
    folder lists (one-rank vtu files), in its order: read_arrays() of each,
    keyed by the section (Points, Cells, PointData, CellData) and the
    DataArray's Name (None for the points)."""
    with open(os.path.join(folder, name + ".pvd")) as f:
        pvd = f.read()
    result = []
    for t, file in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', pvd):
        arrays = {}
        for section, attributes, values in read_arrays(os.path.join(folder, file)):
            arrays[(section, _attribute(attributes, "Name"))] = values
        result.append((float(t), arrays))
    return result


def _document(head, n_points, n_cells, sections):
    """The bytes of a vtu file in tmfdem's layout: @p head (up to
    <UnstructuredGrid>; binary if it names a compressor) and the arrays of
    each section, a list of (attributes without format, values)."""
    binary = "compressor=" in head
    out, appended = [head, '<UnstructuredGrid>\n'
                     f'<Piece NumberOfPoints="{n_points}" NumberOfCells="{n_cells}">\n'], []
    size = 0
    for section, arrays in zip(("Points", "Cells", "PointData", "CellData"), sections):
        out.append(f"<{section}>\n")
        for attributes, values in arrays:
            if binary:
                out.append(f'<DataArray {attributes} format="appended" offset="{size}"/>\n')
                appended.append(_block(attributes, values))
                size += len(appended[-1])
            else:
                body = "".join(t + ("\n" if (k + 1) % 9 == 0 else " ")
                               for k, t in enumerate(values))
                out.append(f'<DataArray {attributes} format="ascii">\n{body}\n</DataArray>\n')
        out.append(f"</{section}>\n")
    out.append("</Piece>\n</UnstructuredGrid>\n")
    if not binary:
        return ("".join(out) + "</VTKFile>\n").encode()
    return "".join(out).encode() + APPENDED + b"".join(appended) + TAIL


def _concatenate(parts):
    """Values of one array from every piece, joined: token lists or numpy."""
    if parts and isinstance(parts[0], np.ndarray):
        return np.concatenate(parts)
    return [t for p in parts for t in p]


def _kept(values, keep):
    """The entries of @p values where @p keep is true."""
    if isinstance(values, np.ndarray):
        return values[np.array(keep, bool)] if len(values) else values
    return [v for v, k in zip(values, keep) if k]


def _shifted(values, shift):
    if isinstance(values, np.ndarray):
        return values + values.dtype.type(shift)
    return [str(int(v) + shift) for v in values]


def merge_pvtu(path):
    """The bytes of the one-rank vtu equal to the pieces of the pvtu @p path."""
    folder = os.path.dirname(path)
    sources = [p.get("Source") for p in ET.parse(path).getroot().iter("Piece")]
    points, cells, point_data, cell_data = [], {}, {}, {}
    conn_offset = point_offset = 0
    order_point, order_cell = [], []
    head = attr_points = None
    empty_cell = {}  # cell data of a placeholder cell, by array
    for source in sources:
        text, appended = _read(os.path.join(folder, source))
        if head is None:
            head = text[:text.index("<UnstructuredGrid>")]
        (attr_points, pts), = _arrays(text, appended, "<Points>", "</Points>")
        n_points = len(pts) // 3
        points.append(pts)
        cell_arrays = {_attribute(a, "Name"): (a, t)
                       for a, t in _arrays(text, appended, "<Cells>", "</Cells>")}
        # a crack piece without cracks holds one placeholder cell (a
        # poly-vertex of no points, VTK type 2): left out here, put back
        # below if the whole has no cells
        types = cell_arrays["types"][1]
        keep = [int(t) != 2 for t in types]
        conn = _shifted(cell_arrays["connectivity"][1], point_offset)
        offs = _shifted(_kept(cell_arrays["offsets"][1], keep), conn_offset)
        for name, values in (("connectivity", conn), ("offsets", offs),
                             ("types", _kept(types, keep))):
            cells.setdefault(name, (cell_arrays[name][0], []))[1].append(values)
        for target, order, start, end in ((point_data, order_point, "<PointData>", "</PointData>"),
                                          (cell_data, order_cell, "<CellData>", "</CellData>")):
            for a, t in _arrays(text, appended, start, end):
                if a not in target:
                    target[a] = []
                    order.append(a)
                if target is cell_data:
                    if not all(keep) and a not in empty_cell:
                        empty_cell[a] = _kept(t, [not k for k in keep])[:1]
                    t = _kept(t, keep)
                target[a].append(t)
        point_offset += n_points
        conn_offset += len(cell_arrays["connectivity"][1])
    points = _concatenate(points)
    cells = {name: (a, _concatenate(v)) for name, (a, v) in cells.items()}
    if len(cells["types"][1]) == 0 and empty_cell:
        for name, value in (("offsets", 0), ("types", 2)):
            a, v = cells[name]
            cells[name] = (a, np.array([value], v.dtype) if isinstance(v, np.ndarray)
                           else [str(value)])
        for a in order_cell:
            cell_data[a] = [empty_cell[a]]
    return _document(head, len(points) // 3, len(cells["types"][1]),
                     [[(attr_points, points)],
                      [cells[name] for name in ("connectivity", "offsets", "types")],
                      [(a, _concatenate(point_data[a])) for a in order_point],
                      [(a, _concatenate(cell_data[a])) for a in order_cell]])


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
            with open(target[:-len(".pvtu")] + ".vtu", "wb") as f:
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
