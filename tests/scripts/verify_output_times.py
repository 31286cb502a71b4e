#!/usr/bin/env python3
"""Every requested output time is written, at that time.

    verify_output_times.py TMFDEM OUT

  quasi-static: prm/thermal_shock_disc.prm (h = 0.8 mm, T0 = 400 C) to
      60 ms with 12 requested times, dense near the onset of cracking and
      between the growing thermal steps: solution.pvd holds t = 0, every
      requested time to 1e-12 s and the end time, nothing else (the thermal
      step lands on each).
  multi-rate: the same disc with Coupling = dynamic (mechanical steps of
      about 4e-8 s) to 20 us with 9 requested times: each written once,
      within half a mechanical step of the request.
"""
import os
import sys
import xml.etree.ElementTree as ET

from common import run, summary, check

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "prm",
                   "thermal_shock_disc.prm")


def written(folder):
    pvd = os.path.join(folder, "solution.pvd")
    return [float(d.get("timestep")) for d in ET.parse(pvd).getroot().iter("DataSet")]


ok = True
requested = [0.001, 0.002, 0.0025, 0.005, 0.01, 0.011, 0.02, 0.021, 0.03, 0.0305, 0.04, 0.05]
folder = os.path.join(out, "quasi_static")
run(binary, prm, folder, "Mesh/Element size=0.8e-3", "Initial conditions/Temperature=400",
    "Time stepping/End time=0.06", "Output/Times=" + ", ".join(str(t) for t in requested))
times = written(folder)
expected = [0.0] + requested + [0.06]
ok &= check(len(times) == len(expected) and
            all(abs(a - b) <= 1e-12 for a, b in zip(times, expected)),
            f"quasi-static: written at {times} s; requested {requested} (+ 0 and the end)")
ok &= check(summary(folder)["broken_joints"] > 0,
            f"quasi-static: the disc cracks on the way "
            f"({summary(folder)['broken_joints']} broken joints)")

requested = [2e-6, 4e-6, 5e-6, 6e-6, 8e-6, 1e-5, 1.2e-5, 1.5e-5, 1.8e-5]
folder = os.path.join(out, "multi_rate")
run(binary, prm, folder, "Mesh/Element size=0.8e-3", "Initial conditions/Temperature=400",
    "Discrete heat/Coupling=dynamic", "Discrete heat/Thermal step growth factor=1",
    "Discrete heat/Fracture event duration=0", "Discrete heat/Relaxation damping=mass",
    "Discrete heat/Mechanical steps per thermal step=50", "Discrete mechanics/Mass damping=0",
    "Time stepping/End time=2e-5", "Output/Times=" + ", ".join(str(t) for t in requested))
dt = summary(folder)["time_step"]
times = written(folder)[1:-1]
ok &= check(len(times) == len(requested) and
            all(abs(a - b) <= 0.5 * dt * (1 + 1e-9) for a, b in zip(times, requested)),
            f"multi-rate: {len(times)} of {len(requested)} requested times written, each "
            f"within half a mechanical step ({0.5 * dt:.3e} s): "
            f"largest offset {max(abs(a - b) for a, b in zip(times, requested)):.3e} s")
sys.exit(0 if ok else 1)
