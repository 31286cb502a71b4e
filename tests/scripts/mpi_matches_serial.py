#!/usr/bin/python3
"""The continuum solvers under mpirun -np 2 give the serial answer (to
solver tolerance): the thick cylinder (heat with AMR on p4est
quadrilaterals, then thermal stress on the same mesh), the transient
plate (heat on a shared triangle mesh), the restrained sheet, and in 3D the
thick cylinder slice (heat, then thermal stress on p4est hexahedra; Q2
displacement, the ranks' agreement does not depend on the degree) and the
free cube on tetrahedra (a shared mesh)."""
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv, read_csv_xyz


def read_lines(path):
    """lines.csv of a 2D or 3D run -> name -> time -> (..., fields)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    if header[:5] == ["time", "name", "x", "y", "z"]:
        return {name: {t: (points, None, fields) for t, (points, fields) in by_time.items()}
                for name, by_time in read_csv_xyz(path).items()}
    return read_csv(path)


binary, mpirun, prm_dir, out = sys.argv[1:5]
ok = True
for case, line, extra in (("thick_cylinder-continuum", "radial", []),
                          ("plate_transient-continuum", "midline", []),
                          ("sheet_restrained_expansion-continuum", "diagonal", []),
                          ("thick_cylinder-3d", "radial", ["Mechanics/Polynomial degree=2"]),
                          ("cube_thermal_stress", "diagonal", ["Mesh/Element type=triangles"])):
    prm = f"{prm_dir}/{case}.prm"
    run(binary, prm, f"{out}/{case}-serial", "Heat solver/Relative tolerance=1e-12", "Output/Write vtu=false",
        *extra)
    run(binary, prm, f"{out}/{case}-np2", "Heat solver/Relative tolerance=1e-12", *extra, mpirun=mpirun, np=2)
    serial = read_lines(f"{out}/{case}-serial/lines.csv")[line]
    parallel = read_lines(f"{out}/{case}-np2/lines.csv")[line]
    ok &= check(sorted(serial) == sorted(parallel), f"{case}: same output times")
    diff = max(abs(serial[t][2]["T"] - parallel[t][2]["T"]).max() for t in serial)
    ok &= check(diff < 1e-6, f"{case}: max |T_np2 - T_serial| = {diff:.2e} C < 1e-6 C")
    last = serial[max(serial)][2]
    # relative 1e-7, or round-off where the exact field vanishes (the
    # restrained sheet does not move): 1e-12 m, 1e-2 Pa
    for group, floor in ((("ux", "uy", "uz"), 1e-12),
                         (("sxx", "syy", "szz", "sxy", "syz", "sxz", "srr", "stt"), 1e-2)):
        fields = [c for c in group if c in last]
        if not fields:
            continue
        # relative to the largest value of the group (components that are
        # zero in exact arithmetic, such as uy on y = 0, are round-off)
        scale = max(abs(serial[t][2][c]).max() for t in serial for c in fields)
        diff = max(abs(serial[t][2][c] - parallel[t][2][c]).max() for t in serial for c in fields)
        ok &= check(diff <= 1e-7 * scale + floor,
                    f"{case}: max |np2 - serial| over {','.join(fields)} = {diff:.2e} "
                    f"<= 1e-7 x {scale:.3e} + {floor:g}")
    ok &= check(summary(f"{out}/{case}-np2")["mpi_processes"] == 2, f"{case}: ran on 2 processes")
    ok &= check(summary(f"{out}/{case}-np2")["dofs"] == summary(f"{out}/{case}-serial")["dofs"],
                f"{case}: same number of DoFs")
sys.exit(0 if ok else 1)
