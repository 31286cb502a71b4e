#!/usr/bin/python3
"""The explicit loop's vector batches (Discrete mechanics/Vector
instructions) give bitwise the results of the one-at-a-time loop.

Each case runs with `none` (triangles and joints one at a time) and with
every instruction set this processor has (SSE2, AVX2, AVX-512); history.csv
must be byte for byte the same, and so must the complete state in full
precision: the last checkpoint (positions, velocities, stresses, damage,
energy terms, contact history, heat) past its header (which holds the
parameters' digest, different since Vector instructions differs) apart from
one 8-byte value, the wall-clock time it records, and the counts of work
done in vector batches that end it. summary.json must name the
set that ran, and
the batches must have done part of the work (vectorised_element_share and
vectorised_joint_share above zero; zero with none), so that the comparison
tests the vector kernels and not the fallback. The cases cover what the
kernels meet: fracture with contact and compression (Brazilian disc, two
blocks colliding), boundary conditions (plate traction), and thermal stretch
with the diagnostics of the heat runs (thermal shock disc, joints breaking).
Last, `auto` must pick the widest set here, and AVX2 instead of AVX-512 for
the plate refined to 123 904 triangles (above 65 536 per process).

usage: verify_vector_instructions.py path/to/tmfdem OUTPUT_DIR"""
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import check, run, summary  # noqa: E402

binary, out = sys.argv[1], sys.argv[2]
prm_dir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "prm")
cases = {
    "brazilian_disc": ["Discrete mechanics/Maximum steps=6000",
                       "Checkpoint/Interval (steps)=6000"],
    "two_blocks_collision": ["Discrete mechanics/Maximum steps=6000",
                             "Checkpoint/Interval (steps)=6000"],
    "plate_traction": ["Discrete mechanics/Maximum steps=3000",
                       "Checkpoint/Interval (steps)=3000"],
    # 500 C on a 0.8 mm mesh (508 triangles): joints damaged from 11.4 ms
    # on, 5 broken at 13.7 ms (step 63 600, one fracture event), 74 600 steps
    # to 16 ms; the checkpoint at step 70 000 holds the state after the
    # breaks
    "thermal_shock_disc": ["Initial conditions/Temperature=500",
                           "Mesh/Element size=0.8e-3",
                           "Time stepping/End time=0.016",
                           "Output/Write vtu=false",
                           "Checkpoint/Interval (steps)=70000"],
}


def checkpoint_state(folder):
    """The newest checkpoint's bytes past its header: magic (8), version,
    size and checksum (8 each), the kind and the parameters' digest (each a
    length of 8 bytes and the text)."""
    directory = os.path.join(folder, "checkpoints")
    newest = sorted(f for f in os.listdir(directory) if f.endswith(".tmfchk"))[-1]
    with open(os.path.join(directory, newest), "rb") as f:
        data = f.read()
    position = 32
    for _ in range(2):
        length = int.from_bytes(data[position:position + 8], "little")
        position += 8 + length
    return newest, data[position:]


def same_state(a, b):
    """Same length, and the differing bytes (if any) within one span of 8:
    the wall-clock time recorded in the checkpoint. Its last four doubles
    are the work counters (triangle-steps, of them in vector batches,
    joint-steps, of them in batches): the step counts must agree, the
    batched ones differ by design."""
    if len(a) != len(b):
        return False, f"{len(a)} against {len(b)} bytes"
    counters_a = struct.unpack("<4d", a[-32:])
    counters_b = struct.unpack("<4d", b[-32:])
    if (counters_a[0], counters_a[2]) != (counters_b[0], counters_b[2]):
        return False, (f"triangle-steps {counters_a[0]:.0f} against {counters_b[0]:.0f}, "
                       f"joint-steps {counters_a[2]:.0f} against {counters_b[2]:.0f}")
    a, b = a[:-32], b[:-32]
    differ = [i for i in range(len(a)) if a[i] != b[i]] if a != b else []
    if not differ:
        return True, "identical"
    return differ[-1] - differ[0] < 8, (f"{len(differ)} bytes differ in "
                                        f"[{differ[0]}, {differ[-1]}] of {len(a)}")
sets = ["SSE2", "AVX2", "AVX-512"]
have = set()  # the sets this processor ran
ok = True
for case, settings in cases.items():
    prm = os.path.join(prm_dir, case + ".prm")
    folder = os.path.join(out, case + "_none")
    run(binary, prm, folder, "Discrete mechanics/Vector instructions=none",
        *settings)
    s = summary(folder)
    ok &= check(s["vector_instructions"] == "none"
                and s["vectorised_element_share"] == 0.
                and s["vectorised_joint_share"] == 0.,
                f"{case}: none runs one at a time")
    with open(os.path.join(folder, "history.csv"), "rb") as f:
        reference = f.read()
    checkpoint, reference_state = checkpoint_state(folder)
    ran = 0
    for name in sets:
        folder_v = os.path.join(out, f"{case}_{name}")
        stdout = run(binary, prm, folder_v,
                     f"Discrete mechanics/Vector instructions={name}",
                     *settings, check=False)
        if not os.path.exists(os.path.join(folder_v, "summary.json")):
            # a set this processor lacks is refused with a clear message
            print(f"{case}: {name} not on this processor", flush=True)
            continue
        ran += 1
        v = summary(folder_v)
        with open(os.path.join(folder_v, "history.csv"), "rb") as f:
            same = f.read() == reference
        ok &= check(v["vector_instructions"] == name,
                    f"{case}: {name} ran ({v['vector_instructions']})")
        ok &= check(v["vectorised_element_share"] > 0.
                    and v["vectorised_joint_share"] > 0.,
                    f"{case} {name}: share of triangle-steps in batches "
                    f"{v['vectorised_element_share']:.3f}, of joint-steps "
                    f"{v['vectorised_joint_share']:.3f} (> 0)")
        ok &= check(same, f"{case} {name}: history.csv bitwise that of none "
                          f"({v['broken_joints']} broken joints, "
                          f"{v['steps']} steps)")
        newest, state = checkpoint_state(folder_v)
        equal, how = same_state(reference_state, state)
        ok &= check(newest == checkpoint and equal,
                    f"{case} {name}: state of {newest} bitwise that of none "
                    f"apart from the wall time ({how})")
    ok &= check(ran >= 1, f"{case}: at least SSE2 ran ({ran} sets)")
    have.update(v_name for v_name in sets
                if os.path.exists(os.path.join(out, f"{case}_{v_name}", "summary.json")))

# auto: the widest set this processor has, but AVX2 instead of AVX-512
# above 65 536 triangles per process (vector_instructions.h)
widest = next((name for name in reversed(sets) if name in have), "none")
prm = os.path.join(prm_dir, "plate_traction.prm")
for refinements, expected in ((0, widest),
                              (4, "AVX2" if widest == "AVX-512" else widest)):
    folder = os.path.join(out, f"auto_{refinements}")
    run(binary, prm, folder, f"Mesh/Global refinements={refinements}",
        "Discrete mechanics/Maximum steps=1", "Output/Write vtu=false")
    a = summary(folder)
    ok &= check(a["vector_instructions"] == expected,
                f"auto with {a['elements']} triangles runs {a['vector_instructions']} "
                f"({expected} expected; widest here {widest})")
sys.exit(0 if ok else 1)
