#!/usr/bin/env python3
"""Bounded, seeded fuzz test of tmfdem's prm and mesh readers (issue 7,
"Hostile input").

usage: fuzz_inputs.py TMFDEM OUT_DIR [--seed N] [--count N] [--jobs N]
                      [--timeout S] [--only I[,J...]] [--mesh-share F]
                      [--strict-exit2]

Builds COUNT hostile inputs from a seed corpus (prm/*.prm, tests/data/*.prm;
tests/data/*.msh, tests/data/discrete/*.msh, tests/data/fuzz/*.msh) with a
random.Random seeded per input (input I of seed S is always the same file,
whatever COUNT and JOBS are), and runs `tmfdem FILE --validate` on each
(reads the parameters, builds and checks the mesh, solves nothing). Mutated
meshes are fed through a host prm with --set "Mesh/File name=...".

Verdict per input:
  exit 0                        fine (the input happened to be valid)
  exit 1 + stderr "tmfdem: ..." fine (rejected with a clear message; other
                                text before it, e.g. muparser's own report,
                                is printed as a note)
  exit 2 + stderr "tmfdem: ..." tolerated (counted; a failure with
                                --strict-exit2): bad input should be exit 1
  anything else                 FAIL: a signal (segfault, abort), a hang
                                past --timeout, another exit status, an
                                exit 1/2 without a "tmfdem:" message, or a
                                Python-level error in the harness.
Every failing input is kept under OUT_DIR/failures/ with the command that
reproduces it; the script prints a summary and exits 1 if anything failed.
Each run is limited to 4 GiB of address space, so an input that asks for
absurd memory shows up as std::bad_alloc instead of taking the machine down.

Only the Python standard library is needed.
"""
import argparse
import collections
import concurrent.futures
import os
import random
import re
import resource
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MEMORY_LIMIT = 4 << 30

# ----------------------------------------------------------------- corpus


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def absolutise_file_names(text, prm_dir):
    """Rewrites `set File name = X` to an absolute path, so that the mutated
    prm, written elsewhere, still finds its mesh."""
    def fix(m):
        name = m.group(2).strip()
        if name and not os.path.isabs(name):
            name = os.path.normpath(os.path.join(prm_dir, name))
        return m.group(1) + name
    return re.sub(r"(?m)^(\s*set\s+File name\s*=\s*)(.*)$", fix, text)


def prm_corpus():
    paths = sorted(
        [os.path.join(REPO, "prm", f) for f in os.listdir(os.path.join(REPO, "prm")) if f.endswith(".prm")]
        + [os.path.join(REPO, "tests", "data", f)
           for f in os.listdir(os.path.join(REPO, "tests", "data")) if f.endswith(".prm")])
    corpus = []
    for p in paths:
        text = read_bytes(p).decode("utf-8", "replace")
        corpus.append((os.path.relpath(p, REPO),
                       absolutise_file_names(text, os.path.dirname(p)).encode()))
    return corpus


def mesh_corpus():
    """(name, bytes, host prm) triples: each mesh with a prm whose boundary
    and material ids it matches, so that mutations reach past the reader into
    the mesh checks. tests/data/fuzz holds msh4 (gmsh -format msh41) seeds
    and one meshed from prm/block_on_incline.geo."""
    data = os.path.join(REPO, "tests", "data")
    square = os.path.join(data, "square_from_file.prm")
    def host(sub, f):
        if sub == "discrete":
            return os.path.join(REPO, "prm", "joint_pull.prm")
        if f.startswith("block_on_incline"):
            return os.path.join(REPO, "prm", "block_on_incline.prm")
        return square
    corpus = []
    for sub in ("", "discrete", "fuzz"):
        folder = os.path.join(data, sub)
        if not os.path.isdir(folder):
            continue
        for f in sorted(os.listdir(folder)):
            if f.endswith(".msh"):
                p = os.path.join(folder, f)
                corpus.append((os.path.relpath(p, REPO), read_bytes(p), host(sub, f)))
    return corpus


def known_entries(binary):
    """(subsection path, entry) pairs of the default prm, for mutations that
    give a known entry a hostile value."""
    try:
        text = subprocess.run([binary, "--print-parameters"], capture_output=True,
                              text=True, timeout=30).stdout
    except (OSError, subprocess.SubprocessError):
        return []
    entries, path = [], []
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("subsection "):
            path.append(s[len("subsection "):].strip())
        elif s == "end" and path:
            path.pop()
        elif s.startswith("set ") and "=" in s:
            entries.append((tuple(path), s[4:s.index("=")].strip()))
    return entries


