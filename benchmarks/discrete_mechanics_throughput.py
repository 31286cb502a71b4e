#!/usr/bin/python3
"""Throughput of the discrete layer's explicit loop, in triangle-steps per
second, at 1 and 2 threads:
  intact:     a 1 m square plate of 60 x 60 cells, two triangles each (7200
              triangles, 10680 joints), bottom on rollers, top pulled at
              0.1 m/s, strong joints (nothing breaks), contact on;
  fragmented: the same plate with weak joints, 2 mm above a fixed floor,
              thrown down at 20 m/s: it hits the floor after about 250
              steps and shatters, and most of the run has thousands of
              active contact pairs.
Memory: bytes per triangle of the discrete state from the peak resident
memory of two intact plates (200 x 200 and 100 x 100 cells), their
difference divided by the difference in triangles (the libraries' fixed
footprint cancels).
Each case runs in REPEATS pairs (1 thread, then 2 threads; default 3): the
machine may be shared, so each pair's speed-up, its load average and the
median are printed; history.csv of the two runs of a pair must be identical.
Columns: cpu = the time loop's process CPU time (all threads), busiest = the
CPU time of its busiest thread. Where other processes take the cores the
wall-clock speed-up says little; 1-thread CPU / busiest thread of the
2-thread run is then the speed-up the split of the work allows (thread
waits spin, so it is a bound, not a measurement of speed).

With --against REFERENCE (a second tmfdem binary, e.g. the build of the
commit before a refactor, in its own build folder or copied together with
its libtmfdem.so: a copy of tmfdem alone loads its build folder's library) the program instead compares the two builds side
by side on one thread: REPEATS rounds of (reference, candidate) runs of both
cases, alternating, and prints each run's rate, the candidate / reference
ratio of the median rates and of the median loop CPU times, and whether the
two builds' history.csv are identical (if not, the three columns that differ
most in the first round, relative to each column's largest value).
With --reference-set "Subsection/Entry=value" (repeatable) the reference
runs get that setting too: --against the same binary compares a setting's
cost, e.g. --reference-set "Discrete mechanics/Anisotropic joint compliance
compensation=false". With --against, --cells N takes plates of N x N cells
instead of 60 x 60 (N = 354: the 250 632 triangles of the MPI benchmark, a
mesh that does not fit in the caches) with 3000 (60 / N)^2 and 6000 (60 /
N)^2 steps (at least 20), and --intact-only leaves out the fragmented plate.
The fragmented runs must end with at least MIN_BROKEN_JOINTS broken joints
and MIN_CONTACT_PAIRS contact pairs (summary.json), else the benchmark fails.
The temporary folder of the runs is removed at the end (--keep keeps it).
usage: benchmarks/discrete_mechanics_throughput.py [path/to/tmfdem [REPEATS]]
       benchmarks/discrete_mechanics_throughput.py --against REFERENCE path/to/tmfdem [REPEATS]
                                                   [--reference-set S ...] [--cells N] [--intact-only]"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))

# the fragmented plate must shatter: at least these many broken joints and
# contact pairs at the end of every fragmented run (summary.json), else the
# benchmark fails (it would measure an intact plate in free flight)
MIN_BROKEN_JOINTS = 1000
MIN_CONTACT_PAIRS = 1000
# gap between the plate and the floor [m]: at 20 m/s the plate reaches the
# floor after 1e-4 s, about 250 of its 6000 steps of 4.1e-7 s
FLOOR_GAP = 0.002


def parse_arguments():
    parser = argparse.ArgumentParser(
        description=__doc__.split("\nusage:")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binary", nargs="?",
                        default=os.path.join(here, "..", "build-release", "tmfdem"),
                        help="the tmfdem binary (default: build-release/tmfdem)")
    parser.add_argument("repeats", nargs="?", type=int, default=3,
                        help="pairs or rounds per case (default 3)")
    parser.add_argument("--against", metavar="REFERENCE",
                        help="compare with this second tmfdem binary, 1 thread")
    parser.add_argument("--reference-set", action="append", default=[],
                        metavar="Subsection/Entry=value",
                        help="a --set for the reference runs only (repeatable)")
    parser.add_argument("--cells", type=int, default=60,
                        help="with --against: plates of N x N cells (default 60)")
    parser.add_argument("--intact-only", action="store_true",
                        help="with --against: leave out the fragmented plate")
    parser.add_argument("--keep", action="store_true",
                        help="keep the temporary folder of the runs")
    arguments = parser.parse_args()
    if not os.path.isfile(arguments.binary):
        parser.error(f"no tmfdem binary at '{arguments.binary}'")
    if arguments.against is not None and not os.path.isfile(arguments.against):
        parser.error(f"no reference binary at '{arguments.against}'")
    if arguments.repeats < 1 or arguments.cells < 1:
        parser.error("repeats and --cells must be >= 1")
    return arguments


options = parse_arguments() if __name__ == "__main__" else None
binary = options.binary if options else None
repeats = options.repeats if options else 3
reference = options.against if options else None
reference_settings = [a for s in (options.reference_set if options else [])
                      for a in ("--set", s)]
cells = options.cells if options else 60
intact_only = options.intact_only if options else False
work = None


def plate_msh(n, with_floor):
    """n x n cells on [0,1]^2, each cut into two triangles (counter-clockwise);
    boundary ids 2 bottom, 3 top (physical lines); material 1. With a floor:
    a fixed slab (material 2) FLOOR_GAP below the plate."""
    nodes, triangles, lines = [], [], []
    def nid(i, j):
        return j * (n + 1) + i + 1
    for j in range(n + 1):
        for i in range(n + 1):
            nodes.append((i / n, j / n))
    for j in range(n):
        for i in range(n):
            a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
            triangles += [(1, a, b, c), (1, a, c, d)]
    for i in range(n):
        lines += [(2, nid(i, 0), nid(i + 1, 0)), (3, nid(i, n), nid(i + 1, n))]
    if with_floor:
        base = len(nodes)
        fx = [-0.5 + 2.0 * k / 20 for k in range(21)]
        for y in (-0.1 - FLOOR_GAP, -FLOOR_GAP):
            for x in fx:
                nodes.append((x, y))
        for k in range(20):
            a, b = base + k + 1, base + k + 2
            c, d = base + 21 + k + 2, base + 21 + k + 1
            triangles += [(2, a, b, c), (2, a, c, d)]
    name = os.path.join(work, f"plate_{n}{'_floor' if with_floor else ''}.msh")
    with open(name, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(nodes))
        for k, (x, y) in enumerate(nodes):
            f.write(f"{k + 1} {x!r} {y!r} 0\n")
        f.write("$EndNodes\n$Elements\n%d\n" % (len(lines) + len(triangles)))
        k = 0
        for tag, a, b in lines:
            k += 1
            f.write(f"{k} 1 2 {tag} {tag} {a} {b}\n")
        for tag, a, b, c in triangles:
            k += 1
            f.write(f"{k} 2 2 {tag} {tag} {a} {b} {c}\n")
        f.write("$EndElements\n")
    return name


def prm(mesh, strong, floor):
    text = f"""set Model = discrete mechanics
