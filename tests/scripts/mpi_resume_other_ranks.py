"""A discrete run resumed on another number of MPI ranks: the collision case
(refined, fracture and contact) runs uninterrupted on 1 rank; then on 2 ranks
with a checkpoint every 1000 steps, its later checkpoints are removed, and it
is resumed from the middle on 3 ranks. Every output file must be bitwise that
of the uninterrupted run (the vtu pieces of each output, written on 2 and
then on 3 ranks, put back together by scripts/vtu_pieces.py) (summary.json without wall-clock, thread and MPI
traffic entries): checkpoints hold the whole state (theory manual 5.11).

usage: mpi_resume_other_ranks.py TMFDEM MPIRUN OUT_DIR"""
import glob
import json
import os
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True
here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "scripts"))
import results_neutral as rn  # noqa: E402
import vtu_pieces  # noqa: E402

binary, mpirun, out = sys.argv[1], sys.argv[2], sys.argv[3]
prm = os.path.join(here, "..", "..", "prm", "two_blocks_collision.prm")
settings = ["Mesh/Global refinements=1", "Output/Progress interval=0",
            "Time stepping/End time=0.004", "Checkpoint/Keep=100"]
rn.VOLATILE.update({"threads", "threads_requested", "mpi_processes", "ghost_elements",
                    "ghost_exchange_bytes", "synchronisations", "synchronisation_bytes",
                    "communication_time_s",
                    # the vector batches depend on each rank's share of
                    # the triangles and joints
                    "vectorised_joint_share", "vectorised_element_share"})
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(folder, ranks, extra=(), resume=False):
    cmd = [mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
           binary, prm, "--set", f"Output/Directory={folder}"]
    for s in settings + list(extra):
        cmd += ["--set", s]
    if resume:
        cmd.append("--resume")
    print("$", " ".join(cmd), flush=True)
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    print(r.stderr[-800:], flush=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: exit status {r.returncode}")
    return r


reference = os.path.join(out, "reference")
resumed = os.path.join(out, "resumed")
for folder in (reference, resumed):
    shutil.rmtree(folder, ignore_errors=True)
run(reference, 1)
run(resumed, 2, ["Checkpoint/Interval (steps)=1000"])
checkpoints = sorted(glob.glob(os.path.join(resumed, "checkpoints", "*.tmfchk")))
if len(checkpoints) < 4:
    sys.exit(f"FAIL: {len(checkpoints)} checkpoints, expected at least 4")
keep = len(checkpoints) // 2
for f in checkpoints[keep:]:
    os.remove(f)
print(f"resuming from {os.path.basename(checkpoints[keep - 1])} of {len(checkpoints)}")
r = run(resumed, 3, ["Checkpoint/Interval (steps)=1000"], resume=True)
ok = "resumed from" in r.stderr
print(("PASS" if ok else "FAIL") + ": resumed on 3 ranks from a checkpoint written on 2")
# the vtu outputs of 2 and then 3 ranks are pieces: put back together
merged = resumed + "_merged"
records = vtu_pieces.merged_view(resumed, merged)
ok &= records > 0
print(("PASS" if records > 0 else "FAIL") + f": {records} pvtu records merged from their pieces")
differ, count = rn.compare(reference, merged)
# the checkpoint files exist in the resumed run only
differ = [d for d in differ if not d.startswith("checkpoints" + os.sep)]
with open(os.path.join(resumed, "summary.json")) as f:
    s = json.load(f)
ok &= s.get("mpi_processes") == 3
print(("PASS" if s.get("mpi_processes") == 3 else "FAIL") +
      f": the resumed run ran on {s.get('mpi_processes')} ranks")
if differ:
    ok = False
    print("FAIL: differ from the uninterrupted run on 1 rank: " + ", ".join(differ))
else:
    print(f"PASS: {count} output files identical to the uninterrupted run on 1 rank")
sys.exit(0 if ok else 1)
