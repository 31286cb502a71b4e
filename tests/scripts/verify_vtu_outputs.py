#!/usr/bin/env python3
"""The vtu outputs in both encodings (Output/Vtu format) and in ParaView.

    verify_vtu_outputs.py TMFDEM MPIRUN|none OUT formats
    verify_vtu_outputs.py TMFDEM MPIRUN|none OUT paraview

formats: the quenched disc (prm/thermal_shock_disc.prm, coarse, T0 = 800 C,
Weibull joint strengths: joints break by 6 ms) run with Output/Vtu format =
ascii and = binary at Output/Vtu precision = single and = double, on one rank
and on two: the same files; at either precision every vtu (pieces included)
holds the same DataArrays, in the same order, with the same attributes and
bitwise the same values in both encodings (decoded by scripts/vtu_pieces.py
and by VTK, vtkmodules); pvd and pvtu records identical; the binary files
hold only appended raw data (no ascii arrays, no base64), zlib-compressed;
single precision: coordinates and real arrays Float32, bitwise the double
run's values rounded to float, integer arrays equal; double: Float64. The
binary single-precision folder at least 3x smaller than the double-precision
ascii one (whole folder), binary at least 2x smaller than ascii at double
precision (vtu files); the two-rank pieces merge into the one-rank files
byte for byte at either precision, and VTK reads the two-rank pvtu; meshio
reads every vtu, also the crack file written before any joint breaks.

paraview: ParaView's own readers (pvbatch under xvfb-run) open the
continuum solution.pvd in 2D and in 3D (prm/cube_thermal_stress.prm,
hexahedra), the discrete solution.pvd, cracks.pvd and a two-rank pvtu, and
the discrete layer's 3D solution.pvd and cracks.pvd (tetrahedra and broken
faces, tests/data/discrete/cube_pull-3d.prm):
time steps, array names, sizes and value ranges as VTK's Python module
decodes them; scripts/render_paraview.py writes a PNG of the 2D disc and one
of the 3D cube in perspective with magnified displacements. Exit 77 (ctest
SKIP_RETURN_CODE) when pvbatch or xvfb-run is missing.
"""
import filecmp
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, HERE)
import vtu_pieces  # noqa: E402
from plot_vtu import grid_arrays, read_grid  # noqa: E402
from common import run, check, SKIP  # noqa: E402

binary, mpirun, out, mode = sys.argv[1:5]
mpirun = None if mpirun == "none" else mpirun
PRM = os.path.join(ROOT, "prm", "thermal_shock_disc.prm")
DISC = ["Mesh/Element size=0.8e-3", "Initial conditions/Temperature=800",
        "Discrete mechanics/Heterogeneity=Weibull", "Time stepping/End time=0.006",
        "Output/Times=0.003"]
SOLUTION = ({"displacement", "velocity", "T"},
            {"sxx", "syy", "sxy", "joint_damage", "material_id", "body"})
CRACKS = (set(), {"failure_mode", "break_time"})


def disc_run(folder, fmt, ranks=1, precision="single"):
    if not os.path.exists(os.path.join(folder, "summary.json")):
        shutil.rmtree(folder, ignore_errors=True)
        run(binary, PRM, folder, *DISC, f"Output/Vtu format={fmt}",
            f"Output/Vtu precision={precision}",
            mpirun=mpirun if ranks > 1 else None, np=ranks)
    return folder


def files(folder, ext):
    return sorted(os.path.relpath(p, folder)
                  for p in glob.glob(os.path.join(folder, f"*{ext}")))


