#!/usr/bin/python3
"""Crack count of the quenched disc (prm/thermal_shock_disc.prm) against the
initial temperature, homogeneous and with Weibull joint strengths.

    thermal_shock_sweep.py TMFDEM OUT_FOLDER PNG_PREFIX
        [--temperatures 250,300,400,500] [--seeds 1,2,3] [--jobs 2]
        [--set "Entry=value" ...]

Runs one case per initial temperature without heterogeneity and one per
temperature and seed with Heterogeneity = Weibull (modulus 10), then writes
PNG_PREFIX_count.png (crack count and broken joints against T0) and
PNG_PREFIX_patterns.png (the final crack pattern over the temperature of the
homogeneous runs), and prints a table. Runs already finished in OUT_FOLDER
(summary.json with finished = true) are reused.
"""
import argparse
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_thermal_cracking import datasets, draw  # noqa: E402

PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "prm",
                   "thermal_shock_disc.prm")


def run(binary, folder, settings):
    summary = os.path.join(folder, "summary.json")
    if os.path.exists(summary) and json.load(open(summary)).get("finished", True):
        return json.load(open(summary))
    cmd = [binary, PRM, "--set", f"Output/Directory={folder}"]
    for s in settings:
        cmd += ["--set", s]
    with open(folder + ".log", "w") as log:
        subprocess.run(cmd, check=True, stderr=log, stdout=log)
    return json.load(open(summary))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("out")
    ap.add_argument("prefix")
    ap.add_argument("--temperatures", default="250,300,400,500")
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], dest="settings")
    args = ap.parse_args()
    temps = [int(t) for t in args.temperatures.split(",")]
    seeds = [int(s) for s in args.seeds.split(",")] if args.seeds else []
    os.makedirs(args.out, exist_ok=True)

    jobs = {}
    for T0 in temps:
        base = args.settings + [f"Initial conditions/Temperature={T0}"]
        jobs[(T0, 0)] = (f"{args.out}/T{T0}_homogeneous", base)
        for s in seeds:
            jobs[(T0, s)] = (f"{args.out}/T{T0}_weibull{s}",
                             base + ["Discrete mechanics/Heterogeneity=Weibull",
                                     f"Discrete mechanics/Random seed={s}"])
    with ThreadPoolExecutor(args.jobs) as pool:
        futures = {key: pool.submit(run, args.binary, folder, settings)
                   for key, (folder, settings) in jobs.items()}
        results = {key: f.result() for key, f in futures.items()}

    print("T0 [C]  run          cracks  broken joints")
    for (T0, s), r in sorted(results.items()):
        print(f"{T0:6d}  {'homogeneous' if s == 0 else f'Weibull {s}':12s} "
              f"{r['cracks']:6d}  {r['broken_joints']:6d}")

    fig, ax = plt.subplots(figsize=(5.5, 3.8), dpi=150)
    ax.plot(temps, [results[(T, 0)]["cracks"] for T in temps], "ko-",
            label="homogeneous")
    if seeds:
        counts = np.array([[results[(T, s)]["cracks"] for s in seeds] for T in temps])
        for i, s in enumerate(seeds):
            ax.plot(temps, counts[:, i], "s", color="tab:blue", alpha=0.5,
                    label="Weibull m = 10, seeds" if i == 0 else None)
        ax.plot(temps, counts.mean(axis=1), "-", color="tab:blue", label="Weibull mean")
    ax.set_xlabel("initial temperature T0 [C] (quench into 15 C water)")
    ax.set_ylabel("number of cracks")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.prefix + "_count.png")

    fig, axes = plt.subplots(1, len(temps), figsize=(3.0 * len(temps) + 0.8, 3.4),
                             dpi=150, squeeze=False)
    for ax, T0 in zip(axes[0], temps):
        folder = jobs[(T0, 0)][0]
        t, solution = datasets(folder, "solution")[-1]
        _, cracks = datasets(folder, "cracks")[-1]
        im, n = draw(ax, solution, cracks, (15, max(temps)))
        ax.set_title(f"T0 = {T0} C, t = {t * 1e3:.0f} ms\n"
                     f"{results[(T0, 0)]['cracks']} cracks", fontsize=9)
    fig.colorbar(im, ax=axes[0].tolist(), label="T [C]", shrink=0.85)
    fig.savefig(args.prefix + "_patterns.png", bbox_inches="tight")
    print(f"wrote {args.prefix}_count.png, {args.prefix}_patterns.png")


if __name__ == "__main__":
    main()
