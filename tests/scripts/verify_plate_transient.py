#!/usr/bin/python3
"""Paper 5.1, continuum: max abs error along 'midline' <= 0.5 C at t = 2, 10,
20, 50 s at element size 0.05 m, against the corrected series (P2,
Crank-Nicolson with a Rannacher start: measured 0.015, 0.0016, 0.0006,
0.0001 C, held to 0.02, 0.003, 0.0015, 0.0005 C); and the heat balance
closes. The P1 limit at this size is checked in
convergence_plate_transient.py."""
import sys
from common import run, summary, check
from analytic import plate_transient, read_csv

binary, prm, out = sys.argv[1:4]


def check_midline(folder, label):
    """Asserts max |T - T_exact| <= 0.5 C on 'midline' at the paper's times."""
    lines = read_csv(f"{folder}/lines.csv")["midline"]
    passed = True
    for t, limit in ((2.0, 0.02), (10.0, 0.003), (20.0, 0.0015), (50.0, 0.0005)):
        x, y, fields = lines[t]
        error = abs(fields["T"] - plate_transient(x, t)).max()
        passed &= check(error <= limit, f"{label}t = {t:4.0f} s: max |T - T_exact| = {error:.5f} C "
                        f"<= {limit} C (target 0.5 C)")
    return passed


run(binary, prm, out)
ok = check_midline(out, "")
s = summary(out)
ok &= check(s["heat"]["relative_imbalance"] < 1e-8,
            f"heat balance: relative imbalance {s['heat']['relative_imbalance']:.2e} < 1e-8")

# the same case on quadrilaterals with transient Kelly refinement and
# coarsening (p4est, solution transfer every 5 steps)
amr = f"{out}/amr"
run(binary, prm, amr, "Mesh/Element type=quadrilaterals", "Adaptive refinement/Enable=true",
    "Adaptive refinement/Interval=5", "Adaptive refinement/Refine fraction=0.5",
    "Adaptive refinement/Coarsen fraction=0.05", "Adaptive refinement/Maximum level=2",
    "Output/Write vtu=false")
ok &= check_midline(amr, "quadrilaterals + AMR, ")
s = summary(amr)
ok &= check(s["heat"]["relative_imbalance"] < 1e-5,
            f"AMR heat balance (solution transfer included): relative imbalance {s['heat']['relative_imbalance']:.1e} < 1e-5")
sys.exit(0 if ok else 1)