def same_bits(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def xml_part(path):
    """The XML of a vtu file: all of an ascii one, a binary one's up to its
    appended raw data."""
    with open(path, "rb") as f:
        data = f.read()
    at = data.find(b"<AppendedData")
    return data[:at if at >= 0 else len(data)].decode()


def appended_raw(path):
    """Does the file end in appended raw data (after its mark '_')?"""
    with open(path, "rb") as f:
        data = f.read()
    return data.find(b'<AppendedData encoding="raw">\n_') > 0 and \
        data.endswith(b"\n</AppendedData>\n</VTKFile>\n")


def compare(ascii_folder, binary_folder, precision):
    """Every vtu of the two folders: same arrays and values; records equal."""
    ok = check(files(ascii_folder, ".vtu") == files(binary_folder, ".vtu") and
               files(ascii_folder, ".vtu"),
               f"{len(files(binary_folder, '.vtu'))} vtu files in both encodings")
    for record in files(ascii_folder, ".pvd") + files(ascii_folder, ".pvtu"):
        ok &= check(filecmp.cmp(os.path.join(ascii_folder, record),
                                os.path.join(binary_folder, record), shallow=False),
                    f"{record} identical")
    real = "Float32" if precision == "single" else "Float64"
    other = "Float64" if precision == "single" else "Float32"
    n_arrays = 0
    for name in files(binary_folder, ".vtu"):
        pa, pb = os.path.join(ascii_folder, name), os.path.join(binary_folder, name)
        text, text_a = xml_part(pb), xml_part(pa)
        fine = ('format="ascii"' not in text and 'format="binary"' not in text and
                'compressor="vtkZLibDataCompressor"' in text and
                text.count('format="appended"') == text.count("<DataArray") and
                appended_raw(pb))
        fine &= all(f'type="{real}"' in t and f'type="{other}"' not in t for t in (text, text_a))
        own_a, own_b = vtu_pieces.read_arrays(pa), vtu_pieces.read_arrays(pb)
        fine &= len(own_a) == len(own_b)
        for (sa, aa, va), (sb, ab, vb) in zip(own_a, own_b):
            fine &= sa == sb and aa == ab and same_bits(va, vb)
            n_arrays += 1
        vtk_a, vtk_b = grid_arrays(read_grid(pa)), grid_arrays(read_grid(pb))
        for xa, xb in zip(vtk_a[:4], vtk_b[:4]):
            fine &= same_bits(xa, xb)
        for da, db in zip(vtk_a[4:], vtk_b[4:]):
            fine &= list(da) == list(db) and all(same_bits(da[k], db[k]) for k in da)
        fine &= vtk_b[0].dtype == (np.float32 if precision == "single" else np.float64)
        expected = CRACKS if os.path.basename(name).startswith("cracks") else SOLUTION
        fine &= set(vtk_b[4]) == expected[0] and set(vtk_b[5]) == expected[1]
        if not fine:
            ok &= check(False, f"{name}: ascii and binary differ")
    return ok & check(n_arrays > 0, f"{precision} precision: {n_arrays} DataArrays bitwise "
                      f"equal in ascii and binary (attributes, order, values; read by "
                      f"vtu_pieces.py and by VTK), real arrays {real}, binary arrays appended "
                      f"raw")


def rounded(single_folder, double_folder):
    """The single-precision files hold the double ones' values rounded to
    float (integer arrays equal)."""
    ok, n_real = True, 0
    for name in files(double_folder, ".vtu"):
        a = vtu_pieces.read_arrays(os.path.join(single_folder, name))
        b = vtu_pieces.read_arrays(os.path.join(double_folder, name))
        fine = len(a) == len(b)
        for (sa, aa, va), (sb, ab, vb) in zip(a, b):
            fine &= sa == sb and aa.replace("Float32", "Float64") == ab
            if vb.dtype == np.float64:
                fine &= va.dtype == np.float32 and same_bits(va, vb.astype(np.float32))
                n_real += 1
            else:
                fine &= same_bits(va, vb)
        if not fine:
            ok &= check(False, f"{name}: the single-precision values are not the double "
                        f"ones rounded to float")
    return ok & check(n_real > 0, f"{n_real} real arrays of {len(files(double_folder, '.vtu'))} "
                      f"files: single precision = the double values rounded to float, bitwise")


def size(folder, ext=""):
    return sum(os.path.getsize(p) for p in glob.glob(os.path.join(folder, "*" + ext)))


def formats():
    ok = True
    folders = {}
    for ranks in ([1, 2] if mpirun else [1]):
        for precision in ("single", "double"):
            for fmt in ("ascii", "binary"):
                tag = f"np{ranks}_{fmt}" + ("" if precision == "single" else "_double")
                folders[ranks, fmt, precision] = disc_run(os.path.join(out, tag), fmt, ranks,
                                                          precision)
            print(f"-- {ranks} rank(s), {precision} precision", flush=True)
            ok &= compare(folders[ranks, "ascii", precision], folders[ranks, "binary", precision],
                          precision)
    ok &= rounded(folders[1, "binary", "single"], folders[1, "binary", "double"])
    a, b = folders[1, "ascii", "double"], folders[1, "binary", "double"]
    ratio = size(a, ".vtu") / size(b, ".vtu")
    ok &= check(ratio >= 2, f"double precision: vtu files: ascii {size(a, '.vtu')} bytes, binary "
                f"{size(b, '.vtu')} bytes ({ratio:.1f}x smaller)")
    s = folders[1, "binary", "single"]
    ratio = size(a) / size(s)
    ok &= check(ratio >= 3, f"the binary single-precision folder {size(s)} bytes against the "
                f"double-precision ascii one {size(a)} bytes: {ratio:.2f}x smaller (>= 3); vtu "
                f"files {size(a, '.vtu')} -> {size(s, '.vtu')} bytes "
                f"({size(a, '.vtu') / size(s, '.vtu'):.2f}x)")
    first = os.path.join(s, "cracks_00000.vtu")
    _, _, _, types, _, cell_data = grid_arrays(read_grid(first))
    ok &= check(list(types) == [2] and cell_data["failure_mode"].tolist() == [0],
                "cracks_00000.vtu (no broken joint): one placeholder cell, a poly-vertex of "
                "no points, failure_mode 0")
    _, _, _, types, _, _ = grid_arrays(read_grid(sorted(glob.glob(os.path.join(s, "cracks_*.vtu")))[-1]))
    ok &= check(len(types) > 0 and set(types.tolist()) == {3},
                f"the last crack file: {len(types)} line cells")
    if mpirun:
        for precision in ("single", "double"):
            one = folders[1, "binary", precision]
            merged = os.path.join(out, f"np2_binary_{precision}_merged")
            records = vtu_pieces.merged_view(folders[2, "binary", precision], merged)
            same = [n for n in files(one, ".vtu")
                    if filecmp.cmp(os.path.join(one, n), os.path.join(merged, n), shallow=False)]
            ok &= check(records > 0 and len(same) == len(files(one, ".vtu")),
                        f"{precision} precision: 2-rank binary pieces merged ({records} pvtu "
                        f"records): {len(same)} of {len(files(one, '.vtu'))} files byte for "
                        f"byte the 1-rank ones")
            pvtu = files(folders[2, "binary", precision], ".pvtu")[-1]
            points = grid_arrays(read_grid(os.path.join(folders[2, "binary", precision], pvtu)))[0]
            one_points = grid_arrays(read_grid(os.path.join(one, pvtu[:-len(".pvtu")] + ".vtu")))[0]
            ok &= check(same_bits(points, one_points),
                        f"{precision} precision: VTK reads the 2-rank {pvtu}: the 1-rank "
                        f"file's {len(points)} points ({points.dtype})")
    try:
        import meshio
    except ImportError:
        meshio = None
        print("meshio not installed (python3-meshio): its check left out")
    if meshio:
        import warnings
        read, empty = 0, []
        for key in sorted(folders):
            folder = folders[key]
            for name in files(folder, ".vtu"):
                if 'NumberOfCells="0"' in xml_part(os.path.join(folder, name)):
                    # a piece of a rank without triangles (the coarse disc's
                    # 508 triangles are one chunk): meshio reads no vtu
                    # without cells
                    empty.append(f"{os.path.basename(folder)}/{name}")
                    continue
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    mesh = meshio.read(os.path.join(folder, name))
                read += 1
                if name == "cracks_00000.vtu":
                    ok &= check(sum(len(c.data) for c in mesh.cells) == 0,
                                f"meshio reads {os.path.basename(folder)}/{name}: "
                                f"{len(mesh.points)} points, no cells")
                elif name == "solution_00000.vtu" and key[0] == 1:
                    mine = vtu_pieces.read_arrays(os.path.join(folder, name))[0][2]
                    ok &= check(same_bits(np.asarray(mesh.points).ravel(), mine),
                                f"meshio reads {os.path.basename(folder)}/{name}: its "
                                f"{len(mesh.points)} points bitwise ({mine.dtype})")
        ok &= check(read > 0 and all(".0000.vtu" in e for e in empty),
                    f"meshio {meshio.__version__} reads all {read} vtu files with cells "
                    f"(left out: {len(empty)} pieces of no cells, of rank 0, e.g. "
                    f"{empty[0] if empty else '-'})")
    return ok


def expected(path, time, times):
    """What ParaView must find in @p path at @p time: from VTK's Python
    module (the file of that time in a pvd)."""
    target = path
    if path.endswith(".pvd"):
        root = ET.parse(path).getroot()
        files_by_time = {float(d.get("timestep")): d.get("file") for d in root.iter("DataSet")}
        target = os.path.join(os.path.dirname(path), files_by_time[time])
    points, _, _, types, point_data, cell_data = grid_arrays(read_grid(target))

    def spans(data, n):
        out = {}
        for name, values in data.items():
            first = values.reshape(n, -1)[:, 0] if n else values
            finite = first[np.isfinite(first)]
            out[name] = [float(finite.min()), float(finite.max())] if len(finite) else None
        return out
    return {"file": path, "times": times, "time": time, "n_points": len(points),
            "n_cells": len(types), "point_data": spans(point_data, len(points)),
            "cell_data": spans(cell_data, len(types))}


def pvd_times(path):
    return [float(d.get("timestep")) for d in ET.parse(path).getroot().iter("DataSet")]


def paraview():
    pvbatch, xvfb = shutil.which("pvbatch"), shutil.which("xvfb-run")
    if not pvbatch or not xvfb:
        print(f"SKIP: pvbatch ({pvbatch}) or xvfb-run ({xvfb}) missing "
              "(Debian paraview python3-paraview xvfb, scripts/install-dependencies.sh)")
        sys.exit(SKIP)
    disc = disc_run(os.path.join(out, "np1_binary"), "binary")
    continuum = os.path.join(out, "continuum")
    if not os.path.exists(os.path.join(continuum, "summary.json")):
        run(binary, os.path.join(ROOT, "prm", "plate_transient-continuum.prm"), continuum,
            "Time stepping/End time=10", "Output/Times=2")
    # a 3D continuum solution: the thermoelastic cube (hexahedra, Q2)
    cube = os.path.join(out, "continuum_3d")
    if not os.path.exists(os.path.join(cube, "summary.json")):
        run(binary, os.path.join(ROOT, "prm", "cube_thermal_stress.prm"), cube)
    # a 3D discrete solution: the cube of tetrahedra pulled until joints
    # break (solution: tetrahedra; cracks: broken faces as triangles)
    discrete_3d = os.path.join(out, "discrete_3d")
    if not os.path.exists(os.path.join(discrete_3d, "summary.json")):
        run(binary, os.path.join(ROOT, "tests", "data", "discrete", "cube_pull-3d.prm"),
            discrete_3d, "Output/Write vtu=true", "Output/Times=1e-4")
    spec = []
    for pvd in (os.path.join(continuum, "solution.pvd"), os.path.join(cube, "solution.pvd"),
                os.path.join(disc, "solution.pvd"), os.path.join(disc, "cracks.pvd"),
                os.path.join(discrete_3d, "solution.pvd"),
                os.path.join(discrete_3d, "cracks.pvd")):
        times = pvd_times(pvd)
        spec.append(expected(pvd, times[-1], times))
    first_cracks = os.path.join(disc, "cracks.pvd")
    spec.append(expected(first_cracks, pvd_times(first_cracks)[0], pvd_times(first_cracks)))
    if mpirun:
        ranks = disc_run(os.path.join(out, "np2_binary"), "binary", 2)
        for stem in ("solution", "cracks"):
            spec.append(expected(sorted(glob.glob(os.path.join(ranks, f"{stem}_*.pvtu")))[-1],
                                 0.0, []))
    spec_file = os.path.join(out, "paraview_spec.json")
    with open(spec_file, "w") as f:
        json.dump(spec, f, indent=1)
    # pvbatch runs the Python it was built with: a PYTHONHOME or PYTHONPATH of
    # another interpreter (pyenv, conda) would hide ParaView's own modules
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHOME", "PYTHONPATH")}
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    ok = True
    xvfb = [xvfb, "-a", "-s", "-screen 0 1280x1024x24"]
    for cmd in (xvfb + [pvbatch, os.path.join(HERE, "paraview_check.py"), spec_file],
                xvfb + [pvbatch, os.path.join(ROOT, "scripts", "render_paraview.py"),
                        os.path.join(disc, "solution.pvd"), os.path.join(out, "disc_T.png"),
                        "--field", "T", "--time", "0.003", "--size", "800x600"],
                # 3D in perspective, the pieces moved apart by their
                # displacements magnified
                xvfb + [pvbatch, os.path.join(ROOT, "scripts", "render_paraview.py"),
                        os.path.join(discrete_3d, "solution.pvd"),
                        os.path.join(out, "cube_3d.png"), "--field", "displacement",
                        "--view-from", "1,0.7,1.3", "--warp", "10", "--size", "800x600"],
                # only the cells wholly in x <= 0.04 m: two of the cube's five
                # columns of hexahedra, each split into tetrahedra
                xvfb + [pvbatch, os.path.join(ROOT, "scripts", "render_paraview.py"),
                        os.path.join(discrete_3d, "solution.pvd"),
                        os.path.join(out, "cube_3d_crop.png"), "--field", "displacement",
                        "--view-from", "1,0.7,1.3", "--view-up", "0,0,1",
                        "--crop=-0.001,0.0401,-0.001,0.101,-0.001,0.101", "--size", "800x600"]):
        # a second try: xvfb-run -a can race another X server for a display
        for attempt in (1, 2):
            print("$", " ".join(cmd), flush=True)
            r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
            print(r.stdout[-6000:], r.stderr[-2000:], flush=True)
            if r.returncode == 0 or "FAIL:" in r.stdout:
                break
        ok &= check(r.returncode == 0, f"{os.path.basename(cmd[5])} exit status {r.returncode}")
        if "--crop" in " ".join(cmd):
            shown = re.search(r"(\d+) cells, (\d+) of them shown", r.stdout)
            ok &= check(shown is not None and 5 * int(shown.group(2)) == 2 * int(shown.group(1)),
                        "--crop to x <= 0.04 m shows two fifths of the cube's cells: " +
                        (f"{shown.group(2)} of {shown.group(1)}" if shown else "no count printed"))
    for png in (os.path.join(out, "disc_T.png"), os.path.join(out, "cube_3d.png"),
                os.path.join(out, "cube_3d_crop.png")):
        with open(png, "rb") if os.path.exists(png) else open(os.devnull, "rb") as f:
            head = f.read(8)
        ok &= check(head == b"\x89PNG\r\n\x1a\n" and os.path.getsize(png) > 5000,
                    f"render_paraview.py wrote {png} "
                    f"({os.path.getsize(png) if os.path.exists(png) else 0} bytes)")
    return ok


os.makedirs(out, exist_ok=True)
ok = formats() if mode == "formats" else paraview()
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
