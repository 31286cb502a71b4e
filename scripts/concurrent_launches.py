#!/usr/bin/env python3
"""Concurrent start-up check: WORKERS loops, each launching
`tmfdem --validate prm/joint_pull.prm` LAUNCHES times one after the other,
all loops at once, and counts the launches that fail (exit status not 0).
Prints the first failure's output. Extra NAME=VALUE arguments go into the
environment of every launch (e.g. to compare Open MPI settings:
OMPI_MCA_orte_create_session_dirs=1 brings back the shared session
directory that made isolated singletons fail, doc/performance.md
"Start-up time").

usage: scripts/concurrent_launches.py [path/to/tmfdem [WORKERS [LAUNCHES]]] [NAME=VALUE ...]
Exit status 0 when every launch succeeded, 1 otherwise."""
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.join(here, "..")
positional = [a for a in sys.argv[1:] if "=" not in a]
settings = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
binary = positional[0] if positional else os.path.join(root, "build-release", "tmfdem")
workers = int(positional[1]) if len(positional) > 1 else 8
launches = int(positional[2]) if len(positional) > 2 else 40
prm = os.path.join(root, "prm", "joint_pull.prm")
env = dict(os.environ)
env.update(settings)


def loop(_):
    failures = []
    for _ in range(launches):
        result = subprocess.run([binary, "--validate", prm], env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True)
        if result.returncode != 0:
            failures.append(result.stdout)
    return failures


with ThreadPoolExecutor(max_workers=workers) as pool:
    failures = [f for fs in pool.map(loop, range(workers)) for f in fs]
total = workers * launches
extra = " ".join(f"{k}={v}" for k, v in settings.items()) or "none"
print(f"{workers} concurrent loops x {launches} launches of tmfdem --validate; "
      f"extra environment: {extra}; load average after: "
      f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}")
print(f"failed: {len(failures)} of {total}")
if failures:
    print("first failure's output:\n" + failures[0][:3000])
sys.exit(1 if failures else 0)
