#!/usr/bin/python3
"""Crack count of the quenched disc against T0 for several element sizes.

    plot_thermal_shock_counts.py PNG SIZE_MM:SWEEP_FOLDER [SIZE_MM:SWEEP_FOLDER ...]
        [--temperatures 300,400,500] [--seeds 1,2]

Each SWEEP_FOLDER is an output folder of scripts/thermal_shock_sweep.py
(sub-folders T<T0>_homogeneous and T<T0>_weibull<seed>). For every run it
reads summary.json (cracks: connected sets of broken joints; broken joints)
and the last cracks_*.vtu (crack groups by polar angle, gap 3 degrees, as
scripts/count_radial_cracks.py; "deep": reaching more than 1 mm inside the
rim R = 6.5 mm), prints one table row per run and draws the crack count and
the count of deep cracks and the crack length against T0, homogeneous and Weibull, one line style
per element size. Runs that are missing are skipped.
"""
import argparse
import json
import os
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from count_radial_cracks import last_cracks, cracks  # noqa: E402
from plot_vtu import read_vtu  # noqa: E402

R = 6.5e-3  # disc radius [m]


def measure(folder):
    """cracks, deep cracks, broken joints, first damage interval [ms] of one run,
    or None if the run is missing or unfinished."""
    path = os.path.join(folder, "summary.json")
    if not os.path.exists(path):
        return None
    s = json.load(open(path))
    if not s.get("finished", True):
        return None
    _, vtu = last_cracks(folder)
    groups = cracks(vtu, 3.0)
    deep = sum(1 for g in groups if R - g[2] > 1e-3)
    pts, lines, _, _ = read_vtu(vtu, "break_time")
    length = 1e3 * sum(float(np.linalg.norm(pts[a] - pts[b])) for a, b in lines)
    d = np.genfromtxt(os.path.join(folder, "history.csv"), delimiter=",", names=True)
    i = int(np.argmax(d["damaged_joints"] > 0))
    first = (1e3 * d["time"][i - 1], 1e3 * d["time"][i]) if d["damaged_joints"][i] > 0 else None
    return dict(cracks=s["cracks"], deep=deep, broken=s["broken_joints"], length=length,
                first=first)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("png")
    ap.add_argument("sweeps", nargs="+", help="SIZE_MM:FOLDER")
    ap.add_argument("--temperatures", default="300,400,500")
    ap.add_argument("--seeds", default="1,2")
    args = ap.parse_args()
    temps = [int(t) for t in args.temperatures.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")]

    fig, axes = plt.subplots(1, 3, figsize=(14, 3.9), dpi=150)
    styles = ["-", "--", ":"]
    print("size [mm]  T0 [C]  run          cracks  deep  broken  length [mm]  first damage [ms]")
    for k, spec in enumerate(args.sweeps):
        size, folder = spec.split(":", 1)
        hom = {T: measure(os.path.join(folder, f"T{T}_homogeneous")) for T in temps}
        wei = {(T, s): measure(os.path.join(folder, f"T{T}_weibull{s}"))
               for T in temps for s in seeds}
        for T in temps:
            for name, r in [("homogeneous", hom[T])] + [(f"Weibull {s}", wei[(T, s)]) for s in seeds]:
                if r is None:
                    continue
                first = "-" if r["first"] is None else f"({r['first'][0]:.2f}, {r['first'][1]:.2f}]"
                print(f"{size:>9s}  {T:6d}  {name:12s} {r['cracks']:6d}  {r['deep']:4d}  "
                      f"{r['broken']:6d}  {r['length']:11.1f}  {first}")
        for ax, key in zip(axes, ["cracks", "deep", "length"]):
            ts = [T for T in temps if hom[T] is not None]
            ax.plot(ts, [hom[T][key] for T in ts], "k" + styles[k % 3], marker="o",
                    label=f"homogeneous, {size} mm mesh")
            tw = [T for T in temps if any(wei[(T, s)] is not None for s in seeds)]
            if not tw:
                continue
            mean = [np.mean([wei[(T, s)][key] for s in seeds if wei[(T, s)] is not None])
                    for T in tw]
            ax.plot(tw, mean, styles[k % 3], color="tab:blue", marker="s",
                    label=f"Weibull m = 10, mean of seeds {args.seeds}, {size} mm mesh")
    axes[0].set_ylabel("cracks (connected sets of broken joints)")
    axes[1].set_ylabel("cracks reaching > 1 mm inside the rim")
    axes[2].set_ylabel("summed length of the broken joints [mm]")
    for ax in axes:
        ax.set_xlabel("initial temperature T0 [C]")
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("alumina disc quenched in 15 C water (3e4 W/(m^2 K)): cracks at t = 100 ms", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.png)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
