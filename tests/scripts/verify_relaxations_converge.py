#!/usr/bin/env python3
"""Every shipped quasi-static case converges: each prm file of prm/ and
doc/tutorial/prm/ with `Coupling = quasi-static`, run as shipped to its End
time, has no relaxation that reached its cap (summary.json
relaxations_at_cap = 0: every thermal step ends in equilibrium, also where
cracks run unstably, which the step control finds and the fracture event
runs with inertia).

    verify_relaxations_converge.py TMFDEM OUT [PRM ...] [--except NAME ...]

Without PRM arguments it finds the files itself (at least 6) and leaves out
those named after --except (file names, run by a test of their own); it
prints per file the thermal steps, the re-run and unstable steps, the
fracture events and the broken joints. prm/thermal_shock_disc.prm is left
to the tests that run it with the same check:
verify.discrete_thermal_shock_pattern (the showcase, 400 C, to the prm's End
time) and verify.discrete_thermal_shock (300 C, the prm's own temperature,
and 500 C, to 50 ms); prm/thermal_shock_disc-3d.prm to
verify.discrete_thermal_shock_3d (the same check, on tetrahedra of 0.4 mm at
the rim instead of 0.25 mm and to 5 ms instead of 12 ms: the shipped run
takes 16 minutes on two cores, doc/cases/thermal_shock_disc-3d.md);
prm/thermal_shock_disc_cracking-3d.prm to verify.discrete_thermal_cracking_3d
(the same check, 0.6 mm at the rim instead of 0.4 mm, 600 C, to 10 ms
instead of 22 ms: the shipped run takes about 10 minutes on one core,
doc/cases/thermal_shock_disc_cracking-3d.md).
"""
import glob
import os
import re
import sys

from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
arguments = sys.argv[3:]
excluded = set()
if "--except" in arguments:
    excluded = set(arguments[arguments.index("--except") + 1:])
    arguments = arguments[:arguments.index("--except")]
root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
files = arguments or sorted(glob.glob(os.path.join(root, "prm", "*.prm")) +
                            glob.glob(os.path.join(root, "doc", "tutorial", "prm", "*.prm")))
CHECKED_ELSEWHERE = {"thermal_shock_disc.prm", "thermal_shock_disc-3d.prm",
                     "thermal_shock_disc_cracking-3d.prm"}
quasi_static = [f for f in files
                if re.search(r"^\s*set\s+Coupling\s*=\s*quasi-static", open(f).read(), re.M)]
if arguments:
    ok = check(len(quasi_static) == len(arguments),
               f"{len(quasi_static)} of the {len(arguments)} prm files given are quasi-static")
else:
    ok = check(len(quasi_static) >= 6, f"{len(quasi_static)} quasi-static prm files found (>= 6)")
    missing = excluded - {os.path.basename(f) for f in quasi_static}
    ok &= check(not missing, f"the files left out are quasi-static prm files ({sorted(missing)} "
                             f"are not)")
    quasi_static = [f for f in quasi_static
                    if os.path.basename(f) not in CHECKED_ELSEWHERE | excluded]
for prm in quasi_static:
    name = os.path.splitext(os.path.basename(prm))[0]
    folder = os.path.join(out, name)
    run(binary, prm, folder, "Output/Write vtu=false")
    s = summary(folder)
    ok &= check(s["finished"] and s["relaxations_at_cap"] == 0,
                f"{name}: relaxations at the cap {s['relaxations_at_cap']} (0) in "
                f"{s['thermal_steps']} thermal steps ({s.get('rejected_thermal_steps')} re-run, "
                f"{s.get('unstable_thermal_steps')} unstable, {s.get('fracture_events')} "
                f"fracture events, {s['broken_joints']} broken joints)")
sys.exit(0 if ok else 1)
