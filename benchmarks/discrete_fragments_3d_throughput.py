#!/usr/bin/python3
"""Throughput of contact between many free tetrahedra: a 0.1 m cube meshed
by gmsh into about 12 700 tetrahedra (size 7.5 mm) that share no node (the
block fully fragmented: no joints, every tetrahedron a piece of its own,
touching its neighbours face to face), moving at 10 m/s onto a fixed base
1 um below it, on one thread, for 20 us (the compression wave crosses 40 %
of the block), with Contact = true and with Contact = false (the same
elements; without contact the pieces pass through each other and the base).

Printed: tetrahedra, steps, contact pairs, the time loop's wall time,
element-steps per second, and the contact's share of the time,
1 - t(Contact = false) / t(Contact = true).

Needs gmsh and python3-meshio (both installed by
scripts/install-dependencies.sh).

usage: benchmarks/discrete_fragments_3d_throughput.py [path/to/tmfdem]
"""
import json
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from bench_common import help_requested, tmfdem, work_folder  # noqa: E402

help_requested(__doc__)
binary = tmfdem(sys.argv[1] if len(sys.argv) > 1 else None)
work = work_folder("tmfdem_fragments_3d_")

import numpy as np  # noqa: E402
import meshio  # noqa: E402

BOX = """SetFactory("OpenCASCADE");
Box(1) = {%s};
Mesh.MeshSizeMin = %g; Mesh.MeshSizeMax = %g;
Mesh.RandomSeed = 1;
"""


def tetrahedra(name, box, size):
    """Nodes and tetrahedra of a gmsh box."""
    geo, msh = os.path.join(work, name + ".geo"), os.path.join(work, name + ".msh")
    with open(geo, "w") as f:
        f.write(BOX % (box, size, size))
    subprocess.run(["gmsh", "-3", geo, "-format", "msh22", "-o", msh],
                   check=True, capture_output=True)
    mesh = meshio.read(msh)
    return mesh.points, mesh.cells_dict["tetra"]


# the block (material 1): every tetrahedron with nodes of its own
points, cells = tetrahedra("block", "0, 0, 0, 0.1, 0.1, 0.1", 0.0075)
block_points = points[cells].reshape(-1, 3)
n_free = len(cells)
block_cells = np.arange(4 * n_free).reshape(n_free, 4)
# the base (material 2, fixed): one conformal mesh, its top 1 um below
points, base_cells = tetrahedra("base", "-0.01, -0.01, -0.02, 0.12, 0.12, 0.019999", 0.02)
all_points = np.vstack([block_points, points])
all_cells = np.vstack([block_cells, base_cells + len(block_points)])
ids = np.concatenate([np.ones(n_free, int), 2 * np.ones(len(base_cells), int)])
mesh_file = os.path.join(work, "fragments.msh")
meshio.write(mesh_file, meshio.Mesh(all_points, [("tetra", all_cells)],
                                    cell_data={"gmsh:physical": [ids],
                                               "gmsh:geometrical": [ids]}),
             file_format="gmsh22", binary=False)

MATERIAL = """  subsection Material %d
    set Density = 2500
    set Young's modulus = 1e10
    set Poisson's ratio = 0.25
  end
"""
prm = os.path.join(work, "fragments.prm")
with open(prm, "w") as f:
    f.write(f"""set Model = discrete mechanics
subsection Mesh
  set Dimension = 3
  set Source = file
  set File name = {mesh_file}
  set Element type = triangles
end
subsection Mechanics
  set Idealisation = 3D
end
subsection Materials
{MATERIAL % 1}{MATERIAL % 2}end
subsection Discrete bodies
  subsection Body 1
    set Material ids = 1
    set Initial velocity z = -10
  end
  subsection Body 2
    set Material ids = 2
    set Motion = fixed
  end
end
subsection Discrete mechanics
  set Friction coefficient = 0.5
  set Damping ratio = 0
end
subsection Time stepping
  set End time = 2e-5
end
subsection Output
  set Write vtu = false
end
""")


def run(contact):
    folder = os.path.join(work, f"contact_{contact}")
    cmd = [binary, prm, "--set", f"Output/Directory={folder}",
           "--set", "Output/Progress interval=0",
           "--set", "Discrete mechanics/Threads=1",
           "--set", f"Discrete mechanics/Contact={'true' if contact else 'false'}"]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"tmfdem failed ({result.returncode}):\n{result.stderr[-2000:]}")
    with open(os.path.join(folder, "summary.json")) as f:
        return json.load(f)


on, off = run(True), run(False)
share = 1.0 - off["wall_time_s"] / on["wall_time_s"]
print(f"{'contact':>8} {'tetrahedra':>10} {'steps':>6} {'pairs':>7} {'loop [s]':>9} "
      f"{'elem-steps/s':>13} {'contact share':>14}")
for s, contact in ((on, True), (off, False)):
    print(f"{str(contact):>8} {s['elements']:>10} {s['steps']:>6} "
          f"{s.get('contact_pairs', 0):>7} {s['wall_time_s']:>9.3f} "
          f"{s['element_steps_per_second']:>13.4g} "
          f"{(f'{100 * share:.1f} %' if contact else ''):>14}", flush=True)