# ---------------------------------------------------------------- values

HUGE_NUMBERS = [
    "1e308", "-1e308", "1.8e308", "-1.8e308", "1e-320", "4.9e-324", "nan", "NaN",
    "-nan", "inf", "-inf", "Infinity", "99999999999999999999",
    "-99999999999999999999", "4294967296", "4294967295", "2147483648",
    "-2147483649", "18446744073709551616", "-1", "0", "-0", "1e400", "0x7fffffff",
    "9" * 400, "1" + "0" * 5000, "0." + "0" * 4000 + "1",
]
WRONG_TYPES = [
    "", " ", "abc", "two thousand", "true", "false", "yes", "1,2,3", "1, 2, 3, 4, 5",
    "1e", "e5", "--1", "1..2", "1.2.3", "1 2", "0,", ",", ";", "x", "x*y/0", "1/0",
    "sqrt(-1)", "log(0)", "t^1e9", "sin(", ")", "((((((((((((((((((((x", "if(x,1)",
    "rectangle", "file", "triangles", "discrete mechanics", "continuum heat",
    "quadrilaterals", "steady", "Munjiza", "\\", "\"", "'", "$", "#", "=", "=1",
    "end", "subsection", "set", "include", "\t", "\u00e9\u00e8", "\u03be", "\U0001f600",
]


def hostile_value(rng):
    r = rng.random()
    if r < 0.45:
        return rng.choice(HUGE_NUMBERS)
    if r < 0.85:
        return rng.choice(WRONG_TYPES)
    if r < 0.92:
        return ", ".join(rng.choice(HUGE_NUMBERS + ["1", "0"]) for _ in range(rng.randint(1, 6)))
    return "x" * rng.choice([1000, 70000, 300000])


def random_bytes(rng, n):
    return bytes(rng.randrange(256) for _ in range(n))


def non_utf8(rng):
    return rng.choice([b"\xff\xfe", b"\xc3\x28", b"\xa0\xa1", b"\xe2\x28\xa1",
                       b"\xf0\x28\x8c\x28", b"\xc0\xaf", b"\xed\xa0\x80", b"\x00",
                       b"\x80", b"\xfe\xff\x00\x00", random_bytes(rng, 8)])


# ------------------------------------------------------- generic mutators


def m_flip(rng, data, ctx):
    if not data:
        return data, "flip(empty)"
    b = bytearray(data)
    n = rng.randint(1, 8)
    for _ in range(n):
        i = rng.randrange(len(b))
        b[i] = b[i] ^ (1 << rng.randrange(8)) if rng.random() < 0.5 else rng.randrange(256)
    return bytes(b), f"flip {n} bytes"


def m_insert_bytes(rng, data, ctx):
    i = rng.randint(0, len(data))
    chunk = random_bytes(rng, rng.randint(1, 64)) if rng.random() < 0.5 else non_utf8(rng)
    return data[:i] + chunk + data[i:], f"insert {len(chunk)} bytes at {i}"


def m_delete(rng, data, ctx):
    if not data:
        return data, "delete(empty)"
    i = rng.randrange(len(data))
    n = rng.randint(1, max(1, min(200, len(data) - i)))
    return data[:i] + data[i + n:], f"delete {n} bytes at {i}"


def m_truncate(rng, data, ctx):
    i = rng.randint(0, len(data))
    return data[:i], f"truncate at {i}/{len(data)}"


def m_garbage_line(rng, data, ctx):
    lines = data.split(b"\n")
    i = rng.randint(0, len(lines))
    r = rng.random()
    if r < 0.4:
        g = random_bytes(rng, rng.randint(1, 120))
    elif r < 0.7:
        g = "".join(chr(rng.randint(32, 126)) for _ in range(rng.randint(1, 120))).encode()
    else:
        g = non_utf8(rng) * rng.randint(1, 20)
    lines.insert(i, g)
    return b"\n".join(lines), f"garbage line at {i}"


def m_long_line(rng, data, ctx):
    lines = data.split(b"\n")
    i = rng.randint(0, len(lines))
    n = rng.choice([5000, 100000, 1000000])
    ch = rng.choice([b"x", b"9", b" ", b"#", b"\xff"])
    lines.insert(i, ch * n)
    return b"\n".join(lines), f"line of {n} x {ch!r} at {i}"


