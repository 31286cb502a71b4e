#!/usr/bin/python3
"""Radial cracks of a hollow cylinder (or disc) centred at the origin, from
the last cracks_*.vtu of a discrete run.

    count_radial_cracks.py OUTPUT_FOLDER [OUTPUT_FOLDER ...] [--gap DEGREES]
                           [--time SECONDS] [--rate C_PER_S]

The broken joints are grouped by the polar angle of their midpoints: joints
whose angles lie within --gap degrees (default 10) of a neighbour belong to
one crack. Per crack: its angle, its number of joints and the radii it
spans [m]. --time picks the cracks_*.vtu written nearest that time [s]
instead of the last one. With --rate (the inner wall's heating rate
[C/s], T_a = rate t) it also prints, from history.csv and summary.json, the
inner-wall temperature of the first damaged and of the first broken joint,
the joints damaged just before the first break, the relaxations that
reached their cap and the CPU time. Needs only numpy.
"""
import argparse
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_vtu import read_vtu  # noqa: E402


def series_entry(folder, name, time=None):
    """(time [s], path) of the last file of the series name.pvd in folder
    (name: cracks, solution), or of the one written nearest time [s]."""
    pvd = os.path.join(folder, name + ".pvd")
    sets = [(float(d.get("timestep")), d.get("file"))
            for d in ET.parse(pvd).getroot().iter("DataSet")]
    if time is None:
        t, f = max(sets)
    else:
        t, f = min(sets, key=lambda s: abs(s[0] - time))
    return t, os.path.join(folder, f)


def last_cracks(folder, time=None):
    """(time [s], path) of the last cracks_*.vtu, or of the one written
    nearest time [s]."""
    return series_entry(folder, "cracks", time)


def cracks(vtu, gap):
    """[(angle [deg], joints, r_min [m], r_max [m])] of the crack groups."""
    pts, lines, _, _ = read_vtu(vtu, "break_time")
    if len(lines) == 0:
        return []
    mid = np.array([0.5 * (pts[a] + pts[b]) for a, b in lines])
    ang = np.degrees(np.arctan2(mid[:, 1], mid[:, 0])) % 360.
    r = np.hypot(mid[:, 0], mid[:, 1])
    order = np.argsort(ang)
    ang, r = ang[order], r[order]
    # split where consecutive angles differ by more than gap (cyclic)
    diffs = np.diff(np.concatenate([ang, [ang[0] + 360.]]))
    cuts = np.nonzero(diffs > gap)[0]
    if len(cuts) == 0:
        return [(float(np.mean(ang)), len(ang), r.min(), r.max())]
    groups = []
    start = (cuts[-1] + 1) % len(ang)
    idx = [(start + k) % len(ang) for k in range(len(ang))]
    current = [idx[0]]
    for a, b in zip(idx[:-1], idx[1:]):
        if a in cuts:
            groups.append(current)
            current = [b]
        else:
            current.append(b)
    groups.append(current)
    return [(float(ang[g].mean()), len(g), float(r[g].min()), float(r[g].max())) for g in groups]


def history_facts(folder, rate):
    """Line of what history.csv and summary.json say of the fracture."""
    with open(os.path.join(folder, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    damaged = next((r for r in rows if float(r["damaged_joints"]) > 0), None)
    broken = next((i for i, r in enumerate(rows) if float(r["broken_joints"]) > 0), None)
    with open(os.path.join(folder, "summary.json")) as f:
        s = json.load(f)
    def temperature(row):
        return f"{rate * float(row['time']):.1f} C" if row else "none"
    before = int(float(rows[broken - 1]["damaged_joints"])) if broken else None
    return (f"  first damaged joint at T_a = {temperature(damaged)}, first broken at "
            f"{temperature(rows[broken] if broken is not None else None)}, "
            f"{before} joints damaged just before the first break; "
            f"relaxations at the cap {s.get('relaxations_at_cap')}, CPU {s.get('cpu_time_s', 0):.0f} s")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("folders", nargs="+")
    p.add_argument("--gap", type=float, default=10.)
    p.add_argument("--time", type=float, default=None,
                   help="output time [s]; default: the last written")
    p.add_argument("--rate", type=float, default=None,
                   help="inner-wall heating rate [C/s]: also print the "
                        "temperatures of first damage and first break")
    args = p.parse_args()
    for folder in args.folders:
        t, vtu = last_cracks(folder, args.time)
        found = cracks(vtu, args.gap)
        print(f"{folder}: t = {t:g} s, {sum(c[1] for c in found)} broken joints in "
              f"{len(found)} crack(s)")
        for a, n, r0, r1 in found:
            print(f"  {a:6.1f} deg: {n:3d} joints, r = {r0:.4f} .. {r1:.4f} m")
        if args.rate is not None:
            print(history_facts(folder, args.rate))


if __name__ == "__main__":
    main()
