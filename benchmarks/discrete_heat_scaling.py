#!/usr/bin/python3
"""The discrete layer's heat on MPI ranks: each rank advances
the nodes of its own triangles (DiscreteHeat::distribute()).

  heat:  Model = discrete heat on the structured unit-square plate of
         discrete_mechanics_throughput.py (n x n cells, two triangles each,
         numbered row by row: each rank's triangles a band; default n = 336,
         225 792 triangles), bottom 0 C, top 100 C, initial 0 C, the
         material and joints of paper 5.1 (prm/plate_transient.prm: k = 10,
         kappa = 0.005 m^2/s, joint conductance factor 1000), implicit (CG,
         Jacobi), STEPS thermal steps of 0.05 s, on np 1 and 2; then with
         Preconditioner = amg (Trilinos ML) on np 1 and 2, whose midline
         temperatures are compared with Jacobi's np 1 (largest difference);
  multi: Model = discrete thermo-mechanics, prm/thermal_shock_disc.prm with
         explicit heat and dynamic (multi-rate) coupling, 4000 mechanical
         steps, a thermal step every 140 of them, on np 1 and 2; with
         --against OLD, the same runs of another build (before the heat was
         distributed, every thermal step began with a full synchronisation);
         each build's np 2 is compared with its own np 1;
  serial: with --against, prm/plate_transient.prm (992 triangles, 1000
         implicit steps) on one rank, the two builds alternating, 3 rounds.

Per run: wall time of the time loop (summary.json wall_time), the wall time
the busiest rank spent in exchanges and reductions (waits for the other rank
included), CG iterations, ghost bytes sent per CG iteration (all ranks),
triangle-steps per second, speed-up against np 1, ghost triangles of rank 0,
and for the thermo-mechanics the bytes per step of synchronisations and
ghost exchanges; and whether every output is bitwise that of np 1
(scripts/results_neutral.py). One thread per rank.

usage: benchmarks/discrete_heat_scaling.py [TMFDEM] [--steps N] [--cells n]
                                           [--against OLD_TMFDEM]"""
import argparse
import json
import os
import subprocess
import sys
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
sys.path.insert(0, os.path.join(root, "scripts"))
import results_neutral as rn  # noqa: E402
import vtu_pieces  # noqa: E402

sys.argv_saved = list(sys.argv)
sys.argv = sys.argv[:1]  # the throughput module reads its own arguments
sys.path.insert(0, here)
import discrete_mechanics_throughput as throughput  # noqa: E402
sys.argv = sys.argv_saved

HEAT_PRM = """set Model = discrete heat
subsection Mesh
  set Source = file
  set File name = {mesh}
end
subsection Materials
  subsection Material 1
    set Density                = 2000
    set Young's modulus        = 50e9
    set Poisson's ratio        = 0.25
    set Thermal conductivity   = 10
    set Specific heat capacity = 1
  end
end
subsection Thermal boundary conditions
  subsection Condition 1
    set Boundary ids = 2
    set Type         = dirichlet
    set Temperature  = 0
  end
  subsection Condition 2
    set Boundary ids = 3
    set Type         = dirichlet
    set Temperature  = 100
  end
end
subsection Initial conditions
  set Temperature = 0
end
subsection Discrete heat
  set Time integration         = implicit
  set Joint conductance factor = 1000
end
subsection Time stepping
  set Mode      = transient
  set End time  = {end}
  set Time step = 0.05
end
subsection Output
  set Write vtu = false
end
subsection Monitors
  set Lines = midline: 0.5, 0, 0.5, 1, 101
end
"""