def m_non_utf8(rng, data, ctx):
    i = rng.randint(0, len(data))
    return data[:i] + non_utf8(rng) + data[i:], f"non-UTF8 at {i}"


def m_empty(rng, data, ctx):
    return rng.choice([b"", b"\n", b"   \n\n", b"\x00", b"\r\n\r\n"]), "empty file"


def m_line_ops(rng, data, ctx):
    lines = data.split(b"\n")
    if len(lines) < 2:
        return data, "line ops(short)"
    op = rng.choice(["dup", "swap", "drop", "shuffle", "crlf", "reverse"])
    if op == "dup":
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
    elif op == "swap":
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif op == "drop":
        del lines[rng.randrange(len(lines))]
    elif op == "shuffle":
        i = rng.randrange(len(lines))
        j = min(len(lines), i + rng.randint(2, 10))
        part = lines[i:j]
        rng.shuffle(part)
        lines[i:j] = part
    elif op == "crlf":
        return data.replace(b"\n", b"\r\n"), "CRLF line ends"
    else:
        lines.reverse()
    return b"\n".join(lines), f"lines: {op}"


def m_splice(rng, data, ctx):
    other = rng.choice(ctx["same_kind"])
    i, j = rng.randint(0, len(data)), rng.randint(0, len(other))
    return data[:i] + other[j:], f"splice at {i} with another seed from {j}"


GENERIC = [m_flip, m_insert_bytes, m_delete, m_truncate, m_garbage_line,
           m_long_line, m_non_utf8, m_line_ops, m_splice]

# ----------------------------------------------------------- prm mutators

SET_LINE = re.compile(rb"(?m)^(\s*set\s+[^=\n]*=)([^\n]*)$")


def m_prm_value(rng, data, ctx):
    """A hostile value for an existing entry: huge numbers, nan/inf, words
    where numbers go, numbers where selections go, long or empty values."""
    matches = list(SET_LINE.finditer(data))
    if not matches:
        return data, "value(no set line)"
    m = rng.choice(matches)
    v = hostile_value(rng).encode()
    return data[:m.start(2)] + b" " + v + data[m.end(2):], \
        f"value of '{m.group(1).strip().decode(errors='replace')}' -> {v[:40]!r}"


def m_prm_number_in_selection(rng, data, ctx):
    matches = [m for m in SET_LINE.finditer(data)
               if re.search(rb"[A-Za-z]", m.group(2)) and not re.search(rb"[0-9]", m.group(2))]
    if not matches:
        return m_prm_value(rng, data, ctx)
    m = rng.choice(matches)
    v = rng.choice(HUGE_NUMBERS[:20]).encode()
    return data[:m.start(2)] + b" " + v + data[m.end(2):], \
        f"number in selection '{m.group(1).strip().decode(errors='replace')}' -> {v!r}"


def m_prm_inject(rng, data, ctx):
    """Reopens a known subsection at the end and sets one of its entries to
    a hostile value (reaches entries the seed does not mention)."""
    if not ctx["entries"]:
        return m_prm_value(rng, data, ctx)
    path, entry = rng.choice(ctx["entries"])
    v = hostile_value(rng) if rng.random() < 0.8 else rng.choice(["0", "1", "12", "1e-9", "1e9"])
    block = "".join(f"subsection {p}\n" for p in path) + f"set {entry} = {v}\n" + "end\n" * len(path)
    return data + b"\n" + block.encode(), f"inject {'/'.join(path + (entry,))} = {v[:40]!r}"


