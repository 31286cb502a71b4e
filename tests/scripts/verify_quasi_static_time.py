"""Quasi-static coupling runs in thermal time: an edge driven at velocity v
moves v t, whatever the number of relaxation steps per thermal step (before,
it moved v dt per relaxation step). A relaxation that reaches its cap is
counted in summary.json and warned about, and with `Relaxation cap is
error` it stops the run (exit 2)."""
import csv
import os
import subprocess
import sys

from common import check, summary

binary, out = sys.argv[1], sys.argv[2]
prm = os.path.join(os.path.dirname(__file__), "..", "..", "prm",
                   "sheet_free_expansion.prm")
v, end = 1e-4, 4.0
base = ["Discrete heat/Coupling=quasi-static", "Time stepping/Time step=1",
        f"Time stepping/End time={end}",
        "Mechanical boundary conditions/Condition 3/Boundary ids=1",
        "Mechanical boundary conditions/Condition 3/Type=velocity",
        f"Mechanical boundary conditions/Condition 3/Velocity x={v}",
        "Mechanical boundary conditions/Condition 3/Velocity y=0",
        "Monitors/Probes=edge: 2, 1", "Monitors/Lines=", "Output/Write vtu=false"]


def run(name, *extra):
    d = os.path.join(out, name)
    cmd = [binary, prm, "--set", f"Output/Directory={d}",
           "--set", "Output/Progress interval=0"]
    for s in base + list(extra):
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True)
    print(r.stderr[-1500:], flush=True)
    return d, r


ok = True
for cap in [400, 2000, 6000]:
    d, r = run(f"cap_{cap}",
               f"Discrete heat/Mechanical steps per thermal step={cap}")
    ok &= check(r.returncode == 0, f"cap {cap}: exit {r.returncode}")
    if r.returncode != 0:
        continue
    with open(os.path.join(d, "probes.csv")) as f:
        rows = [row for row in csv.DictReader(f) if row["name"] == "edge"]
    last = rows[-1]
    ux = float(last["ux"])
    ok &= check(abs(float(last["time"]) - end) < 1e-12 and
                abs(ux - v * end) <= 1e-9 * v * end,
                f"cap {cap}: driven edge at t = {last['time']} s moved "
                f"{ux:.12g} m, v t = {v * end:.12g} m (relative 1e-9)")
    s = summary(d)
    at_cap = s.get("relaxations_at_cap")
    warned = "reached its cap" in r.stderr
    ok &= check(at_cap is not None and (at_cap > 0) == warned,
                f"cap {cap}: {at_cap} relaxations at the cap counted, "
                f"warning printed: {warned}")
    if cap == 400:
        n = s["thermal_steps"]
        ok &= check(at_cap == n, f"cap 400: all {n} thermal steps at the cap "
                                 f"({at_cap})")

d, r = run("cap_error", "Discrete heat/Mechanical steps per thermal step=400",
           "Discrete heat/Relaxation cap is error=true")
ok &= check(r.returncode == 2 and "reached its cap" in r.stderr and
            os.path.exists(os.path.join(d, "last_good_state.vtu")),
            f"Relaxation cap is error: exit {r.returncode} (2), message and "
            f"last good state written")

d, r = run("ramp_too_short", "Discrete heat/Mechanical steps per thermal step=150")
ok &= check(r.returncode == 1 and "too few for quasi-static coupling" in r.stderr,
            f"150 relaxation steps with an imposed velocity refused: exit "
            f"{r.returncode} (1)")
sys.exit(0 if ok else 1)
