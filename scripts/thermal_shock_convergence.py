#!/usr/bin/env python3
"""First damage time of prm/thermal_shock_disc.prm against the element size
(doc/cases/thermal_shock_disc.md, "Convergence of the first damage time").

  /usr/bin/python3 scripts/thermal_shock_convergence.py TMFDEM OUT \\
      [--sizes 0.4e-3,0.25e-3,0.15e-3] [--cases 3e4:300,3e4:500,1e4:300,1e4:500] [--jobs 2]

For every (heat transfer coefficient, T0) and element size h it runs the prm
until the analytic hoop stress at the depth h sqrt(3)/3 has reached f_t
(times --end-factor, default 1.2), reads the first damage from history.csv (the bracket
(t_prev, t_first]) and prints a markdown table with the analytic times at
the rim and at the centroid depths h sqrt(3)/6 and h sqrt(3)/3 of the rim
triangles. Only the temperature field and history are written (no vtu).
"""
import argparse
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "scripts"))
import analytic  # noqa: E402

PRM = os.path.join(HERE, "..", "prm", "thermal_shock_disc.prm")
R, E, ALPHA, FT = 6.5e-3, 370e9, 7.5e-6, 180e6


def analytic_times(hc, T0, h):
    kw = dict(radius=R, conductivity=35., diffusivity=35. / (3980 * 850.), h=hc,
              t_ambient=15., t_initial=T0)
    t = [analytic.quenched_disc_hoop_stress_time(FT, E, ALPHA, R - d, **kw)
         for d in (0., h * np.sqrt(3) / 6, h * np.sqrt(3) / 3)]
    return t


def run_one(binary, out, hc, T0, h, end_factor=1.2, report_only=False):
    t_rim, t1, t2 = analytic_times(hc, T0, h)
    # f_t never reached at the centroid depth: run to 1.3 x the rim time
    # (the rim stress peaks soon after), or 0.3 s
    end = end_factor * t2 if t2 else (1.3 * t_rim if t_rim else 0.3)
    folder = os.path.join(out, f"h{hc:g}_T{T0:g}_size{h * 1e3:.2f}mm")
    cmd = [binary, PRM, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0", "--set", "Output/Write vtu=false",
           "--set", f"Initial conditions/Temperature={T0}",
           "--set", f"Thermal boundary conditions/Condition 1/Heat transfer coefficient={hc}",
           "--set", f"Mesh/Element size={h}", "--set", f"Time stepping/End time={end}"]
    if not report_only:
        result = subprocess.run(cmd, capture_output=True, text=True)
        if result.returncode != 0:
            return (hc, T0, h, t_rim, t1, t2, None, None, result.stderr[-500:])
    if not os.path.exists(os.path.join(folder, "history.csv")):
        return (hc, T0, h, t_rim, t1, t2, None, None, "not run")
    hist = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
    onset = np.nonzero(hist["damaged_joints"] > 0)[0]
    if len(onset) == 0:
        return (hc, T0, h, t_rim, t1, t2, None, None, f"no damage by {end * 1e3:.1f} ms")
    i = onset[0]
    return (hc, T0, h, t_rim, t1, t2, hist["time"][i - 1] if i > 0 else 0.,
            hist["time"][i], "")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("--sizes", default="0.4e-3,0.25e-3,0.15e-3")
    ap.add_argument("--cases", default="3e4:300,3e4:500,1e4:300,1e4:500")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--end-factor", type=float, default=1.2,
                    help="End time = this x the analytic time at h sqrt(3)/3")
    ap.add_argument("--report-only", action="store_true",
                    help="read the runs already in OUT, run nothing")
    a = ap.parse_args()
    sizes = [float(s) for s in a.sizes.split(",")]
    cases = [tuple(float(v) for v in c.split(":")) for c in a.cases.split(",")]
    jobs = [(hc, T0, h) for hc, T0 in cases for h in sizes]
    with ThreadPoolExecutor(a.jobs) as pool:
        rows = list(pool.map(lambda j: run_one(a.binary, a.out, *j, a.end_factor, a.report_only), jobs))
    print("| h [W/(m^2 K)] | T0 [C] | element size [mm] | first damage in [ms] | "
          "analytic: rim [ms] | h sqrt(3)/6 inside [ms] | h sqrt(3)/3 inside [ms] | "
          "in the window | first damage / rim time |")
    print("|---|---|---|---|---|---|---|---|---|")
    for hc, T0, h, t_rim, t1, t2, tp, tf, note in rows:
        def ms(t):
            return f"{t * 1e3:.2f}" if t else "never"
        if tf is None:
            print(f"| {hc:g} | {T0:g} | {h * 1e3:.2f} | {note} | {ms(t_rim)} | "
                  f"{ms(t1)} | {ms(t2)} | {'yes' if t1 is None else 'NO'} | - |")
            continue
        inside = t1 is not None and tf >= t1 and (t2 is None or tp <= t2)
        print(f"| {hc:g} | {T0:g} | {h * 1e3:.2f} | ({tp * 1e3:.2f}, {tf * 1e3:.2f}] | "
              f"{ms(t_rim)} | {ms(t1)} | {ms(t2)} | "
              f"{'yes' if inside else 'NO'} | {tf / t_rim:.3f} |", flush=True)


if __name__ == "__main__":
    main()