def m_prm_structure(rng, data, ctx):
    """Broken structure: duplicated or unterminated subsections, stray or
    missing `end`, unknown subsections and entries, bare keywords."""
    lines = data.split(b"\n")
    subs = [i for i, l in enumerate(lines) if l.strip().startswith(b"subsection")]
    ends = [i for i, l in enumerate(lines) if l.strip() == b"end"]
    op = rng.choice(["dup_sub", "drop_end", "extra_end", "unterminated", "unknown_sub",
                     "unknown_entry", "bare", "deep", "drop_sub"])
    if op == "dup_sub" and subs:
        i = rng.choice(subs)
        lines.insert(i, lines[i])
    elif op == "drop_end" and ends:
        del lines[rng.choice(ends)]
    elif op == "drop_sub" and subs:
        del lines[rng.choice(subs)]
    elif op == "extra_end":
        lines.insert(rng.randint(0, len(lines)), b"end")
    elif op == "unterminated":
        lines.append(b"subsection " + rng.choice([b"Mesh", b"Materials", b"Nowhere", b""]))
    elif op == "unknown_sub":
        lines.insert(rng.randint(0, len(lines)), b"subsection Fuzz\n  set a = 1\nend")
    elif op == "unknown_entry":
        lines.insert(rng.randint(0, len(lines)), b"set Fuzz entry = 1")
    elif op == "bare":
        lines.insert(rng.randint(0, len(lines)), rng.choice(
            [b"set", b"set =", b"set = 3", b"set Model", b"set Model ==", b"subsection",
             b"end end", b"set Model = continuum heat = 2", b"include", b"INCLUDE",
             b"set Model = continuum heat \\", b"\\", b"# \\"]))
    elif op == "deep":
        n = rng.choice([50, 1000, 20000])
        lines.append(b"subsection Mesh\n" * n + b"end\n" * rng.choice([0, n]))
    else:
        return m_prm_value(rng, data, ctx)
    return b"\n".join(lines), f"structure: {op}"


def m_prm_include(rng, data, ctx):
    target = rng.choice(["/nonexistent/fuzz.prm", "/dev/null", "/tmp", "SELF", ""])
    line = b"include " + (target.encode() if target != "SELF" else b"@SELF@")
    lines = data.split(b"\n")
    lines.insert(rng.randint(0, len(lines)), line)
    return b"\n".join(lines), f"include {target or '(nothing)'}"


def m_prm_continuation(rng, data, ctx):
    """A trailing backslash joins the next line (deal.II continuation)."""
    lines = data.split(b"\n")
    i = rng.randrange(len(lines))
    lines[i] = lines[i] + b"\\"
    return b"\n".join(lines), f"continuation backslash at line {i}"


PRM_MUTATORS = GENERIC * 1 + [m_prm_value] * 6 + [m_prm_number_in_selection] * 2 + \
    [m_prm_inject] * 6 + [m_prm_structure] * 4 + [m_prm_include, m_prm_continuation, m_empty]

# ---------------------------------------------------------- mesh mutators


def sections(lines):
    """{name: (begin index, end index)} of the $Name ... $EndName blocks."""
    out, open_ = {}, {}
    for i, l in enumerate(lines):
        s = l.strip()
        if s.startswith(b"$End"):
            name = s[4:]
            if name in open_:
                out[name] = (open_.pop(name), i)
        elif s.startswith(b"$"):
            open_[s[1:]] = i
    return out


def element_lines(lines, secs):
    """Indices of msh2 element lines (ids, type, tags, nodes) or msh4 element
    lines (id nodes...) in $Elements, skipping counts and block headers."""
    if b"Elements" not in secs:
        return []
    b, e = secs[b"Elements"]
    return [i for i in range(b + 2, e) if len(lines[i].split()) >= 3]


def node_lines(lines, secs):
    if b"Nodes" not in secs:
        return []
    b, e = secs[b"Nodes"]
    return [i for i in range(b + 2, e) if len(lines[i].split()) >= 3]


def mesh_parts(data):
    lines = data.split(b"\n")
    return lines, sections(lines)


