"""Reading the block heap's meshes (gmsh 2.2 ASCII, as tmfdem's generator
and Output/Write final mesh write them), in 2D and 3D, for the rock heap
verification scripts."""
import subprocess
import sys


def read_msh(path, dim):
    """Nodes (id -> dim coordinates), cells [(material, nodes...)]
    (triangles in 2D, tetrahedra in 3D) and boundary sides [(id, nodes...)]
    (lines in 2D, triangles in 3D)."""
    with open(path) as f:
        lines = f.read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    nodes = {}
    for line in lines[i + 2:i + 2 + n]:
        v = line.split()
        nodes[int(v[0])] = tuple(float(a) for a in v[1:1 + dim])
    # gmsh element types: line 1, triangle 2, tetrahedron 4
    cell_type, side_type = (2, 1) if dim == 2 else (4, 2)
    i = lines.index("$Elements")
    n = int(lines[i + 1])
    cells, sides = [], []
    for line in lines[i + 2:i + 2 + n]:
        v = [int(a) for a in line.split()]
        n_tags = v[2]
        if v[1] == cell_type:
            cells.append((v[3], *v[3 + n_tags:3 + n_tags + dim + 1]))
        elif v[1] == side_type:
            sides.append((v[3], *v[3 + n_tags:3 + n_tags + dim]))
    return nodes, cells, sides


def bodies(cells, material):
    """The connected sets of cells of one material (sharing a node), each as
    the set of its nodes."""
    parent = {}

    def find(a):
        while parent.setdefault(a, a) != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a
    for c in cells:
        if c[0] == material:
            for k in c[2:]:
                parent[find(c[1])] = find(k)
    sets = {}
    for c in cells:
        if c[0] == material:
            sets.setdefault(find(c[1]), set()).update(c[1:])
    return list(sets.values())


def generate(binary, prm, folder, *settings):
    """The mesh.msh that `tmfdem --validate prm` generates into folder."""
    cmd = [binary, "--validate", prm, "--set", f"Output/Directory={folder}"]
    for s in settings:
        cmd += ["--set", s]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)}: {result.stderr}")
    with open(f"{folder}/mesh.msh") as f:
        return f.read()