def same_as(base, out, ranks):
    """'yes' if every output of @p out is bitwise that of @p base (vtu
    pieces of several ranks put together first)."""
    merged = out + "_merged"
    records = vtu_pieces.merged_view(out, merged) if ranks > 1 else 0
    differ, _ = rn.compare(base, merged if records else out)
    return "yes" if not differ else "NO: " + ", ".join(differ[:3])


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
    parser.add_argument("--cells", type=int, default=336)
    parser.add_argument("--against", help="another build's tmfdem (before/after)")
    args = parser.parse_args()
    from bench_common import tmfdem, work_folder
    args.binary = tmfdem(args.binary)
    if args.against:
        args.against = tmfdem(args.against)
    # what differs between rank counts by design (scripts/rank_independence.py)
    rn.VOLATILE.update({"mpi_processes", "ghost_elements", "ghost_exchange_bytes",
                        "synchronisations", "synchronisation_bytes",
                        "communication_time_s", "heat_distributed"})
    work = work_folder("tmfdem-heat-")
    throughput.work = work
    print(f"load average {os.getloadavg()[0]:.2f}; outputs in {work}")

    # --- Model = discrete heat
    prm = os.path.join(work, "heat_plate.prm")
    with open(prm, "w") as f:
        f.write(HEAT_PRM.format(mesh=throughput.plate_msh(args.cells, False),
                                end=0.05 * args.steps))
    sets = []
    print("\nheat (Model = discrete heat, implicit)")
    print(f"{'precon':>6} {'np':>3} {'triangles':>9} {'steps':>5} {'loop [s]':>9} {'comm [s]':>8} "
          f"{'process [s]':>11} {'CG its':>7} {'tri-steps/s':>11} {'vs np1':>6} "
          f"{'ghosts':>7} {'ghost kB/it':>11} {'outputs = np1':>13}")
    base = None
    for ranks, preconditioner in ((1, "jacobi"), (2, "jacobi"), (1, "amg"), (2, "amg")):
        out = os.path.join(work, f"heat_{preconditioner}_np{ranks}")
        s = run(args.binary, prm, ranks, out,
                sets + [f"Discrete heat/Preconditioner={preconditioner}"])
        if preconditioner == "amg":
            # not bitwise (the hierarchy depends on the ranks): the largest
            # difference of the midline temperatures from Jacobi's np 1
            ref = [float(r.split(",")[4]) for r in
                   open(os.path.join(base[0], "lines.csv")).read().split("\n")[1:] if r]
            new = [float(r.split(",")[4]) for r in
                   open(os.path.join(out, "lines.csv")).read().split("\n")[1:] if r]
            s["same"] = f"dT {max(abs(a - b) for a, b in zip(ref, new)):.1e} C"
        rate = s["elements"] * s["steps"] / s["wall_time"]
        if base is None:
            base = (out, s["wall_time"])
            same = "-"
        elif "same" in s:
            same = s["same"]
        else:
            same = same_as(base[0], out, ranks)
        ghost = s.get("ghost_exchange_bytes", 0) / max(1, s["cg_iterations"]) / 1e3
        print(f"{preconditioner:>6} {ranks:>3} {s['elements']:>9} {s['steps']:>5} {s['wall_time']:>9.2f} "
              f"{s.get('communication_time_s', 0):>8.2f} "
              f"{s['process_wall']:>11.2f} {s['cg_iterations']:>7} {rate:>11.3g} "
              f"{base[1] / s['wall_time']:>6.2f} {s.get('ghost_elements', 0):>7} "
              f"{ghost:>11.1f} {same:>13}", flush=True)

    # --- discrete thermo-mechanics, explicit heat, multi-rate
    prm = os.path.join(root, "prm", "thermal_shock_disc.prm")
    sets = ["Discrete heat/Time integration=explicit", "Discrete heat/Coupling=dynamic",
            "Discrete heat/Fracture event duration=0", "Discrete heat/Relaxation damping=mass",
            "Discrete heat/Mechanical steps per thermal step=0",
            "Discrete heat/Thermal step growth factor=1",
            "Time stepping/End time=1e-2", "Discrete mechanics/Maximum steps=4000"]
    print("\nmulti-rate thermo-mechanics (thermal_shock_disc, explicit heat, 4000 steps)")
    print(f"{'build':>6} {'np':>3} {'steps':>5} {'thermal':>7} {'loop [s]':>9} {'vs np1':>6} "
          f"{'syncs':>5} {'sync kB/step':>12} {'ghost kB/step':>13} {'distributed':>11} "
          f"{'outputs = np1':>13}")
    builds = [("new", args.binary)] + ([("old", args.against)] if args.against else [])
    for name, binary in builds:
        base_wall = None
        reference = None
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
                same = same_as(reference, out, ranks)
            base_wall = base_wall or s["wall_time"]
            print(f"{name:>6} {ranks:>3} {steps:>5} {s.get('thermal_steps', 0):>7} "
                  f"{s['wall_time']:>9.2f} {base_wall / s['wall_time']:>6.2f} "
                  f"{s.get('synchronisations', 0):>5} {sync:>12.1f} {ghost:>13.1f} "
                  f"{str(s.get('heat_distributed', False)):>11} {same:>13}", flush=True)
    if args.against:
        serial_against(args, work)


def serial_against(args, work):
    prm = os.path.join(root, "prm", "plate_transient.prm")
    print("\nserial implicit heat (prm/plate_transient.prm, 1000 steps, np 1)")
    print(f"{'round':>5} {'build':>6} {'loop [s]':>9} {'CG its':>7}")
    for round_ in range(3):
        for name, binary in (("old", args.against), ("new", args.binary)):
            out = os.path.join(work, f"serial_{name}_{round_}")
            s = run(binary, prm, 1, out, [])
            print(f"{round_ + 1:>5} {name:>6} {s['wall_time']:>9.3f} "
                  f"{s['cg_iterations']:>7}", flush=True)


if __name__ == "__main__":
    main()
