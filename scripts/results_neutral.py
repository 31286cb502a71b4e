#!/usr/bin/env python3
"""Results-neutral check for refactors: run every prm/*.prm case for a
fixed short span with two tmfdem binaries (the commit before the change and
the change) and compare all their outputs bitwise.

usage: scripts/results_neutral.py REFERENCE_TMFDEM CANDIDATE_TMFDEM
           [--out DIR] [--cases NAME ...] [--mechanical-steps N]
           [--thermal-steps N] [--keep-vtu]

The span of each case is read from `tmfdem --validate` of the reference
binary: N mechanical steps (default 300) of the step it would use for the
discrete mechanics and the dynamic thermo-mechanics, N thermal steps
(default 3) of `Time stepping/Time step` for quasi-static coupling, the
continuum heat and the discrete heat (x 10), and the whole case for steady
continuum runs. Both binaries get the same `--set` overrides (End time,
output folder, no progress lines, one thread for the discrete layer so that
the comparison does not depend on the machine's cores).

Compared: every file both runs write (csv, vtu, pvd, pvtu, msh), bitwise,
and summary.json without its wall-clock entries (the date stamps deal.II
writes into vtu/pvd headers are ignored). Exit status 0 when every
case is identical, 1 when any differs (the differing files are listed),
2 when a run fails.

Build the reference in a worktree of the commit before the change, e.g.
  git worktree add /tmp/before HEAD~1 && (cd /tmp/before && bash scripts/build.sh)
  scripts/results_neutral.py /tmp/before/build-release/tmfdem build-release/tmfdem
A copy of the tmfdem program alone is not a reference: it still loads the
libtmfdem.so of the build folder it came from, which the next build
replaces. A folder holding copies of both tmfdem and libtmfdem.so is run with
that libtmfdem.so (LD_LIBRARY_PATH). The check refuses two binaries that
load the same libtmfdem.so.
"""
import argparse
import filecmp
import glob
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
VOLATILE = {"wall_time", "element_steps_per_second", "peak_resident_memory_bytes",
            "cpu_time_s", "wall_time_s", "threads_used", "threads_available",
            "cpu_time_busiest_thread_s", "cpu_time_other_threads_s", "prm_file",
            "communication_time_s", "vtu_write_time_s"}
SKIP_FILES = {"gmsh.log"}
NEW_SUMMARY_KEYS = set()  # summary.json entries only the candidate writes


def prm_value(prm, entry, default=None):
    """The first `set <entry> = value` in a prm file (no subsection logic:
    the entries asked for here are unique)."""
    with open(prm) as f:
        for line in f:
            m = re.match(r"\s*set\s+" + re.escape(entry) + r"\s*=\s*(.*?)\s*(#.*)?$", line)
            if m:
                return m.group(1)
    return default


def environment(binary):
    """The environment to run @p binary in: with LD_LIBRARY_PATH on its own
    folder when a libtmfdem.so lies next to it (a copied build)."""
    env = dict(os.environ)
    folder = os.path.dirname(os.path.abspath(binary))
    if os.path.exists(os.path.join(folder, "libtmfdem.so")):
        env["LD_LIBRARY_PATH"] = folder + os.pathsep + env.get("LD_LIBRARY_PATH", "")
    return env


def library_of(binary):
    """The libtmfdem.so @p binary loads (ldd), or None if not found."""
    r = subprocess.run(["ldd", binary], capture_output=True, text=True,
                       env=environment(binary))
    for line in r.stdout.splitlines():
        if "libtmfdem.so" in line and "=>" in line:
            path = line.split("=>")[1].split("(")[0].strip()
            return os.path.realpath(path) if path and path != "not" else None
    return None


def span(binary, prm, mechanical_steps, thermal_steps, work):
    """End time [s] for the short span of this case, or None (whole run)."""
    model = prm_value(prm, "Model", "continuum heat")
    start = float(prm_value(prm, "Start time", "0"))
    mode = prm_value(prm, "Mode", "transient")
    if model.startswith("continuum") and mode == "steady":
        return None
    r = subprocess.run([binary, "--validate", prm, "--set", f"Output/Directory={work}"],
                       env=environment(binary),
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"--validate failed ({r.returncode}): {r.stderr.strip()[-400:]}")
    text = r.stdout + r.stderr
    dt = float(prm_value(prm, "Time step", "0") or 0)
    if model == "discrete thermo-mechanics" and prm_value(prm, "Coupling", "dynamic") == "quasi-static":
        return start + thermal_steps * dt
    m = re.search(r"mechanical time step: (?:stable \S+ s, )?used (\S+) s", text)
    if m:
        return start + mechanical_steps * float(m.group(1))
    m = re.search(r"time step: (?:stable \S+ s, )?used (\S+) s", text)
    if m:
        return start + 10 * thermal_steps * float(m.group(1))
    return None


