#!/usr/bin/python3
"""Start-up time of tmfdem on small cases: wall-clock and CPU time of whole
runs of prm/joint_pull.prm (2 triangles, 30 000 steps) and of
`tmfdem --validate prm/thermal_shock_disc.prm` (reads the mesh, sets up,
runs nothing), REPEATS times each (default 5), interleaved with the same
runs under Open MPI's default singleton start-up (support daemon, session
directory, all transports; what tmfdem did before it isolated the
singleton, see source/main.cc) and with `tmfdem --help` (loading the
libraries and MPI_Init only).

usage: benchmarks/startup_time.py [path/to/tmfdem [REPEATS]]"""
import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
parser = argparse.ArgumentParser(
    description=__doc__.split("\nusage:")[0],
    formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("binary", nargs="?",
                    default=os.path.join(root, "build-release", "tmfdem"),
                    help="the tmfdem binary (default: build-release/tmfdem)")
parser.add_argument("repeats", nargs="?", type=int, default=5,
                    help="runs of each case and start-up (default 5)")
options = parser.parse_args()
if not os.path.isfile(options.binary):
    parser.error(f"no tmfdem binary at '{options.binary}'")
binary, repeats = options.binary, options.repeats
# every output (and the mesh that --validate writes) goes here, removed
# at the end: nothing is left in the working directory
work = tempfile.mkdtemp(prefix="tmfdem-startup-")

# Open MPI's defaults for a process started without mpirun, set explicitly
# (tmfdem's own settings do not overwrite the environment)
default_singleton = {
    "OMPI_MCA_ess_singleton_isolated": "0",
    "OMPI_MCA_orte_create_session_dirs": "1",
    "OMPI_MCA_pml": "ob1",
    "OMPI_MCA_btl": "self,vader,tcp",
}

cases = {
    "help": [binary, "--help"],
    "joint_pull": [binary, os.path.join(root, "prm", "joint_pull.prm"),
                   "--set", f"Output/Directory={os.path.join(work, 'joint_pull')}"],
    "validate": [binary, "--validate", os.path.join(root, "prm", "thermal_shock_disc.prm"),
                 "--set", f"Output/Directory={os.path.join(work, 'validate')}"],
}


def timed(command, env):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = subprocess.run(command, env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if result.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({result.returncode}):\n{result.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


try:
    print(f"cores: {os.cpu_count()}, load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; {repeats} interleaved runs each")
    print(f"{'case':>11} {'start-up':>17} {'wall mean':>9} {'wall min':>8} {'cpu mean':>8}")
    for name, command in cases.items():
        samples = {"isolated": [], "default": []}
        for r in range(repeats):
            for mode in ("isolated", "default"):
                env = dict(os.environ)
                for key in default_singleton:
                    env.pop(key, None)
                if mode == "default":
                    env.update(default_singleton)
                samples[mode].append(timed(command, env))
        for mode in ("isolated", "default"):
            walls = [w for w, _ in samples[mode]]
            cpus = [c for _, c in samples[mode]]
            label = "tmfdem (isolated)" if mode == "isolated" else "Open MPI default"
            print(f"{name:>11} {label:>17} {sum(walls) / len(walls):>9.3f} {min(walls):>8.3f} "
                  f"{sum(cpus) / len(cpus):>8.3f}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
finally:
    shutil.rmtree(work, ignore_errors=True)