subsection Mesh
  set Source = file
  set File name = {mesh}
end
subsection Materials
"""
    for m in (1, 2):
        text += f"""  subsection Material {m}
    set Density = 2500
    set Young's modulus = 10e9
    set Poisson's ratio = 0.25
    set Tensile strength = {'1e9' if strong else '2e5'}
    set Cohesion = {'1e9' if strong else '4e5'}
    set Mode I fracture energy = {'1e6' if strong else '1'}
    set Mode II fracture energy = {'1e6' if strong else '5'}
  end
"""
    text += "end\n"
    if floor:
        text += """subsection Discrete bodies
  subsection Body 1
    set Material ids = 2
    set Motion = fixed
  end
  subsection Body 2
    set Material ids = 1
    set Initial velocity y = -20
  end
end
subsection Discrete mechanics
  set Gravity = 0, -9.81
end
"""
    else:
        text += """subsection Mechanical boundary conditions
  subsection Condition 1
    set Boundary ids = 2
    set Type = roller y
  end
  subsection Condition 2
    set Boundary ids = 3
    set Type = velocity
    set Velocity x = 0
    set Velocity y = 0.1
  end
end
"""
    text += """subsection Time stepping
  set End time = 1
end
subsection Output
  set Write vtu = false
  set Progress interval = 0
