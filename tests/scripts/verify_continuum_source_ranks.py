#!/usr/bin/env python3
"""Discrete thermo-mechanics with the continuum heat as its temperature
source on 2 MPI ranks against 1: prm/thermal_shock_disc.prm with
`Temperature source = continuum heat` (P2), to 12 ms. The continuum heat
runs distributed on deal.II's machinery (Trilinos AMG, whose hierarchy
depends on the partition); every rank then takes the whole field and the
discrete layer reads it replicated, so the two runs agree to the solver,
not bitwise.

Bound, fixed from the solver before the runs: the heat solve stops at a
residual of `Heat solver/Relative tolerance` (default 1e-10 of the
right-hand side); with a condition number below 1e4 the temperatures differ
by at most 1e-6 of their largest value, and the displacements and stresses, linear in
the thermal strains, likewise: every column of probes.csv and lines.csv
(T, ux, uy, sxx, syy, sxy) within 1e-6 of the column's largest value.

    verify_continuum_source_ranks.py TMFDEM MPIRUN PRM_DIR OUT
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import check, run, summary  # noqa: E402

COLUMNS = ("T", "ux", "uy", "sxx", "syy", "sxy")


def table(folder, name):
    with open(os.path.join(folder, name)) as f:
        return list(csv.DictReader(f))


def main():
    binary, mpirun, prm_dir, out = sys.argv[1:5]
    prm = os.path.join(prm_dir, "thermal_shock_disc.prm")
    folders = {}
    for ranks in (1, 2):
        folders[ranks] = os.path.join(out, f"np{ranks}")
        run(binary, prm, folders[ranks],
            "Discrete heat/Temperature source=continuum heat",
            "Heat solver/Polynomial degree=2", "Time stepping/End time=0.012",
            mpirun=mpirun, np=ranks)
    ok = check(summary(folders[2]).get("mpi_processes") == 2, "np 2 ran on 2 ranks")
    for name in ("probes.csv", "lines.csv"):
        a, b = table(folders[1], name), table(folders[2], name)
        ok &= check(len(a) == len(b) and len(a) > 0, f"{name}: {len(a)} rows on both")
        for column in COLUMNS:
            va = [float(r[column]) for r in a]
            vb = [float(r[column]) for r in b]
            scale = max(abs(v) for v in va) or 1.
            worst = max(abs(x - y) for x, y in zip(va, vb)) / scale
            ok &= check(worst <= 1e-6,
                        f"{name} {column}: np 2 within {worst:.1e} of np 1's largest "
                        f"value (bound 1e-6)")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
