#!/usr/bin/python3
"""The halo of each MPI rank of the discrete layer against the numbering of
the triangles (Discrete mechanics/Triangle numbering): a rank owns a range
of triangle indices, so with the mesh generator's numbering (mesh) its part
can be scattered over the body, with the Hilbert-curve numbering (the
default) it is a compact region.

Runs shipped cases (the smallest refined twice: a rank owns whole chunks
of 512 triangles), a few steps each, on np 1, 2 and 3 (3 oversubscribes a
2-core machine: the counts do not depend on it, the times do), once per
numbering, one thread per rank, and prints per run: triangles, ghost
triangles (summed over the ranks, summary.json ghost_elements), ghost bytes
sent per step (all ranks) and the time loop's wall time. With --large, also
prm/plate_transient.prm meshed at 1.6 mm (about 226k triangles, gmsh),
Model = discrete heat, 5 implicit steps (bytes per step then include every
CG iteration's ghost temperatures).

usage: benchmarks/partition_halo.py [TMFDEM] [--large | --only-large]"""
import argparse
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("tmfdem", nargs="?",
                    default=os.path.join(root, "build-release", "tmfdem"))
parser.add_argument("--large", action="store_true")
parser.add_argument("--only-large", action="store_true")
args = parser.parse_args()
sys.path.insert(0, here)
from bench_common import tmfdem, work_folder  # noqa: E402

args.tmfdem = tmfdem(args.tmfdem)

# case, extra settings, what bounds the run
cases = [
    ("thermal_shock_disc", ["Discrete mechanics/Maximum steps=2000"]),
    ("cut_plate", ["Mesh/Global refinements=2",
                   "Discrete mechanics/Maximum steps=2000"]),
    ("two_blocks_collision", ["Mesh/Global refinements=2",
                              "Discrete mechanics/Maximum steps=2000"]),
    ("rock_heap", ["Discrete mechanics/Maximum steps=2000"]),
    ("brazilian_disc", ["Discrete mechanics/Maximum steps=2000"]),
    ("anisotropic_conduction", ["Time stepping/End time=10"]),
    ("contact_conduction", ["Mesh/Global refinements=2",
                            "Time stepping/End time=1e6"]),
]
if args.only_large:
    cases = []
if args.large or args.only_large:
    cases.append(("plate_transient", ["Mesh/Element size=0.0016",
                                      "Time stepping/End time=0.25"]))

work = work_folder("tmfdem-halo-")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
           OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
print(f"{'case':>22} {'np':>2} {'numbering':>13} {'triangles':>9} "
      f"{'ghosts':>7} {'ghost kB/step':>13} {'loop [s]':>8}")
for case, settings in cases:
    for ranks in (1, 2, 3):
        for numbering in ("mesh", "Hilbert curve"):
            out = os.path.join(work, f"{case}-{ranks}-{numbering[0]}")
            command = ["mpirun", "--allow-run-as-root", "--oversubscribe",
                       "-np", str(ranks), args.tmfdem,
                       os.path.join(root, "prm", case + ".prm"),
                       "--set", f"Output/Directory={out}",
                       "--set", "Discrete mechanics/Threads=1",
                       "--set", f"Discrete mechanics/Triangle numbering={numbering}"]
            for setting in settings:
                command += ["--set", setting]
            subprocess.run(command, check=True, capture_output=True, env=env)
            with open(os.path.join(out, "summary.json")) as f:
                s = json.load(f)
            steps = max(1, s.get("steps", s.get("time_steps", 1)))
            print(f"{case:>22} {ranks:>2} {numbering:>13} {s['elements']:>9} "
                  f"{int(s['ghost_elements']):>7} "
                  f"{s['ghost_exchange_bytes'] / steps / 1e3:>13.2f} "
                  f"{s.get('wall_time', float('nan')):>8.3f}", flush=True)
