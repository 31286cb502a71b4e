#!/usr/bin/env python3
"""Same answer on any number of MPI ranks: runs discrete prm cases under
`mpirun -np 1, 2, 3 ...` for a fixed span and compares every output file
of each run with the one-rank run, bitwise (summary.json without its
wall-clock, memory and MPI-traffic entries; the date stamps deal.II writes
into vtu/pvd headers are ignored). On several ranks the vtu outputs are one
piece per rank and a pvtu record; they are put back together
(scripts/vtu_pieces.py) and must equal the one-rank vtu files bitwise.

The discrete layer's reductions are exact on any number of ranks
(include/tmfdem/discrete/partition.h), so the outputs must be identical,
not merely close. Each run also reports, from its summary.json, that it
really ran on that many processes (mpi_processes) and how many ghost
triangles and bytes were exchanged.

    rank_independence.py TMFDEM [--ranks 1 2 3] [--cases joint_pull|path.prm ...]
                         [--mechanical-steps N] [--thermal-steps N]
                         [--set ENTRY=VALUE ...] [--end-time T] [--out FOLDER]
                         [--distributed-heat]

With --distributed-heat a run on several ranks must report in summary.json
that each rank advanced the temperatures of its own triangles
(heat_distributed), not the whole field replicated.

Exit status 0 when every case is identical on every rank count.
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import results_neutral as rn  # noqa: E402
import vtu_pieces  # noqa: E402

MPI_ENTRIES = {"mpi_processes", "ghost_elements", "ghost_exchange_bytes",
               "synchronisations", "synchronisation_bytes", "communication_time_s",
               "heat_distributed",
               # a rank's joints are a range and a list: batches differ
               "vectorised_joint_share", "vectorised_element_share"}
DEFAULT_CASES = ["joint_pull", "block_on_incline", "two_blocks_collision",
                 "plate_traction", "sheet_free_expansion", "thermal_shock_disc",
                 "contact_conduction", "cut_plate"]


def mpirun(n):
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(n)]


def run(binary, prm, folder, end, ranks, extra):
    if os.path.isdir(folder):
        shutil.rmtree(folder)
    cmd = mpirun(ranks) + [binary, prm, "--set", f"Output/Directory={folder}",
                           "--set", "Output/Progress interval=0",
                           "--set", "Discrete mechanics/Threads=1"]
    for s in extra:
        cmd += ["--set", s]
    if end is not None:
        cmd += ["--set", f"Time stepping/End time={end!r}"]
    env = rn.environment(binary)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()[-600:]}")
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary")
    parser.add_argument("--ranks", nargs="*", type=int, default=[1, 2, 3])
    parser.add_argument("--cases", nargs="*", default=DEFAULT_CASES)
    parser.add_argument("--mechanical-steps", type=int, default=2000)
    parser.add_argument("--thermal-steps", type=int, default=3)
    parser.add_argument("--set", action="append", default=[], dest="sets")
    parser.add_argument("--end-time", type=float,
                        help="End time [s] instead of the span of --mechanical/--thermal-steps")
    parser.add_argument("--out", default=os.path.join("output", "rank_independence"))
    parser.add_argument("--distributed-heat", action="store_true",
                        help="require heat_distributed in summary.json on several ranks")
    args = parser.parse_args()
    rn.VOLATILE.update(MPI_ENTRIES)
    status = 0
    for case in args.cases:
        # a name from prm/, or a path to a prm file (tests/data/...)
        if case.endswith(".prm"):
            prm, case = case, os.path.splitext(os.path.basename(case))[0]
        else:
            prm = os.path.join(rn.ROOT, "prm", case + ".prm")
        work = os.path.join(args.out, case)
        os.makedirs(work, exist_ok=True)
        try:
            end = args.end_time if args.end_time is not None else rn.span(
                args.binary, prm, args.mechanical_steps, args.thermal_steps,
                os.path.join(work, "validate"))
            folders = {}
            for n in args.ranks:
                folders[n] = os.path.join(work, f"np{n}")
                s = run(args.binary, prm, folders[n], end, n, args.sets)
                if s.get("mpi_processes") != n:
                    raise RuntimeError(f"np {n}: summary.json says mpi_processes = "
                                       f"{s.get('mpi_processes')}")
                if args.distributed_heat and n > 1 and s.get("heat_distributed") is not True:
                    raise RuntimeError(f"np {n}: summary.json says heat_distributed = "
                                       f"{s.get('heat_distributed')}, not true")
                print(f"{case:24s} np {n}: {s['steps']} steps, broken joints "
                      f"{s.get('broken_joints', '-')}, contact searches "
                      f"{s.get('contact_searches', '-')}, "
                      f"ghost triangles {s.get('ghost_elements', 0):.0f}, ghost bytes "
                      f"{s.get('ghost_exchange_bytes', 0):.3g}, synchronisations "
                      f"{s.get('synchronisations', '-')}"
                      + (f", heat distributed {s['heat_distributed']}"
                         if "heat_distributed" in s else ""), flush=True)
        except RuntimeError as e:
            status = 1
            print(f"{case:24s} RUN FAILED: {e}", flush=True)
            continue
        base = folders[args.ranks[0]]
        for n in args.ranks[1:]:
            merged = folders[n] + "_merged"
            records = vtu_pieces.merged_view(folders[n], merged)
            if n > 1 and records == 0 and glob.glob(os.path.join(base, "*.vtu")):
                status = 1
                print(f"{case:24s} np {n}: no pvtu records (one vtu piece per rank "
                      f"expected)", flush=True)
                continue
            differ, count = rn.compare(base, merged if records else folders[n])
            span_text = "whole run" if end is None else f"to t = {end:.6g} s"
            if differ:
                status = 1
                print(f"{case:24s} np {n} vs np {args.ranks[0]}: DIFFERS ({span_text}): "
                      f"{', '.join(differ[:8])}", flush=True)
            else:
                print(f"{case:24s} np {n} vs np {args.ranks[0]}: identical "
                      f"({count} files, {records} of them vtu merged from "
                      f"{n} pieces each, {span_text})", flush=True)
    sys.exit(status)


if __name__ == "__main__":
    main()
