#!/usr/bin/python3
"""The paper's Sec. 5 meshes reproduced in size: element counts within 10 %
at the paper's element sizes (5.4 gives no size: 0.0056 m is the equilateral
size of 4927 triangles on that annulus; 5.6's disc of 13 mm needs 0.25 mm,
not the printed 0.5 mm, for 5020 elements; see physics-notes.md)."""
import os
import re
import subprocess
import sys

binary, out = sys.argv[1], sys.argv[2]
os.makedirs(out, exist_ok=True)
cases = [
    # name, settings, paper count
    ("5.1 plate 1 x 0.25 m, h = 0.05", ["Mesh/Source=rectangle", "Mesh/Upper right corner=1, 0.25", "Mesh/Element size=0.05"], 244),
    ("5.3 sheet 2 x 2 m, h = 0.05", ["Mesh/Source=rectangle", "Mesh/Upper right corner=2, 2", "Mesh/Element size=0.05"], 3708),
    ("5.4 annulus 0.03/0.15 m, h = 0.0056", ["Mesh/Source=annulus", "Mesh/Element size=0.0056"], 4927),
    ("5.5 annulus 0.03/0.15 m, h = 0.007", ["Mesh/Source=annulus", "Mesh/Element size=0.007"], 3304),
    ("5.6 disc 13 mm, h = 0.25 mm", ["Mesh/Source=disc", "Mesh/Outer radius=0.0065", "Mesh/Element size=0.00025"], 5020),
]
prm = os.path.join(out, "mesh_only.prm")
with open(prm, "w") as f:
    f.write("set Model = continuum heat\nsubsection Mesh\n  set Element type = triangles\nend\n"
            "subsection Materials\n  subsection Material 0\n  end\nend\n")
ok = True
print(f"{'case':40s} {'paper':>6s} {'tmfdem':>7s} {'diff':>7s}")
for name, settings, paper in cases:
    cmd = [binary, "--validate", prm, "--set", f"Output/Directory={out}"]
    for s in settings:
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"mesh: (\d+) cells \((\d+) triangles", r.stdout)
    if r.returncode != 0 or not m:
        print(r.stdout, r.stderr)
        sys.exit(f"FAIL: {name}: tmfdem --validate failed")
    n = int(m.group(1))
    diff = (n - paper) / paper
    print(f"{name:40s} {paper:6d} {n:7d} {100*diff:+6.1f}%")
    ok &= abs(diff) <= 0.10
sys.exit(0 if ok else "FAIL: element counts differ from the paper's by more than 10 %")