end
"""
    name = mesh.replace(".msh", ".prm")
    with open(name, "w") as f:
        f.write(text)
    return name


def run(prm_file, threads, steps, out, program=None, extra=()):
    cmd = [program or binary, prm_file, "--set", f"Output/Directory={out}",
           "--set", f"Discrete mechanics/Threads={threads}",
           "--set", f"Discrete mechanics/Maximum steps={steps}"]
    cmd += list(extra)
    env = dict(os.environ)
    folder = os.path.dirname(os.path.abspath(cmd[0]))
    if os.path.exists(os.path.join(folder, "libtmfdem.so")):
        # a copied build: tmfdem with its own libtmfdem.so beside it
        env["LD_LIBRARY_PATH"] = folder + os.pathsep + env.get("LD_LIBRARY_PATH", "")
    result = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed (exit status {result.returncode}):\n"
                 f"{result.stderr[-2000:]}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def check_fragmented(summary, label):
    """Fails the benchmark unless the fragmented plate really shattered."""
    broken, pairs = summary["broken_joints"], summary["contact_pairs"]
    if broken < MIN_BROKEN_JOINTS or pairs < MIN_CONTACT_PAIRS:
        sys.exit(f"FAILED: the fragmented plate ({label}) did not fragment: "
                 f"{broken} broken joints (at least {MIN_BROKEN_JOINTS} "
                 f"expected) and {pairs} contact pairs (at least "
                 f"{MIN_CONTACT_PAIRS}) at the end of its run")


def identical(a, b):
    with open(os.path.join(a, "history.csv"), "rb") as fa, \
            open(os.path.join(b, "history.csv"), "rb") as fb:
        return fa.read() == fb.read()


def history_difference(a, b):
    """Largest difference between two history.csv files, per column, over
    that column's largest magnitude in the first; the three largest as text."""
    import csv
    with open(os.path.join(a, "history.csv")) as fa, open(os.path.join(b, "history.csv")) as fb:
        ra, rb = list(csv.DictReader(fa)), list(csv.DictReader(fb))
    if len(ra) != len(rb):
        return f"{len(ra)} against {len(rb)} rows"
    worst = {}
    for column in ra[0] if ra else []:
        try:
            va = [float(r[column]) for r in ra]
            vb = [float(r[column]) for r in rb]
        except (ValueError, KeyError):
            continue
        scale = max(abs(v) for v in va) or 1.
        worst[column] = max(abs(x - y) for x, y in zip(va, vb)) / scale
    top = sorted(worst.items(), key=lambda kv: -kv[1])[:3]
    return ", ".join(f"{k} {v:.1e}" for k, v in top)


