"""Run by pvbatch (tests/scripts/verify_vtu_outputs.py paraview): opens
every output named in a JSON spec with ParaView's own readers and checks
its time steps, array names, sizes and value ranges against the spec.

    xvfb-run -a pvbatch tests/scripts/paraview_check.py SPEC.json

SPEC: list of {"file", "times" (the pvd's time steps, [] for a single
file), "time" (the one checked), "n_points", "n_cells", "point_data" and
"cell_data" ({name: [min, max] of component 0, or null without finite
values})}. Exit status 0 when everything matches.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import paraview_path  # noqa: E402,F401  (finds python3-paraview's package)
from paraview.simple import OpenDataFile, UpdatePipeline


def close(a, b):
    return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b))


def main():
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    ok = True

    def check(condition, message):
        nonlocal ok
        ok &= bool(condition)
        print(("PASS: " if condition else "FAIL: ") + message, flush=True)

    for item in spec:
        name = item["file"]
        reader = OpenDataFile(name)
        if reader is None:
            check(False, f"{name}: ParaView has no reader for it")
            continue
        times = list(reader.TimestepValues) if reader.TimestepValues else []
        if isinstance(reader.TimestepValues, float):
            times = [reader.TimestepValues]
        check(len(times) == len(item["times"]) and all(map(close, times, item["times"])),
              f"{name} ({reader.GetXMLName()}): time steps {times} (pvd: {item['times']})")
        UpdatePipeline(time=item["time"], proxy=reader)
        info = reader.GetDataInformation()
        check(info.GetNumberOfPoints() == item["n_points"] and
              info.GetNumberOfCells() == item["n_cells"],
              f"{name} at t = {item['time']:.6g}: {info.GetNumberOfPoints()} points, "
              f"{info.GetNumberOfCells()} cells (expected {item['n_points']}, {item['n_cells']})")
        for kind, arrays in (("point_data", reader.PointData), ("cell_data", reader.CellData)):
            expected = item[kind]
            check(sorted(arrays.keys()) == sorted(expected),
                  f"{name}: {kind} arrays {sorted(arrays.keys())}")
            for array_name, span in expected.items():
                if array_name not in arrays.keys():
                    continue
                low, high = arrays[array_name].GetRange(0)
                if span is None:
                    check(not low <= high, f"{name}: {array_name} has no finite value")
                    continue
                good = (math.isfinite(low) and math.isfinite(high) and close(low, span[0])
                        and close(high, span[1]))
                check(good, f"{name}: {array_name} in [{low:.9g}, {high:.9g}] "
                      f"(expected [{span[0]:.9g}, {span[1]:.9g}])")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
