#!/usr/bin/python3
"""Throughput of contact between tetrahedra: prm/two_blocks_collision-3d.prm
(two 0.1 m cubes, 793 tetrahedra, 1323 face joints, colliding at 10 m/s
closing speed and fracturing) on one thread, over two spans:

  before the impact: 0 to 0.5 ms (the cubes fly apart of each other; the
      candidate pairs are neighbours inside the cubes, touching with
      round-off overlaps);
  through the impact: 0 to 1.5 ms (contact, friction and fracture).

Each span runs with Contact = true and with Contact = false (the same
elements and joints; without contact the cubes pass through each other, so
the two runs part at the impact). Printed: steps, contact pairs, the time
loop's wall time, element-steps per second, and the contact's share of the
time, 1 - t(Contact = false) / t(Contact = true).

usage: benchmarks/discrete_contact_3d_throughput.py [path/to/tmfdem]
"""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from bench_common import help_requested, tmfdem, work_folder  # noqa: E402

help_requested(__doc__)
binary = tmfdem(sys.argv[1] if len(sys.argv) > 1 else None)
prm = os.path.join(here, "..", "prm", "two_blocks_collision-3d.prm")
work = work_folder("tmfdem_contact_3d_")


def run(end, contact):
    folder = os.path.join(work, f"end_{end}_contact_{contact}")
    cmd = [binary, prm, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0", "--set", "Output/Write vtu=false",
           "--set", "Discrete mechanics/Threads=1",
           "--set", f"Discrete mechanics/Contact={'true' if contact else 'false'}",
           "--set", f"Time stepping/End time={end}"]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


print(f"{'span':>22} {'contact':>8} {'steps':>6} {'pairs':>6} {'loop [s]':>9} "
      f"{'elem-steps/s':>13} {'contact share':>14}")
for label, end in (("before the impact", 0.0005), ("through the impact", 0.0015)):
    with_contact = run(end, True)
    without = run(end, False)
    share = 1.0 - without["wall_time_s"] / with_contact["wall_time_s"]
    for s, on in ((with_contact, True), (without, False)):
        print(f"{label:>22} {str(on):>8} {s['steps']:>6} {s.get('contact_pairs', 0):>6} "
              f"{s['wall_time_s']:>9.3f} {s['element_steps_per_second']:>13.4g} "
              f"{(f'{100 * share:.1f} %' if on else ''):>14}", flush=True)