def compare_builds():
    """Reference and candidate side by side on one thread, alternating."""
    print(f"cores: {os.cpu_count()}, load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; {repeats} rounds "
          f"(reference, then candidate) per case, 1 thread\n"
          f"reference: {reference}\ncandidate: {binary}")
    print(f"{'case':>11} {'round':>5} {'build':>9} {'steps':>6} {'wall [s]':>8} "
          f"{'cpu [s]':>7} {'triangle-steps/s':>16} {'load':>5}")
    def steps(n):
        return max(20, round(n * (60 / cells) ** 2))
    cases = [("intact", prm(plate_msh(cells, False), True, False), steps(3000))]
    if not intact_only:
        cases.append(("fragmented", prm(plate_msh(cells, True), False, True),
                      steps(6000)))
    for name, p, steps in cases:
        rates = {"reference": [], "candidate": []}
        cpus = {"reference": [], "candidate": []}
        same = True
        for r in range(repeats):
            folders = {}
            for build, program in (("reference", reference), ("candidate", binary)):
                folder = os.path.join(work, f"{name}_{r}_{build}")
                folders[build] = folder
                s = run(p, 1, steps, folder, program,
                        reference_settings if build == "reference" else ())
                if name == "fragmented":
                    check_fragmented(s, f"{build}, round {r + 1}")
                rates[build].append(s["element_steps_per_second"])
                cpus[build].append(s["cpu_time_s"])
                print(f"{name:>11} {r + 1:>5} {build:>9} {s['steps']:>6} "
                      f"{s['wall_time']:>8.2f} {s['cpu_time_s']:>7.2f} "
                      f"{s['element_steps_per_second']:>16.3e} "
                      f"{os.getloadavg()[0]:>5.2f}", flush=True)
            same &= identical(folders["reference"], folders["candidate"])

        def median(v):
            return sorted(v)[len(v) // 2]
        print(f"{name}: candidate / reference: median rate "
              f"{median(rates['candidate']) / median(rates['reference']):.3f}, "
              f"median loop CPU {median(cpus['candidate']) / median(cpus['reference']):.3f} "
              f"(below 1: candidate faster); history.csv of the builds "
              f"{'identical' if same else 'DIFFER'}", flush=True)
        if not same:
            print(f"{name}: largest difference of round 1 per column / the "
                  f"column's largest value: "
                  f"{history_difference(os.path.join(work, f'{name}_0_reference'), os.path.join(work, f'{name}_0_candidate'))}",
                  flush=True)


def main():
    if reference is not None:
        compare_builds()
        return

    print(f"cores: {os.cpu_count()}, load average before: "
          f"{' '.join(f'{x:.2f}' for x in os.getloadavg())}; {repeats} paired "
          "runs (1 thread, then 2) per case")
    print(f"{'case':>11} {'pair':>4} {'threads':>7} {'used':>4} {'triangles':>9} "
          f"{'steps':>6} {'wall [s]':>8} {'cpu [s]':>7} {'busiest':>7} {'cpu/wall':>8} "
          f"{'triangle-steps/s':>16} {'pairs':>6} {'broken':>7} {'load':>5}")
    intact = prm(plate_msh(60, False), True, False)
    fragmented = prm(plate_msh(60, True), False, True)
    speedups, bounds = {}, {}
    for name, p, steps in (("intact", intact, 3000), ("fragmented", fragmented, 6000)):
        for pair in range(repeats):
            rates, cpu, busiest = {}, {}, {}
            for threads in (1, 2):
                folder = os.path.join(work, f"{name}_{pair}_{threads}")
                s = run(p, threads, steps, folder)
                if name == "fragmented":
                    check_fragmented(s, f"pair {pair + 1}, {threads} thread(s)")
                rate = s["element_steps_per_second"]
                rates[threads] = rate
                cpu[threads] = s["cpu_time_s"]
                busiest[threads] = s["cpu_time_busiest_thread_s"]
                print(f"{name:>11} {pair + 1:>4} {threads:>7} {s['threads_used']:>4} "
                      f"{s['elements']:>9} {s['steps']:>6} {s['wall_time']:>8.2f} "
                      f"{s['cpu_time_s']:>7.2f} {s['cpu_time_busiest_thread_s']:>7.2f} "
                      f"{s['cpu_time_s'] / s['wall_time_s']:>8.2f} {rate:>16.3e} "
                      f"{s['contact_pairs']:>6} {s['broken_joints']:>7} "
                      f"{os.getloadavg()[0]:>5.2f}", flush=True)
            same = identical(os.path.join(work, f"{name}_{pair}_1"),
                             os.path.join(work, f"{name}_{pair}_2"))
            speedups.setdefault(name, []).append(rates[2] / rates[1])
            bounds.setdefault(name, []).append(cpu[1] / busiest[2])
            print(f"{'':>11} {'':>4} 2 threads / 1 thread: {rates[2] / rates[1]:.2f}x wall; "
                  f"CPU 2 / 1 thread {cpu[2] / cpu[1]:.2f}; 1-thread CPU / busiest thread "
                  f"of 2: {cpu[1] / busiest[2]:.2f}; history.csv "
                  f"{'identical' if same else 'DIFFERS'}", flush=True)
    for name, values in speedups.items():
        values = sorted(values)
        b = sorted(bounds[name])
        print(f"{name}: speed-up 2 vs 1 thread: median {values[len(values) // 2]:.2f}x, "
              f"best {values[-1]:.2f}x, worst {values[0]:.2f}x over {len(values)} pairs; "
              f"1-thread CPU / busiest thread of 2: median {b[len(b) // 2]:.2f}")

    big = run(prm(plate_msh(200, False), True, False), 1, 20, os.path.join(work, "mem_200"))
    small = run(prm(plate_msh(100, False), True, False), 1, 20, os.path.join(work, "mem_100"))
    per_triangle = (big["peak_resident_memory_bytes"] - small["peak_resident_memory_bytes"]) / \
                   (big["elements"] - small["elements"])
    print(f"\nmemory: peak RSS {small['peak_resident_memory_bytes'] / 2**20:.1f} MiB at "
          f"{small['elements']} triangles, {big['peak_resident_memory_bytes'] / 2**20:.1f} MiB at "
          f"{big['elements']}: {per_triangle:.0f} bytes per triangle (all of the run: mesh, "
          f"deal.II triangulation and DoFs, discrete state, joints, contact lists)")


if __name__ == "__main__":
    work = tempfile.mkdtemp(prefix="tmfdem-bench-")
    try:
        main()
    finally:
        if options.keep:
            print(f"runs kept in {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)
