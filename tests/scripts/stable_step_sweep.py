"""The stable step holds with damping, joints and contact: a jointed square
and a jointed disc, free and stretched, run 3000 explicit steps at every
damping ratio 0 ... 2 and safety factor 0.5 ... 0.9 with contact off and
on. No run may trip a guard (runaway kinetic energy, deformed-mesh
stability, non-finite state), and the kinetic energy at the end may not
exceed the energy put in (the initial kinetic energy)."""
import os
import subprocess
import sys

from common import check, summary

binary, prm, out = sys.argv[1], sys.argv[2], sys.argv[3]
meshes = {
    "square": [],
    "disc": ["Mesh/Source=disc", "Mesh/Center=0.05, 0.05",
             "Mesh/Outer radius=0.05", "Mesh/Element size=0.012",
             "Discrete mechanics/Joint normal penalty factor=100",
             "Discrete mechanics/Joint tangential penalty factor=30"],
}
ok = True
for mesh, extra in meshes.items():
    for contact in ["false", "true"]:
        for zeta in ["0", "0.25", "0.5", "1", "2"]:
            for safety in ["0.5", "0.9"]:
                d = os.path.join(out, f"{mesh}_c{contact}_z{zeta}_s{safety}")
                cmd = [binary, prm, "--set", f"Output/Directory={d}",
                       "--set", "Output/Progress interval=0",
                       "--set", f"Discrete mechanics/Contact={contact}",
                       "--set", f"Discrete mechanics/Damping ratio={zeta}",
                       "--set", f"Discrete mechanics/Safety factor={safety}"]
                for s in extra:
                    cmd += ["--set", s]
                r = subprocess.run(cmd, capture_output=True, text=True)
                name = f"{mesh} contact={contact} zeta={zeta} safety={safety}"
                if r.returncode != 0:
                    ok = check(False, f"{name}: exit {r.returncode}: "
                                      f"{r.stderr.strip()[-400:]}") and ok
                    continue
                s = summary(d)
                e = s["energy"]
                total = e["kinetic"] + e["strain"] + e["joint_stored"]
                ok = check(s["steps"] == 3000 and
                           total <= 1.1 * e["initial_kinetic"],
                           f"{name}: {s['steps']} steps of "
                           f"{s['time_step']:.4g} s, kinetic + strain + joint "
                           f"{total:.4g} <= 1.1 x initial kinetic "
                           f"{e['initial_kinetic']:.4g} J/m") and ok
sys.exit(0 if ok else 1)
