#!/usr/bin/env python3
"""One joint pulled apart (Mode I) and sheared (Mode II), Munjiza and linear
softening: the work done on the joint until it breaks must equal G times the
joint length (1 m) within 1 %, and the joint must break in the right mode."""
import os
import sys

from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm", "joint_pull.prm")
G = {"I": 1000.0, "II": 5000.0}
ok = True
for law in ("Munjiza", "linear"):
    for mode in ("I", "II"):
        folder = os.path.join(out, f"{law}_{mode}")
        vx, vy, end = ("0.01", "0", "0.3") if mode == "I" else ("0", "0.01", "0.7")
        run(binary, prm, folder,
            f"Discrete mechanics/Softening law={law}",
            f"Discrete bodies/Body 2/Velocity x={vx}",
            f"Discrete bodies/Body 2/Velocity y={vy}",
            f"Time stepping/End time={end}")
        s = summary(folder)
        work = s["energy"]["joint_work"]
        error = abs(work / G[mode] - 1.0)
        ok &= check(s["broken_joints"] == 1 and s[f"broken_mode_{mode}"] == 1,
                    f"{law}, Mode {mode}: the joint broke in Mode {mode}")
        ok &= check(error < 0.01,
                    f"{law}, Mode {mode}: work to break {work:.3f} J/m vs G L = "
                    f"{G[mode]:.0f} J/m, error {100 * error:.4f} % (< 1 %)")
sys.exit(0 if ok else 1)
