#!/usr/bin/python3
"""Size and write time of the discrete layer's vtu files: the showcase
prm/thermal_shock_disc.prm (about 1000 triangles, discrete
thermo-mechanics) run to END_TIME (default 0.03 s: the outputs at 0, 5, 10,
20 and 30 ms of the shipped run, their cracks included) with

  ascii double:   Output/Vtu format = ascii,  Vtu precision = double
  binary double:  Output/Vtu format = binary, Vtu precision = double
  binary single:  Output/Vtu format = binary, Vtu precision = single (default)

each REPEATS times (default 2), the variants alternating. Per variant: bytes
of all vtu files and of the whole output folder (pvd, csv, mesh, summary
included), the solution vtu per output and per 2000 triangles, the ratios
against ascii double, and the wall time of composing and writing one output
(solution and crack vtu with their pvd records: summary.json
vtu_write_time_s over the number of outputs, the smallest of the repeats).

--reference LABEL=TMFDEM (repeatable) adds the same runs of another build
(its own library: LD_LIBRARY_PATH is set to the binary's folder, so a folder
holding copies of tmfdem and libtmfdem.so serves) with its default Vtu
settings, e.g. a build of another writer; its write time needs
summary.json vtu_write_time_s.

The zlib level: the arrays of the binary files, as tmfdem stores them
(scripts/vtu_pieces.py read_arrays), compressed by Python's zlib at levels 1
to 6 (the library tmfdem links, Debian's libz), each level timed over
several rounds: size of all blocks and compression time per output.

usage: benchmarks/output_files.py [TMFDEM] [--end-time T] [--repeats N]
                                  [--reference LABEL=TMFDEM ...]"""
import argparse
import glob
import json
import os
import subprocess
import sys
import time
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, HERE)
import vtu_pieces  # noqa: E402
from bench_common import help_requested, tmfdem, work_folder  # noqa: E402

VARIANTS = {"ascii double": ("ascii", "double"),
            "binary double": ("binary", "double"),
            "binary single": ("binary", "single")}


def run(binary, folder, end_time, settings, library=None):
    cmd = [binary, os.path.join(ROOT, "prm", "thermal_shock_disc.prm"),
           "--set", f"Output/Directory={folder}", "--set", "Output/Progress interval=0",
           "--set", f"Time stepping/End time={end_time}"]
    for setting in settings:
        cmd += ["--set", setting]
    env = dict(os.environ)
    if library:
        env["LD_LIBRARY_PATH"] = library
    result = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({result.returncode}):\n{result.stderr[-3000:]}")
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


def size(folder, pattern="*"):
    return sum(os.path.getsize(p) for p in glob.glob(os.path.join(folder, pattern))
               if os.path.isfile(p))


def zlib_levels(folder, rounds=5):
    """(level, bytes of all blocks, seconds per output) for levels 1-6."""
    arrays = [np.ascontiguousarray(v).tobytes()
              for name in sorted(glob.glob(os.path.join(folder, "*.vtu")))
              for _, _, v in vtu_pieces.read_arrays(name)]
    outputs = len(glob.glob(os.path.join(folder, "solution_*.vtu")))
    rows = []
    for level in range(1, 7):
        best = float("inf")
        for _ in range(rounds):
            start = time.perf_counter()
            total = sum(len(zlib.compress(a, level)) for a in arrays)
            best = min(best, time.perf_counter() - start)
        rows.append((level, total, best / outputs))
    return rows, sum(len(a) for a in arrays)


def main():
    help_requested(__doc__)
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary", nargs="?")
    parser.add_argument("--end-time", type=float, default=0.03)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--reference", action="append", default=[],
                        metavar="LABEL=TMFDEM")
    options = parser.parse_args()
    binary = tmfdem(options.binary)
    variants = {name: (binary, [f"Output/Vtu format={fmt}", f"Output/Vtu precision={precision}"],
                       None)
                for name, (fmt, precision) in VARIANTS.items()}
    for reference in options.reference:
        label, _, path = reference.partition("=")
        if not label or not path:
            parser.error(f"--reference {reference}: LABEL=TMFDEM expected")
        path = tmfdem(path)
        variants[label] = (path, [], os.path.dirname(path))
    work = work_folder("tmfdem-output-files-")
    print(f"cores: {os.cpu_count()}, load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; prm/thermal_shock_disc.prm to "
          f"{options.end_time} s, {options.repeats} repeats, zlib {zlib.ZLIB_RUNTIME_VERSION}",
          flush=True)
    results = {}
    for repeat in range(options.repeats):
        for k, (name, (path, settings, library)) in enumerate(variants.items()):
            folder = os.path.join(work, f"variant{k}_{repeat}")
            s = run(path, folder, options.end_time, settings, library)
            outputs = len(glob.glob(os.path.join(folder, "solution_*.vtu")))
            per_output = s.get("vtu_write_time_s", float("nan")) / outputs
            print(f"  {name:14s} repeat {repeat}: {outputs} outputs, vtu writing "
                  f"{1e3 * per_output * outputs:.1f} ms, time loop "
                  f"{s.get('wall_time_s', float('nan')):.1f} s", flush=True)
            r = results.setdefault(name, {"folder": folder, "write": [], "summary": s,
                                          "outputs": outputs})
            r["write"].append(per_output)
    reference = results["ascii double"]["folder"]
    elements = results["ascii double"]["summary"]["elements"]
    print(f"\n{elements} triangles, {results['ascii double']['outputs']} outputs (solution and "
          f"cracks vtu each)\n")
    print("| variant | vtu files [bytes] | whole folder [bytes] | solution vtu per output "
          "[kB] | per 2000 triangles [kB] | vtu smaller | folder smaller | write per output "
          "[ms] |")
    print("|---|---|---|---|---|---|---|---|")
    for name, r in results.items():
        folder = r["folder"]
        vtu, whole = size(folder, "*.vtu"), size(folder)
        solution = size(folder, "solution_*.vtu") / r["outputs"]
        print(f"| {name} | {vtu} | {whole} | {solution / 1e3:.1f} | "
              f"{solution / 1e3 * 2000 / elements:.1f} | "
              f"{size(reference, '*.vtu') / vtu:.2f}x | {size(reference) / whole:.2f}x | "
              f"{1e3 * min(r['write']):.2f} |")
    print("\nzlib level (the binary files' arrays compressed by Python's zlib, the same "
          "library):\n")
    for name in ("binary single", "binary double"):
        rows, raw = zlib_levels(results[name]["folder"])
        print(f"{name}: {raw} bytes uncompressed")
        print("| level | compressed [bytes] | against level 1 | compression per output [ms] |")
        print("|---|---|---|---|")
        for level, total, seconds in rows:
            print(f"| {level} | {total} | {total / rows[0][1]:.3f} | {1e3 * seconds:.2f} |")
        print()


if __name__ == "__main__":
    main()
