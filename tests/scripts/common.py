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


SKIP = 77  # ctest SKIP_RETURN_CODE of the thread tests


def check_parallel(s, threads=2, load_before=None, min_wall=0.5):
    """Checks that the run of summary s really ran on `threads` threads.
    Asserted always: the cores this process may use (threads_available,
    from its affinity mask and the MPI ranks on the node) are at least
    `threads` -- fewer fails clearly, not vacuously -- and the concurrency
    measured at start-up (threads_used: `threads` threads inside the arena
    together) equals `threads`. For a time loop of at least min_wall
    seconds over more than one chunk (512 triangles, 512 joints or 256
    contact pairs), the work must also have been shared: process CPU time > 1.2 x
    wall time and the other threads' CPU time >= 0.25 x the busiest
    thread's. Those two depend on the machine having the cores free; if
    they fail while other processes kept at least one core busy
    (load_before, the 1-minute load average before the runs, >= 1 on top
    of cores - threads), the result is 'skipped' (ctest: Not Run) with the
    load quoted, never 'passed'.
    Returns "pass", "fail" or "skip"."""
    available = s.get("threads_available", 0)
    if available < threads:
        print(f"FAIL: this machine gives the process {available} core(s) "
              f"(affinity mask, cores per MPI rank): a {threads}-thread run "
              f"cannot be checked here; run this test where {threads} cores "
              "are free", flush=True)
        return "fail"
    if not check(s.get("threads_used") == threads,
                 f"threads_used = {s.get('threads_used')} (measured concurrency "
                 f"of the arena; requested {s.get('threads_requested')}, "
                 f"{available} cores available): {threads} expected"):
        return "fail"
    cpu, wall = s.get("cpu_time_s", 0.0), s.get("wall_time_s", 0.0)
    busiest = s.get("cpu_time_busiest_thread_s", 0.0)
    others = s.get("cpu_time_other_threads_s", 0.0)
    if (s.get("elements", 0) <= 512 and s.get("joints", 0) <= 512
            and s.get("contact_pairs", 0) <= 256):
        print(f"note: {s.get('elements')} triangles, {s.get('joints')} joints "
              f"and {s.get('contact_pairs')} contact pairs each fill one fixed "
              "chunk (512, 512, 256), so the loop cannot split: CPU/wall "
              f"({cpu:.3f}/{wall:.3f} s) not asserted, only threads_used",
              flush=True)
        return "pass"
    if wall < min_wall:
        print(f"note: time loop {wall:.3f} s < {min_wall} s: CPU/wall "
              f"({cpu:.3f}/{wall:.3f} s) not asserted", flush=True)
        return "pass"
    shared = cpu > 1.2 * wall and others >= 0.25 * busiest
    message = (f"time loop: CPU {cpu:.3f} s, wall {wall:.3f} s: ratio "
               f"{cpu / wall:.2f} (needs > 1.2); busiest thread {busiest:.2f} "
               f"s, others {others:.2f} s (need >= 0.25 x busiest): the "
               "threads ran in parallel")
    cores = os.cpu_count() or 1
    busy = load_before is not None and load_before >= 1.0 + (cores - threads)
    if not shared and busy:
        print(f"SKIPPED (not passed): {message} -- not met while the machine "
              f"was busy: 1-minute load average {load_before:.2f} on {cores} "
              "cores before the runs; rerun when it is idle", flush=True)
        return "skip"
    return "pass" if check(shared, message) else "fail"
