#!/usr/bin/python3
"""Scaling of the discrete layer over MPI ranks: the intact plate
of discrete_mechanics_throughput.py (n x n cells, two triangles each,
bottom on rollers, top pulled, strong joints, contact on), one thread per
rank.

  strong: the plate of ~250k triangles (n = 354) on np 1, 2 and 4 (4 on
          this 2-core machine is oversubscribed: correctness only);
  weak:   ~125k triangles per rank: n = 250 on np 1, n = 354 on np 2;
  frag:   the fragmenting plate of the throughput benchmark (60 x 60 cells,
          7200 triangles and a floor, dropped at 20 m/s) on np 1 and 2,
          15 000 steps: it hits the floor after ~6000 and shatters;
  large:  ~1M triangles (n = 707) on np 2, a few steps: does it run, and
          in how much memory per rank.

Per run: time-loop wall time and triangle-steps per second (all ranks'
triangles / wall), the wall time the busiest rank spent communicating
(waits for the other ranks included), the speed-up against np 1, peak resident memory of the
largest rank, ghost triangles, bytes per step sent in ghost exchanges (all
ranks) and in full synchronisations, and whether history.csv is bitwise
that of np 1 (it must be: partition.h).

usage: benchmarks/discrete_mpi_scaling.py [path/to/tmfdem [STEPS [--skip-large]]]"""
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from bench_common import help_requested, tmfdem, work_folder  # noqa: E402

help_requested(__doc__)
sys.argv_saved = list(sys.argv)
sys.argv = sys.argv[:1]  # the throughput module reads its own arguments
sys.path.insert(0, here)
import discrete_mechanics_throughput as throughput  # noqa: E402

arguments = sys.argv_saved[1:]
skip_large = "--skip-large" in arguments
arguments = [a for a in arguments if a != "--skip-large"]
binary = tmfdem(arguments[0] if arguments else None)
steps = int(arguments[1]) if len(arguments) > 1 else 400
work = work_folder("tmfdem-mpi-")
throughput.work = work


def run(prm_file, ranks, n_steps, out):
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
           binary, prm_file, "--set", f"Output/Directory={out}",
           "--set", "Discrete mechanics/Threads=1",
           "--set", f"Discrete mechanics/Maximum steps={n_steps}"]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    start = time.monotonic()
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    total = time.monotonic() - start
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    s["process_wall"] = total
    return s


def history(folder):
    with open(os.path.join(folder, "history.csv"), "rb") as f:
        return f.read()


def row(label, ranks, s, base_rate, same):
    loop = s["wall_time_s"]
    rate = s["elements"] * s["steps"] / loop
    per_step = 1. / max(s["steps"], 1)
    print(f"{label:>6} {ranks:>3} {s['elements']:>9} {s['steps']:>6} {s['process_wall']:>8.1f} "
          f"{loop:>8.2f} {s['communication_time_s']:>7.2f} {rate:>12.3e} {rate / base_rate if base_rate else 1.:>6.2f} "
          f"{s['peak_resident_memory_bytes'] / 2**20:>9.0f} {s['ghost_elements']:>7.0f} "
          f"{s['ghost_exchange_bytes'] * per_step / 1024:>10.1f} "
          f"{s['synchronisation_bytes'] * per_step / 1024:>10.1f} {s['synchronisations']:>5} "
          f"{'yes' if same else 'NO':>9}", flush=True)
    return rate


print(f"cores: {os.cpu_count()}, load average before: "
      f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; {steps} steps, 1 thread per rank")
print(f"{'case':>6} {'np':>3} {'triangles':>9} {'steps':>6} {'all [s]':>8} {'loop [s]':>8} {'comm [s]':>7} "
      f"{'tri-steps/s':>12} {'vs np1':>6} {'mem [MiB]':>9} {'ghosts':>7} "
      f"{'ghost kB/step':>10} {'sync kB/step':>10} {'syncs':>5} {'history=np1':>9}")
plate = {}
for n in (354, 250) + (() if skip_large else (707,)):
    plate[n] = throughput.prm(throughput.plate_msh(n, False), True, False)

# strong scaling
results = {}
for ranks in (1, 2, 4):
    out = os.path.join(work, f"strong_{ranks}")
    results[ranks] = run(plate[354], ranks, steps, out)
base = None
for ranks in (1, 2, 4):
    same = history(os.path.join(work, f"strong_{ranks}")) == history(os.path.join(work, "strong_1"))
    rate = row("strong", ranks, results[ranks], base, same)
    base = base or rate

# weak scaling: ~125k triangles per rank
weak1 = run(plate[250], 1, steps, os.path.join(work, "weak_1"))
rate1 = row("weak", 1, weak1, None, True)
row("weak", 2, results[2], rate1, True)
print(f"weak: loop time per step np 2 (2 x {results[2]['elements'] // 2} triangles) / "
      f"np 1 ({weak1['elements']}): "
      f"{results[2]['wall_time_s'] / results[2]['steps'] / (weak1['wall_time_s'] / weak1['steps']):.2f}")

# fragmented: the shattering plate of the throughput benchmark (contact
# searches every few steps; the search runs on every rank)
frag = throughput.prm(throughput.plate_msh(60, True), False, True)
fr = {}
for ranks in (1, 2):
    fr[ranks] = run(frag, ranks, 15000, os.path.join(work, f"frag_{ranks}"))
fbase = None
for ranks in (1, 2):
    same = history(os.path.join(work, f"frag_{ranks}")) == history(os.path.join(work, "frag_1"))
    rate = row("frag", ranks, fr[ranks], fbase, same)
    fbase = fbase or rate
print(f"frag: {fr[1]['contact_searches']} contact searches, {fr[1]['broken_joints']} broken "
      f"joints, {fr[1]['contact_pairs']} pairs at the end")

if not skip_large:
    large = run(plate[707], 2, max(20, steps // 10), os.path.join(work, "large_2"))
    row("large", 2, large, None, True)
