#!/usr/bin/python3
"""Instructions of the explicit loop, counted by valgrind's callgrind: a
measure of a kernel change's cost that does not depend on what else the
machine is doing (the same count for the same binary and input).

Runs prm/plate_traction.prm (intact plate, vector batches of the widest
instruction set valgrind emulates, AVX2) for STEPS explicit steps on one
thread with each binary and prints the inclusive instruction counts of
ExplicitSolver::step() (the whole step), of the AVX2 joint batch
(elastic_joint_batch_avx2) and of the AVX2 element batch
(update_free_batch_avx2), and the candidate / reference ratios.

usage: benchmarks/loop_instructions.py CANDIDATE_TMFDEM [--against REFERENCE_TMFDEM]
                                        [--steps 1500]

A binary in a folder holding a copy of libtmfdem.so runs with that library
(LD_LIBRARY_PATH), as in benchmarks/discrete_mechanics_throughput.py.
Needs valgrind (callgrind_annotate); about a minute per binary.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from bench_common import help_requested, tmfdem, work_folder  # noqa: E402

PRM = os.path.join(HERE, "..", "prm", "plate_traction.prm")
FUNCTIONS = {"step": r"ExplicitSolver::step\(\)",
             "joint batch": r"elastic_joint_batch_avx2\(",
             "element batch": r"update_free_batch_avx2<false>\("}


def count(binary, steps, work):
    folder = os.path.dirname(os.path.abspath(binary))
    env = dict(os.environ)
    if os.path.exists(os.path.join(folder, "libtmfdem.so")):
        env["LD_LIBRARY_PATH"] = folder + ":" + env.get("LD_LIBRARY_PATH", "")
    out = os.path.join(work, "callgrind.out")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", binary, PRM,
                    "--set", f"Output/Directory={os.path.join(work, 'run')}",
                    "--set", f"Discrete mechanics/Maximum steps={steps}",
                    "--set", "Discrete mechanics/Threads=1",
                    "--set", "Output/Progress interval=0", "--set", "Output/Write vtu=false"],
                   env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", out], check=True,
                          capture_output=True, text=True).stdout
    counts = {}
    for name, pattern in FUNCTIONS.items():
        for line in text.splitlines():
            # the function's own line (its object file named), not its callers'
            if re.search(pattern, line) and "libtmfdem.so]" in line:
                counts[name] = int(line.split()[0].replace(",", ""))
                break
    return counts


def main():
    help_requested(__doc__)
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        sys.exit("valgrind and callgrind_annotate are needed (apt-get install valgrind)")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("--against")
    ap.add_argument("--steps", type=int, default=1500)
    args = ap.parse_args()
    builds = [("candidate", tmfdem(args.binary))] + (
        [("reference", tmfdem(args.against))] if args.against else [])
    results = {}
    for label, binary in builds:
        results[label] = count(binary, args.steps, work_folder(f"tmfdem-instructions-{label}-"))
    print(f"instructions, prm/plate_traction.prm, {args.steps} steps, one thread")
    print("| function | " + " | ".join(label for label, _ in builds) +
          (" | candidate / reference |" if args.against else " |"))
    print("|---|" + "---|" * (len(builds) + (1 if args.against else 0)))
    for name in FUNCTIONS:
        row = [f"{results[label].get(name, 0):.4g}" for label, _ in builds]
        if args.against:
            ref = results["reference"].get(name, 0)
            row.append(f"{results['candidate'].get(name, 0) / ref:.4f}" if ref else "-")
        print(f"| {name} | " + " | ".join(row) + " |")
    return 0 if all(results[label] for label, _ in builds) else 1


if __name__ == "__main__":
    sys.exit(main())
