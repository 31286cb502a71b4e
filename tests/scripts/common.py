"""Helpers shared by the verification scripts: run tmfdem, read outputs."""
import json
import os
import subprocess
import sys

sys.dont_write_bytecode = True


def run(binary, prm, out_dir, *settings, mpirun=None, np=1, check=True):
    """Runs tmfdem on prm with --set overrides into out_dir; returns stdout."""
    cmd = [binary, prm, "--set", f"Output/Directory={out_dir}",
           "--set", "Output/Progress interval=0"]
    for s in settings:
        cmd += ["--set", s]
    if mpirun:
        cmd = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(np)] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    print("$", " ".join(f"'{c}'" if " " in c else c for c in cmd), flush=True)
    result = subprocess.run(cmd, capture_output=True, text=True, env=env)
    print(result.stdout[-2000:], result.stderr[-2000:], flush=True)
    if check and result.returncode != 0:
        sys.exit(f"FAIL: tmfdem exited with {result.returncode}")
    return result.stdout


def summary(out_dir):
    with open(os.path.join(out_dir, "summary.json")) as f:
        return json.load(f)


def check(condition, message):
    print(("PASS: " if condition else "FAIL: ") + message, flush=True)
    return bool(condition)
