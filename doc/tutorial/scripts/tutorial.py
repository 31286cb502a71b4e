"""Shared helpers of the tutorial lesson scripts (doc/tutorial/scripts/).

Each lesson script is run as

    /usr/bin/python3 doc/tutorial/scripts/lesson_NN_<name>.py TMFDEM OUT [--plot PNG]

It runs tmfdem on the lesson's prm files (doc/tutorial/prm/) into OUT,
prints one line per asserted number (PASS: ... / FAIL: ...), draws the
lesson's figure when --plot is given, and exits 0 only if every check
passed. The ctests `tutorial.*` run the same scripts without --plot."""
import argparse
import os
import sys

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
PRM = os.path.join(ROOT, "doc", "tutorial", "prm")
sys.path.insert(0, os.path.join(ROOT, "tests", "scripts"))
sys.path.insert(0, os.path.join(ROOT, "scripts"))

from common import run, summary, check  # noqa: E402,F401
from analytic import read_csv  # noqa: E402


def arguments(doc):
    """TMFDEM OUT [--plot PNG] from the command line."""
    parser = argparse.ArgumentParser(description=doc,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("tmfdem", help="the tmfdem binary, e.g. build-release/tmfdem")
    parser.add_argument("out", help="folder for the runs' outputs")
    parser.add_argument("--plot", help="write the lesson's figure to this png")
    return parser.parse_args()


def prm(name):
    """Path of a tutorial prm file."""
    return os.path.join(PRM, name)


def probes(folder):
    """probes.csv -> {name: {time: {column: value}}}."""
    data = read_csv(os.path.join(folder, "probes.csv"))
    return {name: {t: {c: v[0] for c, v in cols.items()} for t, (_, _, cols) in by_time.items()}
            for name, by_time in data.items()}


def line_at_end(folder, name):
    """(x, y, {column: values}) of monitor line `name` at the last output time."""
    data = read_csv(os.path.join(folder, "lines.csv"))[name]
    return data[max(data)]


def pyplot():
    """matplotlib.pyplot with a file-only backend."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3})
    return plt


def finish(ok):
    print("lesson checks: " + ("all passed" if ok else "SOME FAILED"), flush=True)
    sys.exit(0 if ok else 1)
