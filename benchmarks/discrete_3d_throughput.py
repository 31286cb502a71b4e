#!/usr/bin/python3
"""Throughput and memory of the discrete layer in 3D, beside the 2D loop
measured in the same run on the same machine.

  3D: an intact 1 m cube of N x N x N hexahedra split into 24 tetrahedra
      each (N = 17: 117 912 tetrahedra, 232 356 face joints), bottom face
      fixed, top face pulled at 0.01 m/s, strong joints (nothing breaks),
      STEPS explicit steps, on 1 and 2 threads;
  2D: prm/plate_traction.prm refined twice (7744 triangles, intact, vector
      batches of the machine's widest instruction set), the same number of
      steps, on 1 thread.

Rates are element-steps per second of the time loop (summary.json:
elements x steps / wall_time_s, the time loop's wall time); the ratio
2D rate / 3D rate is what one tetrahedron-step costs in triangle-steps.
Memory: bytes per tetrahedron of the whole process from the peak resident
memory (ru_maxrss) of the cubes N and N - 4, their difference divided by
the difference in tetrahedra (the libraries' fixed footprint cancels), and
the whole process's peak over its tetrahedra for the cube N.

--numbering ROUNDS measures instead what the tetrahedra's numbering
(`Discrete mechanics/Triangle numbering`) does on an unstructured mesh: the
same pull on a 1 m cube meshed by gmsh (size 0.036 m: about 99 000
tetrahedra, numbered as gmsh writes them), one thread, STEPS steps, with
`mesh` and `Hilbert curve` alternately, ROUNDS times each (needs gmsh).

--set ENTRY=VALUE (repeatable) goes to the 3D runs, e.g.
--set "Discrete mechanics/Vector instructions=AVX-512".
usage: benchmarks/discrete_3d_throughput.py [path/to/tmfdem] [--cells N] [--steps S] [--set ENTRY=VALUE] [--numbering ROUNDS]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from bench_common import help_requested  # noqa: E402

PRM_3D = os.path.join(here, "..", "tests", "data", "discrete", "cube_pull-3d.prm")
PRM_2D = os.path.join(here, "..", "prm", "plate_traction.prm")


def run(binary, prm, folder, settings):
    """Runs tmfdem; returns its summary.json and its peak resident memory
    [bytes] (ru_maxrss of the child)."""
    cmd = [binary, prm, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0", "--set", "Output/Write vtu=false"]
    for s in settings:
        cmd += ["--set", s]
    pid = os.fork()
    if pid == 0:
        with open(os.path.join(folder + ".log"), "w") as log:
            os.dup2(log.fileno(), 1)
            os.dup2(log.fileno(), 2)
            os.execv(binary, cmd)
    _, status, usage = os.wait4(pid, 0)
    if status != 0:
        with open(folder + ".log") as log:
            sys.exit(f"FAIL: {' '.join(cmd)}\n{log.read()[-3000:]}")
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f), usage.ru_maxrss * 1024


def cube(n, steps, threads):
    size = 1.0 / n
    return ["Mesh/Upper right corner=1, 1, 1", f"Mesh/Element size={size!r}",
            "Materials/Material 0/Tensile strength=1e8",
            "Materials/Material 0/Cohesion=2e8",
            "Materials/Material 0/Mode I fracture energy=1e6",
            "Materials/Material 0/Mode II fracture energy=5e6",
            "Mechanical boundary conditions/Condition 1/Boundary ids=4",
            "Mechanical boundary conditions/Condition 2/Boundary ids=5",
            "Mechanical boundary conditions/Condition 2/Velocity x=0",
            "Mechanical boundary conditions/Condition 2/Velocity z=0.01",
            "Time stepping/End time=1", f"Discrete mechanics/Maximum steps={steps}",
            f"Discrete mechanics/Threads={threads}"]


GMSH_CUBE = """SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMin = 0.036; Mesh.MeshSizeMax = 0.036;
Physical Volume(0) = {1};
e = 1e-6;
Physical Surface(4) = {Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e}};
Physical Surface(5) = {Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e}};
Physical Surface(0) = {Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e}};
"""


def numbering(binary, work, args):
    """The gmsh cube with both numberings, alternately."""
    geo, msh = os.path.join(work, "cube.geo"), os.path.join(work, "cube.msh")
    with open(geo, "w") as f:
        f.write(GMSH_CUBE)
    subprocess.run(["gmsh", "-3", geo, "-format", "msh22", "-nt", "1", "-o", msh],
                   check=True, capture_output=True)
    print(f"3D: a 1 m cube meshed by gmsh (size 0.036 m), pulled, {args.steps} steps, "
          f"1 thread, load average {os.getloadavg()[0]:.2f}")
    rates = {"mesh": [], "Hilbert curve": []}
    for r in range(args.numbering):
        for order in rates:
            s, _ = run(binary, PRM_3D, os.path.join(work, f"gmsh_{order[0]}{r}"),
                       cube(17, args.steps, 1)
                       + ["Mesh/Source=file", f"Mesh/File name={msh}",
                          f"Discrete mechanics/Triangle numbering={order}"] + args.set)
            rates[order].append(s["elements"] * s["steps"] / s["wall_time_s"])
            print(f"  {order:>13}: {s['elements']} tetrahedra, {s['joints']} joints, "
                  f"{rates[order][-1]:.4g} tetrahedron-steps/s", flush=True)
    for name, pick in (("best", max), ("median", lambda v: sorted(v)[len(v) // 2])):
        value = {order: pick(v) for order, v in rates.items()}
        print(f"{name} of {args.numbering}: mesh {value['mesh']:.4g}, Hilbert curve "
              f"{value['Hilbert curve']:.4g} tetrahedron-steps/s: "
              f"{value['Hilbert curve'] / value['mesh']:.2f} x")


def main():
    if help_requested(__doc__):
        return
    parser = argparse.ArgumentParser()
    parser.add_argument("binary", nargs="?",
                        default=os.path.join(here, "..", "build-release", "tmfdem"))
    parser.add_argument("--cells", type=int, default=17)
    parser.add_argument("--steps", type=int, default=200)
    parser.add_argument("--set", action="append", default=[],
                        help="ENTRY=VALUE for the 3D runs (repeatable)")
    parser.add_argument("--numbering", type=int, default=0, metavar="ROUNDS",
                        help="the gmsh cube with both numberings instead")
    args = parser.parse_args()
    binary = os.path.abspath(args.binary)
    work = tempfile.mkdtemp(prefix="tmfdem_bench3d_")
    try:
        if args.numbering > 0:
            numbering(binary, work, args)
            return
        print(f"3D: cube of {args.cells}^3 hexahedra x 24 tetrahedra, {args.steps} steps; "
              f"2D: {os.path.basename(PRM_2D)}, {args.steps} steps")
        rates = {}
        for threads in (1, 2):
            s, rss = run(binary, PRM_3D, os.path.join(work, f"cube_{threads}"),
                         cube(args.cells, args.steps, threads) + args.set)
            rates[threads] = s["elements"] * s["steps"] / s["wall_time_s"]
            print(f"3D, {threads} thread(s): {s['elements']} tetrahedra, {s['joints']} joints, "
                  f"{rates[threads]:.4g} tetrahedron-steps/s (threads_used "
                  f"{s['threads_used']}), peak memory {rss / 2**20:.1f} MiB "
                  f"= {rss / s['elements']:.0f} B per tetrahedron")
            if threads == 1:
                n_big, rss_big = s["elements"], rss
        s2, _ = run(binary, PRM_2D, os.path.join(work, "plate"),
                    [f"Discrete mechanics/Maximum steps={args.steps}",
                     "Mesh/Global refinements=2", "Discrete mechanics/Threads=1"])
        rate_2d = s2["elements"] * s2["steps"] / s2["wall_time_s"]
        print(f"2D, 1 thread: {s2['elements']} triangles, {rate_2d:.4g} triangle-steps/s "
              f"({s2.get('vector_instructions', '?')})")
        print(f"a tetrahedron-step costs {rate_2d / rates[1]:.2f} triangle-steps "
              f"(target <= 2.5); 2 threads: {rates[2] / rates[1]:.2f} x 1 thread "
              "(target >= 1.7)")
        small = max(2, args.cells - 4)
        s_small, rss_small = run(binary, PRM_3D, os.path.join(work, "cube_small"),
                                 cube(small, 20, 1) + args.set)
        per = (rss_big - rss_small) / (n_big - s_small["elements"])
        print(f"memory: cubes {args.cells} and {small}: {n_big} and {s_small['elements']} "
              f"tetrahedra, peak {rss_big / 2**20:.1f} and {rss_small / 2**20:.1f} MiB: "
              f"{per:.0f} B per tetrahedron (difference); whole process "
              f"{rss_big / n_big:.0f} B per tetrahedron (target <= 2500)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