def run(binary, prm, folder, end):
    if os.path.isdir(folder):
        shutil.rmtree(folder)
    cmd = [binary, prm, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0",
           "--set", "Discrete mechanics/Threads=1"]
    if end is not None:
        cmd += ["--set", f"Time stepping/End time={end!r}"]
    r = subprocess.run(cmd, capture_output=True, text=True, env=environment(binary))
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()[-400:]}")


def strip(value):
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


STAMP = re.compile(rb"This file was generated by the deal.II library on [^\n]*")


def same_but_stamp(pa, pb):
    """deal.II writes the date and time into vtu/pvd/pvtu headers: equal
    apart from those stamps?"""
    with open(pa, "rb") as fa, open(pb, "rb") as fb:
        return STAMP.sub(b"", fa.read()) == STAMP.sub(b"", fb.read())


def compare(a, b):
    """Files that differ or exist on one side only (relative paths)."""
    differ = []
    files_a = {os.path.relpath(p, a) for p in glob.glob(os.path.join(a, "**", "*"), recursive=True)
               if os.path.isfile(p)}
    files_b = {os.path.relpath(p, b) for p in glob.glob(os.path.join(b, "**", "*"), recursive=True)
               if os.path.isfile(p)}
    for name in sorted(files_a ^ files_b):
        if os.path.basename(name) not in SKIP_FILES:
            differ.append(name + " (one side only)")
    for name in sorted(files_a & files_b):
        if os.path.basename(name) in SKIP_FILES:
            continue
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if name.endswith("summary.json"):
            with open(pa) as fa, open(pb) as fb:
                ja, jb = strip(json.load(fa)), strip(json.load(fb))
            # entries the candidate adds are reported, not a difference;
            # entries it drops or changes are
            added = sorted(set(jb) - set(ja))
            if added:
                NEW_SUMMARY_KEYS.update(added)
            if ja != {k: v for k, v in jb.items() if k in ja}:
                differ.append(name)
        elif not filecmp.cmp(pa, pb, shallow=False) and not same_but_stamp(pa, pb):
            differ.append(name)
    return differ, len(files_a & files_b)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("reference")
    parser.add_argument("candidate")
    parser.add_argument("--out", default=os.path.join("output", "results_neutral"))
    parser.add_argument("--cases", nargs="*", help="prm names without .prm (default: all)")
    parser.add_argument("--mechanical-steps", type=int, default=300)
    parser.add_argument("--thermal-steps", type=int, default=3)
    args = parser.parse_args()
    for b in (args.reference, args.candidate):
        if not os.access(b, os.X_OK):
            sys.exit(f"error: '{b}' is not an executable tmfdem binary")
    libraries = [library_of(b) for b in (args.reference, args.candidate)]
    for b, lib in zip((args.reference, args.candidate), libraries):
        print(f"{b} loads {lib}")
    if (libraries[0] is not None and libraries[0] == libraries[1] and
            os.path.realpath(args.reference) != os.path.realpath(args.candidate)):
        sys.exit(f"error: both binaries load the same {libraries[0]}: the comparison "
                 "would run one library twice. Build the reference in its own folder "
                 "(a git worktree), or copy tmfdem together with its libtmfdem.so.")
    prms = sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm")))
    if args.cases:
        names = set(args.cases)
        prms = [p for p in prms if os.path.basename(p)[:-4] in names]
        missing = names - {os.path.basename(p)[:-4] for p in prms}
        if missing:
            sys.exit(f"error: no prm/<case>.prm for {', '.join(sorted(missing))}")
    status = 0
    for prm in prms:
        case = os.path.basename(prm)[:-4]
        folder = os.path.join(args.out, case)
        try:
            end = span(args.reference, prm, args.mechanical_steps, args.thermal_steps,
                       os.path.join(folder, "validate"))
            run(args.reference, prm, os.path.join(folder, "reference"), end)
            run(args.candidate, prm, os.path.join(folder, "candidate"), end)
        except RuntimeError as e:
            print(f"{case:40s} RUN FAILED: {e}", flush=True)
            status = max(status, 2)
            continue
        differ, n = compare(os.path.join(folder, "reference"), os.path.join(folder, "candidate"))
        span_text = "whole run" if end is None else f"to t = {end:.6g} s"
        if differ:
            status = max(status, 1)
            print(f"{case:40s} DIFFERS ({span_text}): {', '.join(differ[:8])}"
                  + (" ..." if len(differ) > 8 else ""), flush=True)
        else:
            print(f"{case:40s} identical ({n} files, {span_text})", flush=True)
    if NEW_SUMMARY_KEYS:
        print("summary.json entries only the candidate writes (not compared): "
              + ", ".join(sorted(NEW_SUMMARY_KEYS)))
    sys.exit(status)


if __name__ == "__main__":
    main()
