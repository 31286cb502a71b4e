#!/usr/bin/python3
"""Quasi-static relaxation: prm/hollow_cylinder_cracking.prm (paper 5.5) on
one thread (Discrete mechanics/Threads = 1) with the mass-damped relaxation
("old": mass damping 6e4 1/s, each relaxation from the last state,
Relaxation force tolerance 1e-3) and as shipped ("new": the start extrapolated from the last relaxation, kinetic
damping, no mass damping, force tolerance 1e-5; doc/theory.md 8).
The two run alternately, REPEATS pairs (default 1; the machine may be
shared: each run prints its wall and CPU time, steps and the 1-minute load
average after it). Per run: the inner-wall temperature T_a = 1e-4 t at the
first damaged joint (the verified quantity), the broken joints at the end,
the relaxations that hit their cap; per pair: the largest difference of
sigma_theta / T_a and sigma_r / T_a on the radial line between the two runs
at the outputs before the first damage, relative to max |sigma_theta| / T_a.
usage: benchmarks/quasi_static_relaxation.py [path/to/tmfdem [REPEATS [END_TIME]]]
END_TIME (default: the prm's 1.2e6 s) shortens the runs."""
import collections
import csv
import json
import os
import subprocess
import sys
import numpy as np

from bench_common import help_requested, tmfdem, work_folder

here = os.path.dirname(os.path.abspath(__file__))
help_requested(__doc__)
binary = tmfdem(sys.argv[1] if len(sys.argv) > 1 else None)
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 1
end_time = sys.argv[3] if len(sys.argv) > 3 else None
prm = os.path.join(here, "..", "prm", "hollow_cylinder_cracking.prm")
work = work_folder("tmfdem-relax-")
RATE = 1e-4  # C/s: the prm's inner-wall ramp

VARIANTS = {
    "old": ["Discrete heat/Relaxation predictor=none", "Discrete heat/Relaxation damping=mass",
            "Discrete mechanics/Mass damping=6e4", "Discrete heat/Relaxation force tolerance=1e-3",
            # the fracture event (shipped since) pauses kinetic damping: not
            # part of the old relaxation; its step cap was 40000
            "Discrete heat/Fracture event duration=0",
            "Discrete heat/Mechanical steps per thermal step=40000"],
    "new": [],
}


def run(name, folder):
    args = [binary, prm, "--set", f"Output/Directory={folder}",
            "--set", "Discrete mechanics/Threads=1"]
    if end_time:
        args += ["--set", f"Time stepping/End time={end_time}"]
    for s in VARIANTS[name]:
        args += ["--set", s]
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    s = json.load(open(os.path.join(folder, "summary.json")))
    hist = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
    onset = np.nonzero(hist["damaged_joints"] > 0)[0]
    return dict(wall=s["wall_time_s"], cpu=s["cpu_time_s"],
                steps=s["steps"], cap=s["relaxations_at_cap"], broken=s["broken_joints"],
                t_onset=hist["time"][onset[0]] if len(onset) else None,
                load=os.getloadavg()[0])


def lines(folder):
    d = collections.defaultdict(list)
    with open(os.path.join(folder, "lines.csv")) as f:
        for r in csv.DictReader(f):
            d[float(r["time"])].append([float(r["sxx"]), float(r["syy"])])
    return {t: np.array(v) for t, v in d.items() if t > 0}


def stress_difference(a, b, t_max):
    """max over outputs before t_max of the largest difference of sigma / T_a
    on the radial line (y = 0: sxx = sigma_r, syy = sigma_theta), relative to
    max |sigma_theta| / T_a."""
    la, lb = lines(a), lines(b)
    worst = 0.
    for ta in la:
        tb = min(lb, key=lambda t: abs(t - ta))
        if ta >= t_max or tb >= t_max or abs(tb - ta) > 0.05 * ta:
            continue
        A, B = la[ta] / (RATE * ta), lb[tb] / (RATE * tb)
        worst = max(worst, np.abs(A - B).max() / np.abs(A[:, 1]).max())
    return worst


print(f"prm/hollow_cylinder_cracking.prm, 1 thread, {repeats} pair(s), "
      f"End time {end_time or 'of the prm'}; load average before: "
      + " ".join(f"{x:.2f}" for x in os.getloadavg()))
print(f"{'pair':>4} {'run':>4} {'wall [s]':>9} {'cpu [s]':>8} {'steps':>9} {'at cap':>6} "
      f"{'T_a onset [C]':>13} {'broken':>6} {'load':>5}")
results = collections.defaultdict(list)
for p in range(repeats):
    folders = {}
    for name in ("old", "new"):
        folders[name] = os.path.join(work, f"{name}{p}")
        r = run(name, folders[name])
        results[name].append(r)
        onset = f"{RATE * r['t_onset']:.2f}" if r["t_onset"] is not None else "none"
        print(f"{p + 1:>4} {name:>4} {r['wall']:9.1f} {r['cpu']:8.1f} {r['steps']:9d} "
              f"{r['cap']:6d} {onset:>13} {r['broken']:6d} {r['load']:5.2f}", flush=True)
    o, n = results["old"][-1], results["new"][-1]
    t_max = min(t for t in (o["t_onset"], n["t_onset"], 1e300) if t is not None)
    print(f"     new / old: wall {o['wall'] / n['wall']:.1f}x faster, CPU "
          f"{o['cpu'] / n['cpu']:.1f}x, steps {o['steps'] / n['steps']:.1f}x; sigma / T_a on "
          f"'radial' before the first damage differs by "
          f"{stress_difference(folders['old'], folders['new'], t_max):.1e} of max |sigma_theta|",
          flush=True)
for name in ("old", "new"):
    r = results[name]
    print(f"{name}: median wall {np.median([x['wall'] for x in r]):.1f} s, "
          f"median CPU {np.median([x['cpu'] for x in r]):.1f} s")
print(f"outputs in {work}")
