#!/usr/bin/env python3
"""The implicit discrete heat's capacity matrix (Discrete heat/Capacity
matrix) on a quench: the 13 mm alumina disc of paper 5.6 at 400 C, its rim
cooled by water at 15 C (Robin, h = 3e4 W/(m^2 K)), heat alone, in 2D
(prm/thermal_shock_disc.prm, 0.4 mm triangles at the rim) and in 3D
(prm/thermal_shock_disc_cracking-3d.prm, 0.4 mm tetrahedra at the rim), 100
backward-Euler steps of 50 us to 5 ms: steps far shorter than h^2 / kappa
(0.016 s), as the quasi-static coupling takes near the onset of cracking.

Three variants: Capacity matrix = consistent; lumped; lumped with
Conduction matrix = M-matrix (each element's positive couplings moved onto
its diagonal). Asserted (bounds from the physics, fixed before the runs):
1. the maximum principle, every nodal temperature at every output within
   [15, 400] C to 1e-6 of the drop (a body cooled from a uniform
   temperature never exceeds it nor falls below the water's): lumped with
   the M-matrix in 2D and 3D, and lumped alone in 2D;
2. every variant: the mean temperature (area or volume weighted, the heat
   content) at 5 ms within 0.5 % of the drop of the series'
   (analytic.quenched_disc: the temperature depends on r and t only);
3. every variant: heat balance 1e-6.
Printed: each variant's range of nodal temperatures, and its RMS and
largest nodal difference from the series at 5 ms (what the M-matrix's
added conduction costs).

Measured: 2D meets 1 with both lumped variants (consistent: 4.90 C above
400 C); 3D meets it with the M-matrix only (consistent: 8.50 C above,
lumped alone: 0.445 C above, 0.12 % of the drop): a lumped capacity keeps
the maximum principle only where the conduction matrix has no positive
off-diagonal entry, which tetrahedra with an obtuse dihedral angle
(gmsh's unstructured ones) give it, and the M-matrix removes.

usage: verify_discrete_heat_capacity.py TMFDEM OUT [--dimensions 2,3]
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from common import run, summary, check  # noqa: E402
import analytic  # noqa: E402
import vtu_pieces  # noqa: E402

PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "prm")
T0, T_WATER, END = 400.0, 15.0, 0.005
KW = dict(radius=6.5e-3, conductivity=35., diffusivity=35. / (3980 * 850.), h=3e4,
          t_ambient=T_WATER, t_initial=T0)
CASES = {2: "thermal_shock_disc.prm", 3: "thermal_shock_disc_cracking-3d.prm"}


def mean_temperature(arrays, dim):
    """Measure-weighted mean of the nodal temperatures (each element's mean
    of its nodes, weighted by its area or volume) [C]."""
    x = arrays[("Points", None)].reshape(-1, 3).astype(float)
    T = arrays[("PointData", "T")].astype(float)
    n = dim + 1
    corners = x.reshape(-1, n, 3)
    if dim == 2:
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        measure = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    else:
        measure = np.abs(np.einsum("ij,ij->i", np.cross(corners[:, 1] - corners[:, 0],
                                                        corners[:, 2] - corners[:, 0]),
                                   corners[:, 3] - corners[:, 0])) / 6
    return np.sum(measure * T.reshape(-1, n).mean(axis=1)) / measure.sum()


def main():
    binary, out = sys.argv[1], sys.argv[2]
    dimensions = [2, 3]
    if "--dimensions" in sys.argv:
        dimensions = [int(d) for d in sys.argv[sys.argv.index("--dimensions") + 1].split(",")]
    ok = True
    drop = T0 - T_WATER
    _, series_mean = analytic.quenched_disc([0.0], END, n_terms=200, **KW)
    for dim in dimensions:
        prm = CASES[dim]
        for capacity, conduction in (("consistent", "consistent"), ("lumped", "consistent"),
                                     ("lumped", "M-matrix")):
            folder = os.path.join(out, f"{dim}d-{capacity}-{conduction}")
            run(binary, os.path.join(PRM, prm), folder, "Model=discrete heat",
                f"Initial conditions/Temperature={T0:g}", "Time stepping/Time step=5e-5",
                f"Time stepping/End time={END:g}", "Output/Times=0.001, 0.002, 0.005",
                f"Discrete heat/Capacity matrix={capacity}",
                f"Discrete heat/Conduction matrix={conduction}")
            series = vtu_pieces.read_series(folder)
            highest = max(a[("PointData", "T")].max() for _, a in series)
            lowest = min(a[("PointData", "T")].min() for _, a in series)
            label = f"{dim}D, {capacity} capacity, {conduction} conduction"
            bounded = highest <= T0 + 1e-6 * drop and lowest >= T_WATER - 1e-6 * drop
            text = (f"{label}: every nodal temperature in [{lowest:.6f}, {highest:.6f}] C "
                    f"(within [15, 400] C to 1e-6 of the drop: {bounded}; "
                    f"{max(highest - T0, 0.):.3f} C above 400 C)")
            if capacity == "lumped" and (conduction == "M-matrix" or dim == 2):
                ok &= check(bounded, text)
            else:
                print(text, flush=True)
            last = series[-1][1]
            x = last[("Points", None)].reshape(-1, 3).astype(float)
            radius = np.hypot(x[:, 0], x[:, 1])
            exact, _ = analytic.quenched_disc(list(radius), END, n_terms=200, **KW)
            difference = last[("PointData", "T")].astype(float) - np.asarray(exact)
            print(f"{label}: nodal difference from the series at {END * 1e3:g} ms: RMS "
                  f"{np.sqrt(np.mean(difference**2)):.4f} C, largest "
                  f"{np.abs(difference).max():.4f} C", flush=True)
            mean = mean_temperature(last, dim)
            ok &= check(abs(mean - series_mean) <= 0.005 * drop,
                        f"{label}: mean temperature at {END * 1e3:g} ms {mean:.4f} C against "
                        f"the series' {series_mean:.4f} C ({(mean - series_mean) / drop * 100:+.3f} % "
                        "of the drop; 0.5 %)")
            imbalance = summary(folder)["heat_balance"]["relative_imbalance"]
            ok &= check(imbalance < 1e-6, f"{label}: heat balance {imbalance:.2g} (< 1e-6)")
    if not ok:
        sys.exit(1)
    print("all checks of the capacity matrices passed")


if __name__ == "__main__":
    main()
