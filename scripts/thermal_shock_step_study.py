#!/usr/bin/python3
"""Crack pattern of the quenched disc (prm/thermal_shock_disc.prm) against
the thermal step, the element size and the coupling.

    thermal_shock_step_study.py TMFDEM OUT_FOLDER
        [--temperatures 300,400,500] [--steps 0.02,0.005,0.001]
        [--sizes 0.4e-3] [--dynamic] [--mass-scaling 1e4,1e3] [--end 0.1] [--jobs 2]
        [--set "Entry=value" ...]

For every initial temperature T0, element size h and maximum thermal step it
runs the prm (quasi-static coupling, the shipped step control) to --end and,
with --dynamic, once per T0 and h fully dynamic instead (Coupling = dynamic:
one physical clock, the mechanical step of the mesh, the heat every 1000
mechanical steps; --set "Discrete heat/Mechanical steps per thermal step=0"
takes Time stepping/Time step instead: every --set comes after the script's
own settings), and with --mass-scaling F,... once per factor F
dynamic with Discrete mechanics/Mass scaling factor = F (sqrt(F) times
fewer mechanical steps; doc/theory.md 5.6). It prints one markdown row per run: broken joints,
cracks (connected sets of broken joints), deep cracks (reaching more than
1 mm inside the rim), the summed length of the broken joints [mm], the
longest crack's depth below the rim [mm], thermal steps, re-run steps,
steps accepted as unstable growth, relaxations at the cap, CPU time.
Runs already finished in OUT_FOLDER are reused.
"""
import argparse
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_thermal_shock_counts import measure  # noqa: E402
from count_radial_cracks import last_cracks, cracks  # noqa: E402

PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                   "thermal_shock_disc.prm")
R = 6.5e-3
# the prm switched to the dynamic coupling: one clock, a thermal step every
# 1000 mechanical steps (also tests/scripts/verify_discrete_thermal_cracking.py)
DYNAMIC = ["Discrete heat/Coupling=dynamic",
           "Discrete heat/Mechanical steps per thermal step=1000",
           "Discrete heat/Thermal step growth factor=1",
           "Discrete heat/Maximum thermal step=0",
           "Discrete heat/Relaxation damping=mass",
           "Discrete heat/Fracture event duration=0"]


def run(binary, folder, settings):
    summary = os.path.join(folder, "summary.json")
    if os.path.exists(summary) and json.load(open(summary)).get("finished", False):
        return
    cmd = [binary, PRM, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0"]
    for s in settings:
        cmd += ["--set", s]
    with open(folder + ".log", "w") as log:
        subprocess.run(cmd, check=True, stderr=log, stdout=log)


def row(label, folder):
    m = measure(folder)
    if m is None:
        return f"| {label} | (missing) |"
    s = json.load(open(os.path.join(folder, "summary.json")))
    _, vtu = last_cracks(folder)
    groups = cracks(vtu, 3.0)
    longest = max((R - g[2] for g in groups), default=0.)
    return (f"| {label} | {m['broken']} | {m['cracks']} | {m['deep']} | "
            f"{m['length']:.2f} | {1e3 * longest:.2f} | {s.get('thermal_steps', '-')} | "
            f"{s.get('rejected_thermal_steps', '-')} | {s.get('unstable_thermal_steps', '-')} | "
            f"{s.get('relaxations_at_cap', '-')} | {s.get('cpu_time_s', 0):.0f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("--temperatures", default="300,400,500")
    ap.add_argument("--steps", default="0.02,0.005,0.001")
    ap.add_argument("--sizes", default="0.4e-3")
    ap.add_argument("--dynamic", action="store_true")
    ap.add_argument("--mass-scaling", default="")
    ap.add_argument("--end", default="0.1")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], dest="settings")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    runs = []
    for h in args.sizes.split(","):
        for T0 in args.temperatures.split(","):
            common = [f"Initial conditions/Temperature={T0}", f"Mesh/Element size={h}",
                      f"Time stepping/End time={args.end}"]
            for step in args.steps.split(",") if args.steps else []:
                label = f"h {float(h) * 1e3:g} mm, T0 {T0} C, max step {float(step) * 1e3:g} ms"
                folder = os.path.join(args.out, f"h{h}_T{T0}_step{step}")
                runs.append((label, folder, common + [f"Discrete heat/Maximum thermal step={step}"]
                             + args.settings))
            scalings = (["1"] if args.dynamic else []) + \
                [f for f in args.mass_scaling.split(",") if f]
            for f in scalings:
                label = f"h {float(h) * 1e3:g} mm, T0 {T0} C, dynamic" + \
                    (f", mass scaling {f}" if f != "1" else "")
                folder = os.path.join(args.out, f"h{h}_T{T0}_dynamic" +
                                      (f"_f{f}" if f != "1" else ""))
                runs.append((label, folder, common + DYNAMIC +
                             [f"Discrete mechanics/Mass scaling factor={f}"] + args.settings))
    with ThreadPoolExecutor(args.jobs) as pool:
        list(pool.map(lambda r: run(args.binary, r[1], r[2]), runs))
    print("| run | broken joints | cracks | deep cracks | crack length [mm] | "
          "longest [mm] | thermal steps | re-run | unstable | at cap | CPU [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for label, folder, _ in runs:
        print(row(label, folder))


if __name__ == "__main__":
    main()
