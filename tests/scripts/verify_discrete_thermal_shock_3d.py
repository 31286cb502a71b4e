#!/usr/bin/env python3
"""The quenched disc of paper 5.6 as it was tested, in 3D.

prm/thermal_shock_disc-3d.prm: the 13 mm x 1 mm alumina disc of
tetrahedra (0.25 mm at the rim, 0.8 mm inside), faces insulated, the rim
quenched (Robin, h = 3e4 W/(m^2 K)) from T0 = 400 C, quasi-static coupling.
The temperature depends on r and t only (the 2D series,
analytic.quenched_disc). Two closed forms bound the rim hoop stress:

  plane stress (a thin disc):             sigma_t = E alpha (T_m - T(R))
  generalised plane strain (a long        sigma_t = E alpha (T_m - T(R))
  cylinder, free ends):                             / (1 - nu)

(and inside the rim the same with the 1/r^2 integral: analytic.
quenched_disc_hoop_stress with E or E / (1 - nu)). The disc is thin against
its radius but not against the thermal layer of the quench (sqrt(kappa t)
= 0.2 mm at 4 ms against 1 mm): the cooled rim layer is held along z by the
warmer material beside it (sigma_z > 0), and its hoop stress lies between
the plane-stress value and the long cylinder's 1 / (1 - nu) = 1.28 times
it, nearer the latter the thinner the layer.

Asserted (the bounds are the two closed forms):
1. Before cracking (outputs with no damaged joint): the mean hoop stress of
   the rim tetrahedra (a face on the mantle) of the middle half of the
   thickness, each over the plane-stress value averaged over it (what a
   constant-stress tetrahedron can carry of a field that varies steeply
   across it), between 1 and 1 / (1 - nu), with 3 % for the discretisation
   (the 3D stress target); and that excess shrinks as the thermal layer
   deepens (the last output before cracking below the first).
2. The first damage inside the window the two closed forms set: not before
   the generalised-plane-strain hoop stress, averaged over a rim
   tetrahedron, reaches f_t in any of them, not after the plane-stress one
   does in those of the middle half of the thickness.
3. The first damaged tetrahedra lie at the rim (centroids within two rim
   element sizes); heat balance 1e-6; no relaxation at the cap.
Printed: where along z the first damage lies, and the 2D plane-stress
case's first damage (prm/thermal_shock_disc.prm at 400 C) beside it.

usage: verify_discrete_thermal_shock_3d.py TMFDEM OUT [--rim-size H]
           [--end-time T] [--with-2d] [--reuse]
  --rim-size H: tetrahedra of H [m] at the rim (the .geo's h_rim; 0.25e-3)
  --end-time T: run the 3D disc to T [s] (the prm's 12 ms)
  --with-2d: also run the 2D case (its first damage printed beside)
  --reuse: check the runs already in OUT
"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from common import run, summary, check  # noqa: E402
import analytic  # noqa: E402
import vtu_pieces  # noqa: E402
from plot_vtu import mesh_vertices  # noqa: E402

PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "prm")
R, H, H_RIM = 6.5e-3, 1e-3, 0.25e-3
E, NU, ALPHA, F_T = 370e9, 0.22, 7.5e-6, 180e6
T0 = 400.0
KW = dict(radius=R, conductivity=35., diffusivity=35. / (3980 * 850.), h=3e4,
          t_ambient=15., t_initial=T0)
# the 2D case over the 3D prm's time span and outputs
END_TIME = 0.012
OUTPUT_TIMES = "0.001, 0.002, 0.003, 0.004, 0.005, 0.006, 0.007, 0.008, 0.01, 0.012"


outputs = vtu_pieces.read_series  # [(time, {(section, name): values})]


def history(folder):
    with open(os.path.join(folder, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def tetrahedra(arrays):
    """Per tetrahedron: reference vertices and centroid [m], hoop and axial
    stress [Pa], number of its nodes on the mantle, joint damage."""
    u = arrays[("PointData", "displacement")].reshape(-1, 3)
    X = (arrays[("Points", None)].reshape(-1, 3) - u).reshape(-1, 4, 3).astype(float)
    centroid = X.mean(axis=1)
    r = np.hypot(centroid[:, 0], centroid[:, 1])
    c, s = centroid[:, 0] / r, centroid[:, 1] / r
    sxx, syy, sxy = (arrays[("CellData", k)] for k in ("sxx", "syy", "sxy"))
    hoop = sxx * s * s - 2 * sxy * s * c + syy * c * c
    on_mantle = (np.abs(np.hypot(X[:, :, 0], X[:, :, 1]) - R) < 1e-6).sum(axis=1)
    return dict(vertices=X, r=r, z=centroid[:, 2], hoop=hoop,
                szz=arrays[("CellData", "szz")], on_mantle=on_mantle,
                damage=arrays[("CellData", "joint_damage")])


# the faces of a tetrahedron, each opposite one corner, outward for a
# positively oriented tetrahedron
_FACES = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]])


def cracks(solution, crack_file):
    """The broken faces of one output and the cracks they form.

    Each triangle of cracks.pvd (its corners the midpoints of the two faces'
    nodes) is matched to the pair of tetrahedron faces it lies between; the
    normal opening at each corner is (x_b - x_a) . n_a, n_a the outward unit
    normal of side a in the current configuration (> 0: the faces apart).
    Broken faces that share an edge belong to one crack. Returns
    (per-face minimum opening [m], list of cracks: dict(faces, r_min, r_max,
    z_min, z_max [m], theta [rad], radial = the area-weighted mean of
    |n . e_theta|, 1 for a plane through the axis))."""
    from scipy.spatial import cKDTree
    x = solution[("Points", None)].reshape(-1, 3).astype(float)
    reference = x - solution[("PointData", "displacement")].reshape(-1, 3)
    # copies within 1e-9 m: the vtu's single-precision points
    vertex = mesh_vertices(reference, 1e-9)
    n_tets = len(x) // 4
    corners = (4 * np.arange(n_tets)[:, None, None] + _FACES[None]).reshape(-1, 3)
    key = np.sort(vertex[corners], axis=1)
    order = np.lexsort(key.T[::-1])
    same = np.all(key[order[1:]] == key[order[:-1]], axis=1)
    a, b = order[:-1][same], order[1:][same]  # the two sides of each interior face
    midpoint = 0.5 * (x[corners[a]].mean(axis=1) + x[corners[b]].mean(axis=1))
    crack_points = crack_file[("Points", None)].reshape(-1, 3).astype(float)
    conn = crack_file[("Cells", "connectivity")].astype(np.int64)
    types = crack_file[("Cells", "types")].astype(np.int64)
    triangles = conn[:3 * int((types == 5).sum())].reshape(-1, 3) if np.all(types[types != 2] == 5) else None
    assert triangles is not None, "cracks.pvd holds cells other than triangles"
    if len(triangles) == 0:
        return np.zeros(0), []
    distance, pair = cKDTree(midpoint).query(crack_points[triangles].mean(axis=1))
    assert distance.max() < 1e-8, f"a crack triangle lies {distance.max():.3g} m from every face pair"
    a, b = a[pair], b[pair]
    xa = x[corners[a]]
    normal = np.cross(xa[:, 1] - xa[:, 0], xa[:, 2] - xa[:, 0])
    area = 0.5 * np.linalg.norm(normal, axis=1)
    normal /= 2 * area[:, None]
    # side b's node at each corner of side a: the same mesh vertex
    vb = vertex[corners[b]]
    match = np.argmax(vb[:, None, :] == vertex[corners[a]][:, :, None], axis=2)
    xb = x[corners[b][np.arange(len(b))[:, None], match]]
    opening = np.einsum("fkd,fd->fk", xb - xa, normal).min(axis=1)
    # cracks: broken faces joined by an edge
    parent = list(range(len(a)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i
    edges = {}
    for f, ids in enumerate(np.sort(vertex[corners[a]], axis=1)):
        for e in ((ids[0], ids[1]), (ids[0], ids[2]), (ids[1], ids[2])):
            if e in edges:
                parent[root(f)] = root(edges[e])
            edges[e] = f
    groups = {}
    for f in range(len(a)):
        groups.setdefault(root(f), []).append(f)
    result = []
    for faces in groups.values():
        points = reference[corners[a[faces]]].reshape(-1, 3)
        r = np.hypot(points[:, 0], points[:, 1])
        centre = points.mean(axis=0)
        theta = np.arctan2(centre[1], centre[0])
        e_theta = np.array([-np.sin(theta), np.cos(theta), 0.0])
        radial = np.sum(area[faces] * np.abs(normal[faces] @ e_theta)) / np.sum(area[faces])
        result.append(dict(faces=len(faces), r_min=r.min(), r_max=r.max(),
                           z_min=points[:, 2].min(), z_max=points[:, 2].max(),
                           theta=theta, radial=radial))
    return opening, sorted(result, key=lambda c: c["theta"])


def plane_stress_hoop(t, n=8001, n_terms=200):
    """The plane-stress hoop stress of the quenched disc at time t as a
    function of r [Pa] (E alpha (T_m / 2 + (1/r^2) int_0^r T r' dr' - T),
    analytic.quenched_disc_hoop_stress on a grid of n radii, interpolated);
    the generalised-plane-strain one is it over (1 - nu)."""
    rr = np.linspace(0.0, R, n)
    T, T_mean = analytic.quenched_disc(rr, t, n_terms=n_terms, **KW)
    integral = np.concatenate(([0.0], np.cumsum(0.5 * (T[1:] * rr[1:] + T[:-1] * rr[:-1])
                                                 * np.diff(rr))))
    inner = np.where(rr > 0, integral / np.maximum(rr, 1e-300) ** 2, 0.5 * T[0])
    sigma = E * ALPHA * (0.5 * T_mean + inner - T)
    return lambda r: np.interp(r, rr, sigma)


# the four-point rule of degree 2 on a tetrahedron (weights 1/4)
_A, _B = 0.5854101966249685, 0.1381966011250105
_RULE = np.full((4, 4), _B) + np.eye(4) * (_A - _B)


def element_mean(profile, vertices):
    """The mean of profile(r) over each tetrahedron (degree-2 rule): the
    value a constant-stress tetrahedron can carry of a field that varies
    across it."""
    points = np.einsum("qk,ekd->eqd", _RULE, vertices)
    return profile(np.hypot(points[..., 0], points[..., 1])).mean(axis=1)


def rim_stress_ratios(arrays, t):
    """(mid-thickness mean, faces mean) of the rim tetrahedra's hoop stress
    over the plane-stress value averaged over each of them, their counts,
    and sigma_z / sigma_t at mid-thickness."""
    tet = tetrahedra(arrays)
    rim = tet["on_mantle"] == 3
    mid = rim & (np.abs(tet["z"]) <= H / 4)
    faces = rim & (np.abs(tet["z"]) >= H / 2 - H_RIM / 2)
    profile = plane_stress_hoop(t)
    ratio = {}
    for name, cells in (("mid", mid), ("faces", faces)):
        ratio[name] = np.mean(tet["hoop"][cells] / element_mean(profile, tet["vertices"][cells]))
    axial = np.mean(tet["szz"][mid]) / np.mean(tet["hoop"][mid])
    return ratio["mid"], ratio["faces"], mid.sum(), faces.sum(), axial


def window(arrays):
    """(t1, t2): the first damage may not come before t1, when the
    generalised-plane-strain hoop stress averaged over a rim tetrahedron
    (a face on the mantle) first reaches f_t in any of them, nor after t2,
    when the plane-stress one does in those of the middle half of the
    thickness (where the stress lies between the two) [s]."""
    from scipy.optimize import brentq
    tet = tetrahedra(arrays)
    rim = tet["on_mantle"] == 3
    mid = rim & (np.abs(tet["z"]) <= H / 4)

    def reach(factor, cells):
        def excess(t):
            return factor * element_mean(plane_stress_hoop(t), tet["vertices"][cells]).max() - F_T
        return brentq(excess, 1e-4, 0.1, xtol=1e-7)
    return reach(1 / (1 - NU), rim), reach(1.0, mid)


def first_damage(folder):
    """(t_prev, t_first): the first damaged joint appeared in this thermal
    step [s]; None if none."""
    hist = history(folder)
    onset = np.nonzero(hist["damaged_joints"] > 0)[0]
    if len(onset) == 0:
        return None
    return (hist["time"][onset[0] - 1] if onset[0] > 0 else 0.0, hist["time"][onset[0]])


def disc_geo(out, rim_size):
    """Writes out/disc-3d.geo: prm/thermal_shock_disc-3d.geo with tetrahedra
    of @p rim_size [m] at the rim; returns its path."""
    os.makedirs(out, exist_ok=True)
    geo = os.path.join(os.path.abspath(out), "disc-3d.geo")
    with open(geo, "w") as f:
        f.write(f"h_rim = {rim_size!r};\n"
                f'Include "{os.path.abspath(os.path.join(PRM, "thermal_shock_disc-3d.geo"))}";\n')
    return geo


def run_case(binary, out, rim_size=None, end_time=None, with_2d=True):
    """The 3D disc (Element size at the rim @p rim_size [m], else the .geo's
    0.25 mm; to @p end_time [s], else the prm's) into out/disc-3d and, with
    @p with_2d, the 2D case at the same T0 over the 3D prm's span into
    out/disc-2d."""
    settings = [f"Initial conditions/Temperature={T0:g}"]
    if rim_size is not None:
        settings.append(f"Mesh/File name={disc_geo(out, rim_size)}")
    if end_time is not None:
        times = [t for t in OUTPUT_TIMES.split(", ") if float(t) < end_time] + [f"{end_time!r}"]
        settings += [f"Time stepping/End time={end_time!r}", "Output/Times=" + ", ".join(times)]
    run(binary, os.path.join(PRM, "thermal_shock_disc-3d.prm"), os.path.join(out, "disc-3d"),
        *settings)
    if with_2d:
        run(binary, os.path.join(PRM, "thermal_shock_disc.prm"), os.path.join(out, "disc-2d"),
            f"Initial conditions/Temperature={T0:g}", f"Time stepping/End time={END_TIME:g}",
            f"Output/Times={OUTPUT_TIMES}")


def main():
    binary, out = sys.argv[1], sys.argv[2]
    options = sys.argv[3:]
    global H_RIM
    rim_size = None
    if "--rim-size" in options:
        rim_size = float(options[options.index("--rim-size") + 1])
        H_RIM = rim_size
    end_time = None
    if "--end-time" in options:
        end_time = float(options[options.index("--end-time") + 1])
    if "--reuse" not in options:
        run_case(binary, out, rim_size, end_time, with_2d="--with-2d" in options)
    folder = os.path.join(out, "disc-3d")
    ok = True
    s = summary(folder)
    series = outputs(folder)
    # 1. the rim hoop stress before cracking
    intact = [(t, a) for t, a in series if t > 0 and not np.any(a[("CellData", "joint_damage")] > 0)]
    ok &= check(len(intact) > 0, f"{len(intact)} outputs before the first damage")
    ratios = []
    for t, arrays in intact:
        mid, faces, n_mid, n_faces, axial = rim_stress_ratios(arrays, t)
        ratios.append(mid)
        ok &= check(1 - 0.03 <= mid <= 1 / (1 - NU) + 0.03,
                    f"t = {t * 1e3:g} ms: rim hoop stress / plane stress at mid-thickness "
                    f"{mid:.4f} ({n_mid} tetrahedra; between 1 and 1 / (1 - nu) = "
                    f"{1 / (1 - NU):.4f}, 3 %); at the faces {faces:.4f} ({n_faces}); "
                    f"sigma_z / sigma_t at mid-thickness {axial:.3f}")
    if len(ratios) > 1:
        ok &= check(ratios[-1] < ratios[0],
                    f"the excess over plane stress shrinks as the thermal layer deepens: "
                    f"{ratios[0]:.4f} at {intact[0][0] * 1e3:g} ms, {ratios[-1]:.4f} at "
                    f"{intact[-1][0] * 1e3:g} ms")
    # 2. the first damage in the window of the two closed forms
    t1, t2 = window(series[0][1])
    onset = first_damage(folder)
    ok &= check(onset is not None, "joints damaged")
    if onset is not None:
        t_prev, t_first = onset
        ok &= check(t_first >= t1 and t_prev <= t2,
                    f"first damage in ({t_prev * 1e3:.3f}, {t_first * 1e3:.3f}] ms; averaged "
                    f"over the rim tetrahedra, the generalised-plane-strain hoop stress "
                    f"reaches f_t at {t1 * 1e3:.3f} ms, the plane-stress one (middle half "
                    f"of the thickness) at {t2 * 1e3:.3f} ms (first damage in between)")
        damaged = [(t, a) for t, a in series if np.any(a[("CellData", "joint_damage")] > 0)]
    if onset is not None and damaged:
        t, arrays = damaged[0]
        tet = tetrahedra(arrays)
        cells = tet["damage"] > 0
        ok &= check(tet["r"][cells].min() > R - 2 * H_RIM,
                    f"t = {t * 1e3:g} ms: {cells.sum()} tetrahedra with damaged joints, "
                    f"centroids at r >= {tet['r'][cells].min() * 1e3:.3f} mm (the rim: > "
                    f"{(R - 2 * H_RIM) * 1e3:.3f} mm); |z| of their centroids: median "
                    f"{np.median(np.abs(tet['z'][cells])) * 1e3:.3f} mm, "
                    f"{np.mean(np.abs(tet['z'][cells]) <= H / 4) * 100:.0f} % in the "
                    "middle half of the thickness")
    ok &= check(s["heat_balance"]["relative_imbalance"] < 1e-6,
                f"heat balance {s['heat_balance']['relative_imbalance']:.2g} (< 1e-6)")
    ok &= check(s["relaxations_at_cap"] == 0,
                f"relaxations at the cap: {s['relaxations_at_cap']} (0)")
    two_d = os.path.join(out, "disc-2d")
    if os.path.exists(os.path.join(two_d, "history.csv")):
        onset_2d = first_damage(two_d)
        if onset_2d is not None:
            print(f"2D plane stress (prm/thermal_shock_disc.prm, 0.4 mm triangles): first "
                  f"damage in ({onset_2d[0] * 1e3:.3f}, {onset_2d[1] * 1e3:.3f}] ms", flush=True)
    if not ok:
        sys.exit(1)
    print("all checks of the 3D quenched disc passed")


if __name__ == "__main__":
    main()
