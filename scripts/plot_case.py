#!/usr/bin/python3
"""Plot a case's computed line samples against its analytic reference.

    plot_case.py CASE OUTPUT_FOLDER PNG

Reads OUTPUT_FOLDER/lines.csv (header time,name,x,y,T; one row per sample
point per output time), evaluates the reference from tests/scripts/analytic.py
on the same points, and draws two panels: T (computed as markers, reference
as lines, one colour per time) and the error T - T_exact. The max abs error
per time is printed as a table. To add a case, add an entry to CASES.
"""
import os
import sys

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "scripts"))
sys.dont_write_bytecode = True  # keep tests/scripts free of __pycache__
import analytic  # noqa: E402

# case -> line in lines.csv, reference T(x, y, t), abscissa s(x, y) and its label,
# steady (plot one curve, no "t = " labels) or transient (skip t = 0, the initial state)
CASES = {
    "plate_transient-continuum": dict(
        line="midline",
        reference=lambda x, y, t: analytic.plate_transient(x, t),
        abscissa=lambda x, y: x, xlabel="x [m]",
        steady=False,
        title="Plate, transient conduction: midline y = 0.125"),
    "thick_cylinder-continuum": dict(
        line="radial",
        reference=lambda x, y, t: analytic.cylinder_temperature(np.hypot(x, y)),
        abscissa=lambda x, y: np.hypot(x, y), xlabel="r [m]",
        steady=True,
        title="Thick cylinder, steady conduction: radial line"),
}


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in CASES:
        sys.exit(f"usage: {os.path.basename(sys.argv[0])} CASE OUTPUT_FOLDER PNG\n"
                 f"  CASE: {', '.join(CASES)}")
    case, folder, png = sys.argv[1:]
    spec = CASES[case]
    data = analytic.read_csv(os.path.join(folder, "lines.csv"))
    if spec["line"] not in data:
        sys.exit(f"{folder}/lines.csv: no line '{spec['line']}' (have: {', '.join(data)})")
    by_time = data[spec["line"]]
    times = sorted(by_time)
    if spec["steady"]:
        times = times[-1:]
    else:
        times = [t for t in times if t > 0]

    fig, (ax_t, ax_e) = plt.subplots(2, 1, figsize=(7, 7), sharex=True, dpi=150,
                                     gridspec_kw=dict(height_ratios=[3, 2]))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(times)))
    print(f"{case}: line '{spec['line']}'")
    print(f"{'time [s]':>10} {'points':>7} {'max |T - T_exact| [C]':>22}")
    for t, c in zip(times, colours):
        x, y, cols = by_time[t]
        s = spec["abscissa"](x, y)
        order = np.argsort(s)
        s, T, T_exact = s[order], cols["T"][order], spec["reference"](x, y, t)[order]
        err = T - T_exact
        max_err = np.max(np.abs(err))
        print(f"{t:>10g} {len(s):>7d} {max_err:>22.4g}")
        label = "computed" if spec["steady"] else f"t = {t:g} s"
        label += f" (max err {max_err:.3g} C)"
        ax_t.plot(s, T_exact, "-", color=c, lw=1.2)
        ax_t.plot(s, T, "o", color=c, ms=3, mfc="none", label=label)
        ax_e.plot(s, err, "o-", color=c, ms=2, lw=0.8)
    ax_t.plot([], [], "-", color="gray", label="analytic")
    ax_t.set_ylabel("T [C]")
    ax_t.set_title(spec["title"])
    ax_t.legend(fontsize=8)
    ax_t.grid(alpha=0.3)
    ax_e.axhline(0, color="k", lw=0.5)
    ax_e.set_xlabel(spec["xlabel"])
    ax_e.set_ylabel("T - T_exact [C]")
    ax_e.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
