#!/usr/bin/python3
"""The discrete layer's heat on MPI ranks (issue 14): each rank advances
the nodes of its own triangles (DiscreteHeat::distribute()).

  heat:  Model = discrete heat, the plate of paper 5.1 (prm/plate_transient.prm,
         1 m x 0.25 m, left 0 C, right 100 C) meshed at Element size H
         (default 0.0016 m: ~230k triangles), implicit (CG, Jacobi), STEPS
         thermal steps of 0.05 s, on np 1 and 2;
  multi: Model = discrete thermo-mechanics, prm/thermal_shock_disc.prm with
         explicit heat and dynamic (multi-rate) coupling, 4000 mechanical
         steps, a thermal step every 140 of them, on np 1 and 2; with
         --against OLD, the same runs of another build (before the heat was
         distributed, every thermal step began with a full synchronisation).

Per run: wall time of the time loop (summary.json wall_time), CG iterations,
triangle-steps per second, speed-up against np 1, ghost triangles of rank 0,
and for the thermo-mechanics the bytes per step of synchronisations and
ghost exchanges; and whether every output is bitwise that of np 1
(scripts/results_neutral.py). One thread per rank.

usage: benchmarks/discrete_heat_scaling.py [TMFDEM] [--steps N] [--size H]
                                           [--against OLD_TMFDEM]"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
sys.path.insert(0, os.path.join(root, "scripts"))
import results_neutral as rn  # noqa: E402


def run(binary, prm, ranks, out, sets):
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
           binary, prm, "--set", f"Output/Directory={out}",
           "--set", "Output/Progress interval=0",
           "--set", "Discrete mechanics/Threads=1"]
    for s in sets:
        cmd += ["--set", s]
    env = rn.environment(binary)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stderr[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    s["process_wall"] = time.monotonic() - start
    return s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary", nargs="?",
                        default=os.path.join(root, "build-release", "tmfdem"))
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--size", type=float, default=0.0016)
    parser.add_argument("--against", help="another build's tmfdem (before/after)")
    args = parser.parse_args()
    # what differs between rank counts by design (scripts/rank_independence.py)
    rn.VOLATILE.update({"mpi_processes", "ghost_elements", "ghost_exchange_bytes",
                        "synchronisations", "synchronisation_bytes",
                        "communication_time_s", "heat_distributed"})
    work = tempfile.mkdtemp(prefix="tmfdem-heat-")
    print(f"load average {os.getloadavg()[0]:.2f}; outputs in {work}")

    # --- Model = discrete heat
    prm = os.path.join(root, "prm", "plate_transient.prm")
    sets = [f"Mesh/Element size={args.size}",
            f"Time stepping/End time={0.05 * args.steps}",
            "Output/Interval=1e9", "Output/Write vtu=false"]
    print("\nheat (Model = discrete heat, implicit)")
    print(f"{'np':>3} {'triangles':>9} {'steps':>5} {'loop [s]':>9} {'process [s]':>11} "
          f"{'CG its':>7} {'tri-steps/s':>11} {'vs np1':>6} {'ghosts':>7} {'outputs = np1':>13}")
    base = None
    for ranks in (1, 2):
        out = os.path.join(work, f"heat_np{ranks}")
        s = run(args.binary, prm, ranks, out, sets)
        rate = s["elements"] * s["steps"] / s["wall_time"]
        if base is None:
            base = (out, s["wall_time"])
            same = "-"
        else:
            differ, _ = rn.compare(base[0], out)
            same = "yes" if not differ else "NO: " + ", ".join(differ[:3])
        print(f"{ranks:>3} {s['elements']:>9} {s['steps']:>5} {s['wall_time']:>9.2f} "
              f"{s['process_wall']:>11.2f} {s['cg_iterations']:>7} {rate:>11.3g} "
              f"{base[1] / s['wall_time']:>6.2f} {s.get('ghost_elements', 0):>7} {same:>13}",
              flush=True)

    # --- discrete thermo-mechanics, explicit heat, multi-rate
    prm = os.path.join(root, "prm", "thermal_shock_disc.prm")
    sets = ["Discrete heat/Time integration=explicit", "Discrete heat/Coupling=dynamic",
            "Discrete heat/Mechanical steps per thermal step=0",
            "Discrete heat/Thermal step growth factor=1",
            "Time stepping/End time=1e-2", "Discrete mechanics/Maximum steps=4000"]
    print("\nmulti-rate thermo-mechanics (thermal_shock_disc, explicit heat, 4000 steps)")
    print(f"{'build':>6} {'np':>3} {'steps':>5} {'thermal':>7} {'loop [s]':>9} {'vs np1':>6} "
          f"{'syncs':>5} {'sync kB/step':>12} {'ghost kB/step':>13} {'distributed':>11} "
          f"{'outputs = np1':>13}")
    builds = [("new", args.binary)] + ([("old", args.against)] if args.against else [])
    reference = None
    for name, binary in builds:
        base_wall = None
        for ranks in (1, 2):
            out = os.path.join(work, f"multi_{name}_np{ranks}")
            s = run(binary, prm, ranks, out, sets)
            steps = s["steps"]
            sync = s.get("synchronisation_bytes", 0) / steps / 1e3
            ghost = s.get("ghost_exchange_bytes", 0) / steps / 1e3
            if reference is None:
                reference = out
                same = "-"
            else:
                differ, _ = rn.compare(reference, out)
                same = "yes" if not differ else "NO: " + ", ".join(differ[:3])
            base_wall = base_wall or s["wall_time"]
            print(f"{name:>6} {ranks:>3} {steps:>5} {s.get('thermal_steps', 0):>7} "
                  f"{s['wall_time']:>9.2f} {base_wall / s['wall_time']:>6.2f} "
                  f"{s.get('synchronisations', 0):>5} {sync:>12.1f} {ghost:>13.1f} "
                  f"{str(s.get('heat_distributed', False)):>11} {same:>13}", flush=True)


if __name__ == "__main__":
    main()
