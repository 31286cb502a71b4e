#!/usr/bin/python3
"""Neumann, Robin and volumetric sources against exact steady solutions of
-k T'' = Q on 0 < x < L (P2 elements reproduce the quadratic exactly), and
the heat balance of a transient Robin cooling run."""
import os
import sys
import numpy as np
from common import run, summary, check
from analytic import read_csv

binary, out = sys.argv[1:3]
os.makedirs(out, exist_ok=True)
k, L, Q = 2.0, 1.0, 1000.0
T0, h, T_inf, q = 10.0, 50.0, 20.0, 500.0
prm = f"{out}/slab.prm"
with open(prm, "w") as f:
    f.write(f"""set Model = continuum heat
subsection Mesh
  set Source = rectangle
  set Element type = triangles
  set Element size = 0.1
  set Upper right corner = {L}, 0.2
end
subsection Materials
  subsection Material 0
    set Thermal conductivity = {k}
    set Density = 1000
    set Specific heat capacity = 1
    set Volumetric heat source = {Q}
  end
end
subsection Thermal boundary conditions
  subsection Condition 1
    set Boundary ids = 0
    set Type = dirichlet
    set Temperature = {T0}
  end
  subsection Condition 2
    set Boundary ids = 1
    set Type = robin
    set Heat transfer coefficient = {h}
    set Ambient temperature = {T_inf}
  end
end
subsection Heat solver
  set Polynomial degree = 2
  set Relative tolerance = 1e-12
end
subsection Time stepping
  set Mode = steady
end
subsection Monitors
  set Lines = axis: 0, 0.1, {L}, 0.1, 21
end
""")
ok = True
# Dirichlet left, Robin right, uniform source
run(binary, prm, f"{out}/robin")
x, y, fld = read_csv(f"{out}/robin/lines.csv")["axis"][0.0]
a = (h * (T_inf - T0) + h * Q * L**2 / (2 * k) + Q * L) / (k + h * L)
exact = T0 + a * x - Q * x**2 / (2 * k)
err = abs(fld["T"] - exact).max()
ok &= check(err < 1e-6, f"Dirichlet + Robin + source: max error {err:.2e} C < 1e-6 C")
s = summary(f"{out}/robin")["heat"]
ok &= check(abs(s["source_heat"] - Q * L * 0.2) < 1e-8 * Q, f"source heat {s['source_heat']:.6f} W/m = Q A")
ok &= check(s["relative_imbalance"] < 1e-8, f"steady balance, relative imbalance {s['relative_imbalance']:.1e}")

# Neumann left (inward flux q), Dirichlet right, no source
run(binary, prm, f"{out}/neumann", "Materials/Material 0/Volumetric heat source=0",
    "Thermal boundary conditions/Condition 1/Boundary ids=1",
    "Thermal boundary conditions/Condition 2/Boundary ids=0",
    "Thermal boundary conditions/Condition 2/Type=neumann",
    f"Thermal boundary conditions/Condition 2/Heat flux={q}")
x, y, fld = read_csv(f"{out}/neumann/lines.csv")["axis"][0.0]
exact = T0 + q / k * (L - x)
err = abs(fld["T"] - exact).max()
ok &= check(err < 1e-6, f"Neumann + Dirichlet: max error {err:.2e} C < 1e-6 C")

# transient: a plate at 100 C cooled by convection on all sides, with a
# time-dependent h; heat out through Robin = heat lost from storage
run(binary, prm, f"{out}/cooling", "Time stepping/Mode=transient", "Time stepping/End time=5",
    "Time stepping/Time step=0.05", "Initial conditions/Temperature=100",
    "Thermal boundary conditions/Condition 1/Boundary ids=",
    "Thermal boundary conditions/Condition 2/Boundary ids=0, 1, 2, 3",
    "Thermal boundary conditions/Condition 2/Heat transfer coefficient=50*(1+t)",
    "Materials/Material 0/Volumetric heat source=200*sin(t)")
s = summary(f"{out}/cooling")["heat"]
ok &= check(s["stored_heat"] < 0 and s["relative_imbalance"] < 1e-8,
            f"transient Robin balance: stored {s['stored_heat']:.2f} J/m, in {s['total_heat_in']:.2f} J/m, "
            f"relative imbalance {s['relative_imbalance']:.1e}")

# transient, Crank-Nicolson with its Rannacher start, every kind of term
# depending on t: Dirichlet 10 + t, Robin ambient 20 + 10 t, Neumann flux
# 500 t [W/m^2] on the top edge (length L). The Neumann heat is the exact
# time integral of the prescribed flux, 500 * 5^2 / 2 * L = 6250 J/m (the
# theta rule integrates a linear flux exactly; the 4 backward Euler half
# steps at the start add 500 L (dt/2)^2 / 2 per step, 1e-4 of it); the
# balance closes to the solver tolerance
B = "Thermal boundary conditions/Condition "
run(binary, prm, f"{out}/time_dependent", "Time stepping/Mode=transient",
    "Time stepping/End time=5", "Time stepping/Time step=0.05",
    "Time stepping/Method=Crank-Nicolson", "Initial conditions/Temperature=10",
    "Materials/Material 0/Volumetric heat source=0",
    B + "1/Temperature=10+t", B + "2/Ambient temperature=20+10*t",
    B + "3/Boundary ids=3", B + "3/Type=neumann", B + "3/Heat flux=500*t")
s = summary(f"{out}/time_dependent")["heat"]
neumann = s["boundary_heat_in"]["3"]
exact = 500 * 5 ** 2 / 2 * L
ok &= check(abs(neumann - exact) < 1e-3 * exact,
            f"time-dependent Neumann heat {neumann:.4f} J/m, exact {exact:.4f} J/m (< 1e-3 relative)")
ok &= check(s["relative_imbalance"] < 1e-8,
            f"time-dependent Dirichlet/Robin/Neumann balance: relative imbalance {s['relative_imbalance']:.1e}")
sys.exit(0 if ok else 1)
