#!/usr/bin/python3
"""Tutorial lesson 5: the restrained sheet in the discrete layer; what the
joint penalty does and what does (not) converge.

Runs doc/tutorial/prm/lesson-05-jointed-sheet.prm (0.5 m sheet on rollers,
dT = +100 C, plane stress, Table 3 material) at joint penalties p = 10, 100
and 1000 E (h = 0.05 m) and at h = 0.1, 0.05 and 0.025 m (p = 100 E).

Prediction, fixed before any run (lesson text): every triangle carries the
same stress sigma I, every joint the normal traction sigma and closes by
sigma L / p (spring p / L per unit length, L its length). With the edges
held, the area-average strain is zero, and tracing it gives
    0 = 2 ((1 - nu) sigma / E + alpha dT) + (sigma / p) sum_j L_j^2 / A,
so
    sigma / sigma_exact - 1 = -x / (1 + x),   x = c E / ((1 - nu) p),
    c = sum over the joints of L_j^2 / (2 A)   (a pure number of the mesh's
shape: sqrt(3) = 1.732 for equilateral triangles, less where boundary edges,
which are not joints, take a share; independent of the element size).
Checked: the area-weighted mean of (sxx + syy) / 2 over the triangles has
the predicted relative error to within 10 % of that error, in every run."""
import os
import numpy as np
from tutorial import arguments, prm, run, summary, check, pyplot, finish
from plot_vtu import read_vtu

E, nu, alpha, dT = 75.1e9, 0.311, 3e-6, 100.0
exact = -E * alpha * dT / (1 - nu)
args = arguments(__doc__)
ok = True


def vtu_files(folder):
    import xml.etree.ElementTree as ET
    return [os.path.join(folder, d.get("file"))
            for d in ET.parse(os.path.join(folder, "solution.pvd")).getroot().iter("DataSet")]


def mesh_constant(vtu):
    """(c = sum of L^2 over interior edges / (2 A), number of joints, triangles)
    from the reference configuration (the first output, t = 0)."""
    pts, cells, _, _ = read_vtu(vtu, "material_id")
    count, area = {}, 0.0
    for c in cells:
        p = pts[c]
        area += 0.5 * abs(np.cross(p[1] - p[0], p[2] - p[0]))
        for i in range(3):
            a, b = p[i], p[(i + 1) % 3]
            key = tuple(sorted((tuple(np.round(a, 9)), tuple(np.round(b, 9)))))
            count[key] = count.get(key, 0) + 1
    joints = [k for k, n in count.items() if n == 2]
    total = sum((k[0][0] - k[1][0])**2 + (k[0][1] - k[1][1])**2 for k in joints)
    return total / (2 * area), len(joints), len(cells)


def mean_stress(vtu):
    """Area-weighted mean of (sxx + syy) / 2 over the triangles [Pa]."""
    pts, cells, sxx, point = read_vtu(vtu, "sxx")
    _, _, syy, _ = read_vtu(vtu, "syy")
    areas = np.array([0.5 * abs(np.cross(pts[c][1] - pts[c][0], pts[c][2] - pts[c][0])) for c in cells])
    if point:  # per-vertex values of each triangle's own nodes: average them
        sxx = np.array([sxx[c].mean() for c in cells])
        syy = np.array([syy[c].mean() for c in cells])
    return float(np.sum(areas * (sxx + syy) / 2) / areas.sum())


runs = [(0.05, 10), (0.05, 100), (0.05, 1000), (0.1, 100), (0.025, 100)]
results = {}
for h, factor in runs:
    folder = f"{args.out}/h{h}_p{factor}"
    run(args.tmfdem, prm("lesson-05-jointed-sheet.prm"), folder, f"Mesh/Element size={h}",
        f"Discrete mechanics/Joint normal penalty factor={factor}",
        f"Discrete mechanics/Joint tangential penalty factor={factor}",
        "Discrete heat/Relaxation tolerance=1e-12")
    files = vtu_files(folder)
    c, joints, triangles = mesh_constant(files[0])
    x = c / ((1 - nu) * factor)
    predicted = -x / (1 + x)
    measured = mean_stress(files[-1]) / exact - 1
    s = summary(folder)
    step = s.get("time_step", float("nan"))
    results[(h, factor)] = dict(c=c, predicted=predicted, measured=measured, step=step,
                                triangles=triangles, joints=joints, steps=s.get("steps"))
    print(f"  h = {h} m, p = {factor} E: {triangles} triangles, {joints} joints, c = {c:.4f}, "
          f"explicit step {step:.3e} s, {s.get('steps')} relaxation steps")
    ok &= check(abs(measured - predicted) <= 0.1 * abs(predicted),
                f"h = {h} m, p = {factor} E: mean sigma / exact - 1 = {100 * measured:+.4f} % vs "
                f"predicted -x/(1+x) = {100 * predicted:+.4f} % (x = c E/((1 - nu) p), c = {c:.4f}); "
                f"off by {100 * abs(measured / predicted - 1):.1f} % of the prediction (<= 10 %)")
    ok &= check(s.get("broken_joints", 0) == 0, f"h = {h} m, p = {factor} E: no joint broken")

if args.plot:
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.6))
    pf = np.geomspace(5, 2000, 50)
    c05 = results[(0.05, 100)]["c"]
    xx = c05 / ((1 - nu) * pf)
    a1.loglog(pf, 100 * xx / (1 + xx), "k-", label=f"predicted x/(1+x), c = {c05:.3f} (h = 0.05 m)")
    a1.loglog(pf, 100 * np.sqrt(3) / ((1 - nu) * pf), "k:", label=r"$\sqrt{3}/((1-\nu)\,p/E)$ (equilateral, no boundary)")
    for (h, factor), r in results.items():
        if h == 0.05:
            a1.loglog(factor, -100 * r["measured"], "o", color="C0")
    a1.plot([], [], "o", color="C0", label="tmfdem (area mean)")
    a1.set_xlabel("joint penalty p / E")
    a1.set_ylabel(r"$|\sigma/\sigma_{exact} - 1|$ [%]")
    a1.set_title("penalty: the error falls like 1/p")
    a1.legend(fontsize=7)
    hs = sorted(h for h, f in results if f == 100)
    a2.plot(hs, [-100 * results[(h, 100)]["measured"] for h in hs], "o-", color="C0", label="tmfdem (area mean)")
    a2.plot(hs, [-100 * results[(h, 100)]["predicted"] for h in hs], "kx--", label="predicted from the mesh's c")
    a2.set_xscale("log")
    a2.set_ylim(0, 1.3 * max(-100 * results[(h, 100)]["measured"] for h in hs))
    a2.set_xlabel("element size h [m]")
    a2.set_ylabel(r"$|\sigma/\sigma_{exact} - 1|$ [%]")
    a2.set_title("mesh size at p = 100 E: no convergence")
    a2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")
finish(ok)
