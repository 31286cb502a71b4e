#!/usr/bin/env python3
"""The implicit discrete heat's two preconditioners agree: the contact
blocks of prm/contact_conduction.prm (Model = discrete heat, contact heat
between two blocks, refined twice; 10 backward Euler steps of 1e6 s) with
`Discrete heat/Preconditioner = jacobi` on one rank (bitwise any rank count,
mpi.discrete_heat_ranks) against `amg` (Trilinos ML on the distributed
matrix) on 1 and 2 ranks.

Bound, fixed from the solver before the runs: both solves stop at a residual
of `Linear solver tolerance` = 1e-12 of the right-hand side; the error of
the temperatures is at most the condition number times that, and the
condition number of these matrices (capacity / dt against the joints'
conductance beta k / 2, beta = 1000) is below 1e6: the axis temperatures
(lines.csv) must agree to 1e-6 of their largest value. The AMG runs must
also take fewer CG iterations than Jacobi (the option really switched the
preconditioner); on 2 ranks at most twice the iterations of one (a
multigrid's iterations should not grow with the ranks; with aggregates
confined to each rank they went from 33 to 481); and a fixed step on an
unchanged body must build the AMG hierarchy once and reuse it
(summary.json amg_setups below the step count).

    verify_heat_preconditioners.py TMFDEM MPIRUN PRM_DIR OUT
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import check, run, summary  # noqa: E402


def axis(folder):
    with open(os.path.join(folder, "lines.csv")) as f:
        return [float(r["T"]) for r in csv.DictReader(f)]


def main():
    binary, mpirun, prm_dir, out = sys.argv[1:5]
    prm = os.path.join(prm_dir, "contact_conduction.prm")
    runs = {}
    for name, preconditioner, ranks in (("jacobi_np1", "jacobi", 1),
                                        ("amg_np1", "amg", 1),
                                        ("amg_np2", "amg", 2)):
        folder = os.path.join(out, name)
        run(binary, prm, folder, "Mesh/Global refinements=2",
            f"Discrete heat/Preconditioner={preconditioner}",
            mpirun=mpirun, np=ranks)
        runs[name] = (axis(folder), summary(folder))
    reference, s_ref = runs["jacobi_np1"]
    scale = max(abs(t) for t in reference)
    ok = True
    for name in ("amg_np1", "amg_np2"):
        values, s = runs[name]
        ok &= check(len(values) == len(reference), f"{name}: {len(values)} axis points")
        worst = max(abs(a - b) for a, b in zip(values, reference)) / scale
        ok &= check(worst <= 1e-6,
                    f"{name}: axis temperatures within {worst:.2e} of Jacobi's "
                    f"largest value (bound 1e-6)")
        ok &= check(s["cg_iterations"] < s_ref["cg_iterations"],
                    f"{name}: {s['cg_iterations']} CG iterations against "
                    f"Jacobi's {s_ref['cg_iterations']}")
        ok &= check(s.get("mpi_processes") == (2 if name.endswith("2") else 1),
                    f"{name}: ran on {s.get('mpi_processes')} rank(s)")
        # a fixed step on an unchanged body: the matrix is the same every
        # step, so its hierarchy is built once and reused
        ok &= check(0 < s.get("amg_setups", 0) < s["steps"],
                    f"{name}: AMG built {s.get('amg_setups')} times in "
                    f"{s['steps']} steps")
    # multigrid should not lose its efficiency to the partition: aggregates
    # confined to each rank cut the joints' strong couplings at the border
    # (481 iterations on 2 ranks against 33 on one, before aggregation
    # across ranks)
    its = {name: runs[name][1]["cg_iterations"] for name in ("amg_np1", "amg_np2")}
    ok &= check(its["amg_np2"] <= 2 * its["amg_np1"],
                f"AMG on 2 ranks: {its['amg_np2']} CG iterations, at most twice "
                f"the {its['amg_np1']} of one rank")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