def m_mesh_counts(rng, data, ctx):
    lines, secs = mesh_parts(data)
    names = [n for n in (b"Nodes", b"Elements") if n in secs]
    if not names:
        return m_flip(rng, data, ctx)
    name = rng.choice(names)
    i = secs[name][0] + 1
    words = lines[i].split()
    if not words:
        return data, "counts(empty)"
    k = rng.randrange(len(words))
    old = int(words[k]) if words[k].lstrip(b"-").isdigit() else 0
    new = rng.choice([old + 1, old - 1, old + 7, max(0, old // 2), 0, -1, 2 ** 31, 2 ** 32 + 3,
                      99999999999, 10 ** 9, 10 ** 30, "abc", "1e3", "nan"])
    words[k] = str(new).encode()
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"${name.decode()} count word {k}: {old} -> {new}"


def m_mesh_node_index(rng, data, ctx):
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el:
        return m_flip(rng, data, ctx)
    i = rng.choice(el)
    words = lines[i].split()
    k = rng.randrange(len(words) - 1, len(words)) if rng.random() < 0.6 else rng.randrange(len(words))
    new = rng.choice([0, -1, -5, 10 ** 6, 2 ** 31, 2 ** 32, 2 ** 32 + 1, 2 ** 64, 99999999999,
                      "x", "1.5", "nan", ""])
    words[k] = str(new).encode()
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"element line {i} word {k} -> {new!r}"


def m_mesh_duplicate_element(rng, data, ctx):
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el:
        return m_flip(rng, data, ctx)
    i = rng.choice(el)
    copy = lines[i]
    if rng.random() < 0.5:  # same nodes under a fresh id
        words = copy.split()
        words[0] = str(10 ** 6 + rng.randrange(1000)).encode()
        copy = b" ".join(words)
    lines.insert(i + 1, copy)
    fix = rng.random() < 0.5 and not lines[secs[b"Elements"][0] + 1].strip().count(b" ")
    if fix:
        c = secs[b"Elements"][0] + 1
        lines[c] = str(int(lines[c]) + 1).encode()
    return b"\n".join(lines), f"duplicate element line {i}{' (count fixed)' if fix else ''}"


def m_mesh_swap_nodes(rng, data, ctx):
    """Swaps two node ids of cells: inverted (clockwise) triangles."""
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el:
        return m_flip(rng, data, ctx)
    picked = rng.sample(el, min(len(el), rng.choice([1, 1, 3, len(el)])))
    for i in picked:
        words = lines[i].split()
        words[-1], words[-2] = words[-2], words[-1]
        lines[i] = b" ".join(words)
    return b"\n".join(lines), f"swap last two nodes of {len(picked)} element(s)"


def m_mesh_collapse(rng, data, ctx):
    """Repeats a node in an element (a degenerate cell)."""
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el:
        return m_flip(rng, data, ctx)
    i = rng.choice(el)
    words = lines[i].split()
    words[-1] = words[-2]
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"repeated node in element line {i}"


def m_mesh_coordinates(rng, data, ctx):
    lines, secs = mesh_parts(data)
    nl = node_lines(lines, secs)
    if not nl:
        return m_flip(rng, data, ctx)
    value = rng.choice(["nan", "-nan", "inf", "-inf", "1e308", "-1e308", "1e300", "1e-300",
                        "99999999999999999999", "1e400", "0", "x", "1,5", ""])
    picked = rng.sample(nl, min(len(nl), rng.choice([1, 1, 2, len(nl)])))
    for i in picked:
        words = lines[i].split()
        k = rng.randrange(max(0, len(words) - 3), len(words) - 1) if len(words) >= 3 else 0
        words[k] = value.encode()
        lines[i] = b" ".join(words)
    return b"\n".join(lines), f"coordinate -> {value!r} on {len(picked)} node(s)"


def m_mesh_all_same_point(rng, data, ctx):
    lines, secs = mesh_parts(data)
    nl = node_lines(lines, secs)
    if not nl:
        return m_flip(rng, data, ctx)
    for i in nl:
        words = lines[i].split()
        words[-3:] = [b"0", b"0", b"0"]
        lines[i] = b" ".join(words)
    return b"\n".join(lines), "all nodes at the origin"


def m_mesh_node_id(rng, data, ctx):
    lines, secs = mesh_parts(data)
    nl = node_lines(lines, secs)
    if not nl or not data.startswith(b"$MeshFormat\n2"):
        return m_mesh_node_index(rng, data, ctx)
    i = rng.choice(nl)
    words = lines[i].split()
    new = rng.choice([b"1", b"0", b"-1", b"4294967296", lines[nl[0]].split()[0]])
    words[0] = new
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"node id on line {i} -> {new!r}"


def m_mesh_element_type(rng, data, ctx):
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el or not data.startswith(b"$MeshFormat\n2"):
        return m_flip(rng, data, ctx)
    i = rng.choice(el)
    words = lines[i].split()
    k = rng.choice([1, 2])  # type or number of tags
    words[k] = rng.choice([b"0", b"1", b"3", b"4", b"5", b"15", b"99", b"-1", b"255", b"1000"])
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"element line {i}: {'type' if k == 1 else 'tag count'} -> {words[k]!r}"


def m_mesh_tags(rng, data, ctx):
    """Physical (material/boundary) ids: huge, negative, non-numeric."""
    lines, secs = mesh_parts(data)
    el = element_lines(lines, secs)
    if not el or not data.startswith(b"$MeshFormat\n2"):
        return m_flip(rng, data, ctx)
    i = rng.choice(el)
    words = lines[i].split()
    if len(words) < 5:
        return data, "tags(short)"
    words[3] = rng.choice([b"0", b"-1", b"255", b"256", b"65535", b"4294967295", b"99999999999", b"x"])
    lines[i] = b" ".join(words)
    return b"\n".join(lines), f"physical tag of element line {i} -> {words[3]!r}"


def m_mesh_format(rng, data, ctx):
    lines, secs = mesh_parts(data)
    if len(lines) < 2:
        return m_flip(rng, data, ctx)
    lines[1] = rng.choice([b"2.2 1 8", b"2.2 0 4", b"4.1 0 8", b"2.2 0 8", b"1.0 0 8", b"3.0 0 8",
                           b"4.0 0 8", b"5 0 8", b"-1 0 8", b"nan 0 8", b"", b"2.2"])
    return b"\n".join(lines), f"format line -> {lines[1]!r}"


def m_mesh_sections(rng, data, ctx):
    lines, secs = mesh_parts(data)
    if not secs:
        return m_flip(rng, data, ctx)
    name = rng.choice(sorted(secs))
    b, e = secs[name]
    op = rng.choice(["drop_end", "drop_section", "dup_section", "empty_section", "drop_begin"])
    if op == "drop_end":
        del lines[e]
    elif op == "drop_begin":
        del lines[b]
    elif op == "drop_section":
        del lines[b:e + 1]
    elif op == "dup_section":
        lines[e + 1:e + 1] = lines[b:e + 1]
    else:
        lines[b + 1:e] = [b"0"]
    return b"\n".join(lines), f"${name.decode(errors='replace')}: {op}"


def m_mesh_number_bytes(rng, data, ctx):
    """Flips characters inside numbers only (digits, signs, dots, exponents)."""
    b = bytearray(data)
    idx = [i for i, c in enumerate(b) if c in b"0123456789.-+eE"]
    if not idx:
        return m_flip(rng, data, ctx)
    n = rng.randint(1, 6)
    for _ in range(n):
        b[rng.choice(idx)] = rng.choice(b"0123456789.-+eE x\x00")
    return bytes(b), f"{n} number characters changed"


MESH_MUTATORS = GENERIC + [m_truncate] * 2 + [m_mesh_counts] * 3 + [m_mesh_node_index] * 3 + \
    [m_mesh_duplicate_element] * 2 + [m_mesh_swap_nodes] * 3 + [m_mesh_collapse] + \
    [m_mesh_coordinates] * 3 + [m_mesh_all_same_point, m_mesh_node_id, m_mesh_element_type,
                                m_mesh_tags, m_mesh_format] + [m_mesh_sections] * 2 + \
    [m_mesh_number_bytes] * 3

# ------------------------------------------------------------- the inputs


def make_input(seed, index, prm_seeds, mesh_seeds, entries, mesh_share):
    """Input `index` of `seed`: a dict with the file kind, its bytes, the
    mutations applied and, for meshes, the host prm."""
    rng = random.Random(f"tmfdem-fuzz:{seed}:{index}")
    kind = "mesh" if rng.random() < mesh_share else "prm"
    if kind == "prm":
        name, data = rng.choice(prm_seeds)
        ctx = {"same_kind": [d for _, d in prm_seeds], "entries": entries}
        mutators, host = PRM_MUTATORS, None
    else:
        name, data, host = rng.choice(mesh_seeds)
        ctx = {"same_kind": [d for _, d, _ in mesh_seeds], "entries": entries}
        mutators = MESH_MUTATORS
    log = []
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        mutator = rng.choice(mutators)
        try:
            data, what = mutator(rng, data, ctx)
        except (ValueError, IndexError) as exc:  # a mutator that met an odd file
            data, what = m_flip(rng, data, ctx)
            what = f"{mutator.__name__} gave up ({exc}); {what}"
        log.append(what)
    # a host of the other kind now and then, so that a discrete mesh meets
    # the continuum checks and back
    if kind == "mesh" and rng.random() < 0.15:
        host = rng.choice([h for _, _, h in mesh_seeds])
        log.append(f"host {os.path.relpath(host, REPO)}")
    return {"index": index, "kind": kind, "seed_file": name, "data": data,
            "mutations": log, "host": host}


def limit_child():
    os.setsid()
    try:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    except (ValueError, OSError):
        pass


def command_for(binary, item, input_path, out_dir):
    if item["kind"] == "prm":
        return [binary, input_path, "--validate", "--set", f"Output/Directory={out_dir}"]
    return [binary, item["host"], "--validate", "--set", f"Output/Directory={out_dir}",
            "--set", f"Mesh/File name={input_path}"]


def run_one(binary, item, work, timeout):
    """Writes the input, runs tmfdem on it, returns the verdict dict."""
    folder = tempfile.mkdtemp(prefix=f"in{item['index']:05d}-", dir=work)
    suffix = ".prm" if item["kind"] == "prm" else ".msh"
    input_path = os.path.join(folder, f"input{suffix}")
    data = item["data"].replace(b"@SELF@", input_path.encode())
    with open(input_path, "wb") as f:
        f.write(data)
    out_dir = os.path.join(folder, "out")
    cmd = command_for(binary, item, input_path, out_dir)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, preexec_fn=limit_child, env=env)
    timed_out = False
    try:
        stdout, stderr = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        timed_out = True
        try:  # the whole group: tmfdem and a gmsh it started
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        stdout, stderr = proc.communicate()
    seconds = time.monotonic() - start
    try:  # a gmsh left behind by a tmfdem that died
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass
    rc = proc.returncode
    warning = None
    err = stderr.decode("utf-8", "replace")
    first = next((l for l in err.splitlines() if l.strip()), "")
    if timed_out:
        status, problem = "timeout", f"no answer within {timeout} s (a hang)"
    elif rc < 0:
        status = f"signal {-rc}"
        problem = f"killed by signal {-rc} ({signal.Signals(-rc).name if -rc in signal.valid_signals() else '?'})"
    else:
        status = f"exit {rc}"
        problem = None
        if rc in (1, 2):
            tm = [l for l in err.splitlines() if l.startswith("tmfdem:")]
            if not tm or len(tm[0].strip()) < 25:
                problem = f"exit {rc} without a clear 'tmfdem: ...' message on stderr"
            elif not first.startswith("tmfdem:"):
                warning = "other text on stderr before the 'tmfdem:' message"
        elif rc != 0:
            problem = f"exit status {rc} (allowed: 0, 1, 2)"
    return {"index": item["index"], "status": status, "problem": problem, "cmd": cmd,
            "folder": folder, "input": input_path, "stderr": err, "stdout":
            stdout.decode("utf-8", "replace"), "seconds": seconds, "message": first, "warning": warning}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tmfdem")
    parser.add_argument("out_dir")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--count", type=int, default=80)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=20)
    parser.add_argument("--only", default="", help="comma-separated input indices to run")
    parser.add_argument("--mesh-share", type=float, default=0.45,
                        help="fraction of inputs that are mutated meshes")
    parser.add_argument("--strict-exit2", action="store_true",
                        help="count exit status 2 on bad input as a failure")
    parser.add_argument("--replay", default="",
                        help="folder of known bad inputs to run unchanged as well (*.prm as "
                             "prm files, @SELF@ standing for their own path; *.msh through "
                             "tests/data/square_from_file.prm)")
    parser.add_argument("--keep", action="store_true", help="keep every input, not only failures")
    args = parser.parse_args()

    binary = os.path.abspath(args.tmfdem)
    if not os.access(binary, os.X_OK):
        sys.exit(f"FAIL: {binary} is not an executable")
    out_dir = os.path.abspath(args.out_dir)
    shutil.rmtree(out_dir, ignore_errors=True)
    work = os.path.join(out_dir, "work")
    failures_dir = os.path.join(out_dir, "failures")
    os.makedirs(work)
    os.makedirs(failures_dir)

    prm_seeds, mesh_seeds = prm_corpus(), mesh_corpus()
    entries = known_entries(binary)
    indices = ([int(i) for i in args.only.split(",") if i.strip()] if args.only
               else list(range(args.count)))
    print(f"fuzz: seed {args.seed}, {len(indices)} inputs, {args.jobs} jobs, timeout "
          f"{args.timeout} s; corpus {len(prm_seeds)} prm + {len(mesh_seeds)} msh files, "
          f"{len(entries)} known entries", flush=True)

    items = [make_input(args.seed, i, prm_seeds, mesh_seeds, entries, args.mesh_share)
             for i in indices]
    if args.replay:
        square = os.path.join(REPO, "tests", "data", "square_from_file.prm")
        for k, f in enumerate(sorted(os.listdir(args.replay))):
            if f.endswith((".prm", ".msh")):
                items.append({"index": 90000 + k, "kind": "prm" if f.endswith(".prm") else "mesh",
                              "seed_file": os.path.join(args.replay, f),
                              "data": read_bytes(os.path.join(args.replay, f)),
                              "mutations": ["replayed unchanged"], "host": square})
        print(f"fuzz: replaying {len(items) - len(indices)} known inputs from {args.replay}")
    histogram = collections.Counter()
    exit2, failures, notes = [], [], []
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(run_one, binary, it, work, args.timeout): it for it in items}
        for future in concurrent.futures.as_completed(futures):
            item = futures[future]
            try:
                r = future.result()
            except Exception as exc:  # the harness itself: also a failure
                r = {"index": item["index"], "status": "harness error",
                     "problem": f"Python error: {exc!r}", "cmd": [], "folder": None,
                     "input": None, "stderr": "", "stdout": "", "seconds": 0, "message": ""}
            histogram[r["status"]] += 1
            if r["problem"] is None and r["status"] == "exit 2":
                exit2.append((item, r))
                if args.strict_exit2:
                    r["problem"] = "exit 2 on bad input (--strict-exit2)"
            if r["problem"]:
                failures.append((item, r))
            elif r.get("warning"):
                notes.append((item, r))
            keep = r["problem"] or r["status"] == "exit 2" or args.keep
            if r["folder"] and keep:
                dest = os.path.join(failures_dir if r["problem"] else out_dir,
                                    f"input{item['index']:05d}")
                shutil.rmtree(dest, ignore_errors=True)
                shutil.move(r["folder"], dest)
                r["kept"] = dest
                kept_input = os.path.join(dest, os.path.basename(r["input"]))
                with open(kept_input, "rb") as f:  # an include of itself
                    data = f.read()
                with open(kept_input, "wb") as f:
                    f.write(data.replace(r["input"].encode(), kept_input.encode()))
                with open(os.path.join(dest, "README.txt"), "w") as f:
                    f.write(describe(args.seed, item, r, dest))
            elif r["folder"]:
                shutil.rmtree(r["folder"], ignore_errors=True)

    elapsed = time.monotonic() - start
    shutil.rmtree(work, ignore_errors=True)
    for item, r in sorted(exit2, key=lambda x: x[0]["index"]):
        print(f"note: input {item['index']} ({item['kind']}, {'; '.join(item['mutations'])}) "
              f"gave exit 2, not 1: {r['message'][:200]}")
    for item, r in sorted(notes, key=lambda x: x[0]["index"]):
        print(f"note: input {item['index']} ({item['kind']}, {'; '.join(item['mutations'])}): "
              f"{r['warning']}: {r['message'][:120]!r}")
    for item, r in sorted(failures, key=lambda x: x[0]["index"]):
        print("\n" + "=" * 72)
        print(describe(args.seed, item, r, r.get("kept")))
    print("\nsummary: %d inputs in %.1f s (%.2f s each); exit statuses: %s; failures: %d"
          % (len(items), elapsed, elapsed / max(1, len(items)),
             ", ".join(f"{k}: {v}" for k, v in sorted(histogram.items())), len(failures)))
    if failures:
        print(f"FAIL: {len(failures)} input(s) crashed, hung or gave no clear message; "
              f"kept under {failures_dir}")
        return 1
    print("PASS")
    return 0


def describe(seed, item, r, kept):
    def adjusted(cmd):
        if not kept or not r.get("input"):
            return cmd
        new_input = os.path.join(kept, os.path.basename(r["input"]))
        return [c.replace(r["input"], new_input).replace(r["folder"], kept) for c in cmd]
    lines = [
        f"input {item['index']} of seed {seed}: {item['kind']} file mutated from {item['seed_file']}",
        f"mutations: {'; '.join(item['mutations'])}",
        f"verdict: {r['status']}" + (f" -> FAIL: {r['problem']}" if r["problem"] else ""),
        f"time: {r['seconds']:.2f} s",
        f"input kept at: {kept}" if kept else "input: not kept",
        "reproduce: " + " ".join(shlex.quote(c) for c in adjusted(r["cmd"])),
        f"  or: {os.path.abspath(__file__)} TMFDEM OUT --seed {seed} --only {item['index']}",
        "stderr (tail):",
        r["stderr"][-1500:].rstrip() or "(empty)",
    ]
    if item.get("host"):
        lines.insert(2, f"host prm: {item['host']}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
