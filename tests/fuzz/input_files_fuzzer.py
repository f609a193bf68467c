#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Mutation-based fuzzer of the files a case names, run by ctest (labels `fuzz`, `slow`).

Three surfaces, each a small seed that solves in a fraction of a second:

  - `.geo` files (cases2d/gmsh-body/body.geo; cases3d/gmsh-punch/punch.geo on a 4 x 4 x 2
    grid) read by `frictopt solve`: line- and value-level mutations, and Gmsh commands inserted
    anywhere — the ones the restricted reading refuses (System, SystemCall, Shell, OnelabRun,
    Exit, Printf > file, Save, Merge of a device, Include outside the folder, General.* and
    Solver.* options, macros that hide a command; docs/meshes.md, "A .geo file runs no code")
    and ones it allows (mesh options, an algorithm Gmsh crashes on, degenerate geometry);
  - `.msh` files (tests/mesh/data: a 2D format 4.1 plate and a 3D format 2.2 block) read by
    `frictopt solve`: the same text mutations, and elements naming missing nodes, wrong counts,
    short element lines, huge tags;
  - measurement CSVs (cases3d/identify-anisotropic on a 5 x 5 x 2 grid, 25 iterations) read by
    `frictopt identify`: the text mutations, and fields replaced by boundary values, unknown
    quantities, locations off the surface, rows copied a thousand times.

The outcome must be exit 0 or 3, or exit 2 with an "error: " line of bounded length, and the
.geo must not have run a command: no file whose name starts with the marker may appear (every
inserted command that would write, touches such a file). Never a crash (signal, exit 134 or
139), an internal error (exit 1), exit 4, any other code, or a run beyond the time limit per
mutant. Mesh reads are bounded by `--max-memory 1` (Gmsh's child process with them).
Failing mutants are kept in --keep-dir with the command's output.

    input_files_fuzzer.py --frictopt build/apps/frictopt/frictopt --source . --seconds 90 [--seed 1]
"""

import argparse
import concurrent.futures
import glob
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

# Values that replace a number: edges, non-finite, huge, negative, wrong types. (No count big
# enough to make a legitimate mesh of minutes: Gmsh's time limit is 600 s, not under test here.)
INTERESTING = ["0", "-1", "1", "2", "1e308", "-1e308", "1e-308", "1e-300", "nan", "inf", "-0",
               "2147483648", "9223372036854775808", "1e400", "0.5", "3", "4", '"x"', "", "+", "--1"]

# Gmsh commands inserted into a .geo; {mark} is a path whose creation means the command ran.
GEO_COMMANDS = [
    'System "touch {mark}_system";', 'SystemCall "touch {mark}_call";', 'SystemCall("touch {mark}_call2");',
    'NonBlockingSystemCall "touch {mark}_nb";', 'Shell "touch {mark}_shell";',
    'OnelabRun("x", "touch {mark}_onelab");', 'Exit;', 'Abort;', 'Printf("x") > "{mark}_printf";',
    'Printf("x") >> "{mark}_append";', 'Save "{mark}_save.msh";', 'Print "{mark}_print.png";',
    'CreateDir "{mark}_dir";', 'DeleteFile "{other}";', 'RenameFile "{other}", "{mark}_renamed";',
    'Sleep 100;', 'Merge "/dev/zero";', 'Merge "/etc/hostname";', 'Include "/etc/hostname";',
    'Include "../outside.geo";', 'Include "self.geo";', 'Include StrCat("/etc/", "hostname");',
    'General.SaveOptions = 1;', 'General.SaveSession = 1;', 'Solver.Executable0 = "/bin/sh";',
    'SetNumber("General.Terminal", 1);', 'SetString("Solver.Executable0", "/bin/sh");',
    'Macro Hidden System "touch {mark}_macro"; Return', 'Call Hidden;', 'Function F Exit; Return',
    'Plugin(Smooth).Run;', 'NewModel;', 'ListFromFile "/etc/hostname";',
    'Printf("%g", 1);', 'Printf("%s %s %s %s");', 'Error("stop");', 'x = 1/0;', 'x = y;',
    'Mesh.Algorithm = 8;', 'Mesh.Algorithm = 0;', 'Mesh.RecombineAll = 0;', 'Mesh.ElementOrder = 2;',
    'Mesh.MeshSizeMax = 1e-9;', 'Mesh.MeshSizeMin = 1e300;', 'Mesh.MeshSizeFactor = 1e-6;',
    'Mesh.SubdivisionAlgorithm = 1;', 'Mesh.RecombinationAlgorithm = 3;', 'Geometry.Tolerance = 1e308;',
    'Delete Physicals;', 'Physical Curve("Bottom") = {};', 'Physical Surface("Body") = {};',
    'Physical Surface("Bottom") = {1};', 'Point(1000) = {1e308, 1e308, 0, 1};', 'Point(1001) = {0, 0, 0, 0};',
    'Coherence;', 'Recombine Surface{:};', 'Delete { Surface{1}; }', 'Mesh 2;', 'Mesh 3;', 'RefineMesh;',
    '/* unterminated comment', '"unterminated string', 'Include "missing.geo";', '\0',
]


def text_mutation(text, rng):
    """One line- or byte-level mutation of any text file."""
    kind = rng.randrange(9)
    lines = text.split("\n")
    if kind == 0 and text:  # flip bytes
        data = bytearray(text.encode("utf-8", "surrogateescape"))
        for _ in range(rng.randrange(1, 5)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        return data.decode("utf-8", "surrogateescape")
    if kind == 1:  # truncate
        return text[: rng.randrange(len(text) + 1)]
    if kind == 2 and len(lines) > 1:  # delete a line
        del lines[rng.randrange(len(lines))]
    elif kind == 3 and lines:  # duplicate a line (or copy it many times)
        i = rng.randrange(len(lines))
        lines[i:i] = [lines[i]] * rng.choice([1, 2, 1000])
    elif kind == 4 and len(lines) > 1:  # swap two lines
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif kind == 5:  # a number replaced by an interesting value
        numbers = list(re.finditer(r"-?\d+(\.\d+)?(e[-+]?\d+)?", text))
        if numbers:
            m = rng.choice(numbers)
            return text[: m.start()] + rng.choice(INTERESTING) + text[m.end():]
    elif kind == 6:  # NUL bytes
        i = rng.randrange(len(text) + 1)
        return text[:i] + "\0" * rng.randrange(1, 8) + text[i:]
    elif kind == 7:  # random bytes
        i = rng.randrange(len(text) + 1)
        junk = bytes(rng.randrange(1, 256) for _ in range(rng.randrange(1, 32))).decode("utf-8", "surrogateescape")
        return text[:i] + junk + text[i:]
    else:  # CRLF line ends or a byte order mark
        return text.replace("\n", "\r\n") if rng.random() < 0.5 else "\ufeff" + text
    return "\n".join(lines)


def geo_mutation(text, rng, mark, other):
    if rng.random() < 0.5:
        return text_mutation(text, rng)
    lines = text.split("\n")
    command = rng.choice(GEO_COMMANDS).replace("{mark}", mark).replace("{other}", other)
    lines.insert(rng.randrange(len(lines) + 1), command)
    return "\n".join(lines)


def msh_mutation(text, rng):
    if rng.random() < 0.6:
        return text_mutation(text, rng)
    lines = text.split("\n")
    try:
        start = lines.index("$Elements") + 1
        end = lines.index("$EndElements")
    except ValueError:
        return text_mutation(text, rng)
    rows = [i for i in range(start + 1, end) if len(lines[i].split()) > 3]
    if not rows:
        return text_mutation(text, rng)
    i = rng.choice(rows)
    fields = lines[i].split()
    kind = rng.randrange(5)
    if kind == 0:  # an element names a node the file does not define
        fields[-1] = rng.choice(["0", "-1", "99999", "2147483648"])
    elif kind == 1:  # a short element line (one node less: Gmsh's 2.2 reader reads on)
        fields = fields[:-1]
    elif kind == 2:  # one node more
        fields.append(fields[-1])
    elif kind == 3:  # the element count of the section
        lines[start] = " ".join(rng.choice(["0", "1", "99999999", "-1"]) for _ in lines[start].split())
    else:  # the same element twice
        lines.insert(i, lines[i])
    if kind != 3:
        lines[i] = " ".join(fields)
    return "\n".join(lines)


CSV_QUANTITIES = ["normal_force", "pressure", "traction_x1", "traction_x2", "slip_x1", "total_normal_force",
                  "total_tangential_force_x2", "normal_forse", "", "pressure,", "PRESSURE"]
CSV_LOCATIONS = ["x=0.5;0.5", "x=0.5", "x=0.5;0.5;0.5", "x=1e308;0", "x=nan;0", "x=;", "x=0.5;", "0", "-1",
                 "120", "2147483648", "all", "", "x=0.1;0.1;", "x=-5;-5"]


def csv_mutation(text, rng):
    if rng.random() < 0.5:
        return text_mutation(text, rng)
    lines = text.split("\n")
    rows = [i for i, l in enumerate(lines) if l.count(",") == 3 and not l.startswith("quantity")]
    if not rows:
        return text_mutation(text, rng)
    i = rng.choice(rows)
    fields = lines[i].split(",")
    column = rng.randrange(4)
    if column == 0:
        fields[0] = rng.choice(CSV_QUANTITIES)
    elif column == 1:
        fields[1] = rng.choice(CSV_LOCATIONS)
    else:
        fields[column] = rng.choice(INTERESTING)
    lines[i] = ",".join(fields)
    return "\n".join(lines)


def read(path):
    with open(path, encoding="utf-8", errors="surrogateescape", newline="") as f:
        return f.read()


def write(path, text):
    with open(path, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write(text)


def make_seeds(source, work):
    """Each seed: (surface, folder with case.toml and the seed file, the file's name, its text)."""
    seeds = []
    # .geo: the 2D body and the 3D punch on a coarse grid.
    folder = os.path.join(work, "seed_geo2d")
    os.makedirs(folder)
    shutil.copy(os.path.join(source, "cases2d/gmsh-body/case.toml"), os.path.join(folder, "case.toml"))
    seeds.append(("geo", folder, "body.geo", read(os.path.join(source, "cases2d/gmsh-body/body.geo"))))
    folder = os.path.join(work, "seed_geo3d")
    os.makedirs(folder)
    shutil.copy(os.path.join(source, "cases3d/gmsh-punch/case.toml"), os.path.join(folder, "case.toml"))
    punch = read(os.path.join(source, "cases3d/gmsh-punch/punch.geo"))
    punch = re.sub(r"n1 = \d+, n2 = \d+, nv = \d+", "n1 = 4, n2 = 4, nv = 2", punch)
    seeds.append(("geo", folder, "punch.geo", punch))
    # .msh: a 2D plate (format 4.1) and a 3D block (format 2.2) with cases of their own.
    common = """
[material]
young = 1.0e9
poisson = 0.3

[contact.friction]
kind = "isotropic"
mu = 0.25
"""
    plate = """[geometry]
dim = 2

[mesh]
file = "plate.msh"
contact = "Bottom"

[[load]]
boundary = "Top"
traction = [-1.0e6, -5.0e6]

[[dirichlet]]
boundary = "Left"

[design]
control_points = [3]
initial = 0.0
upper_bound = 0.1
""" + common
    block = """[geometry]
dim = 3

[mesh]
file = "block.msh"
contact = "Bottom"

[[dirichlet]]
boundary = "Top"
displacement = [1.0e-5, 0.0, -1.0e-4]

[design]
control_points = [2, 2]
initial = 0.0
upper_bound = 0.1
""" + common
    for name, case, data in (("plate.msh", plate, "plate41.msh"), ("block.msh", block, "block22.msh")):
        folder = os.path.join(work, "seed_" + name.replace(".", "_"))
        os.makedirs(folder)
        write(os.path.join(folder, "case.toml"), case)
        seeds.append(("msh", folder, name, read(os.path.join(source, "tests/mesh/data", data))))
    # Measurements: the identification case on a coarse grid (its fit takes 0.1 s).
    folder = os.path.join(work, "seed_csv")
    os.makedirs(folder)
    case = read(os.path.join(source, "cases3d/identify-anisotropic/case.toml"))
    case = re.sub(r"^cells\s*=[^\n]*", "cells = [5, 5, 2]", case, count=1, flags=re.M)
    # The seed converges in 21 iterations; a mutant's fit may wander for the default 100, with
    # solves of 0.1 s each far from the data (a row copied 1000 times: 66 iterations, 17 s).
    case = re.sub(r"^max_iterations\s*=[^\n]*", "max_iterations = 25", case, count=1, flags=re.M)
    write(os.path.join(folder, "case.toml"), case)
    seeds.append(("csv", folder, "measurements.csv",
                  read(os.path.join(source, "cases3d/identify-anisotropic/measurements.csv"))))
    return seeds


def judge(code, output, ran):
    """None when the outcome is acceptable, else the reason."""
    if ran:
        return "the .geo ran a command: " + ", ".join(ran)
    if code is None:
        return "no result in time"
    if code in (0, 3):
        return None
    if code == 2:
        errors = [l for l in output.splitlines() if l.startswith("error: ")]
        if not errors:
            return "exit 2 without an 'error:' line"
        if len(errors[0]) > 2000:
            return "an error line of %d characters (unbounded echo of the file)" % len(errors[0])
        return None
    if code < 0:
        return "killed by signal %d" % -code
    return "exit %d" % code


def run_one(frictopt, work, index, seed, rng_seed, timeout):
    surface, folder, name, text = seed
    rng = random.Random(rng_seed)
    run = os.path.join(work, "m%06d" % index)
    shutil.copytree(folder, run)
    mark = os.path.join(run, "MARK")
    other = os.path.join(run, "case.toml")  # a file a .geo must not delete or rename
    for _ in range(rng.randrange(1, 3)):
        if surface == "geo":
            text = geo_mutation(text, rng, mark, other)
        elif surface == "msh":
            text = msh_mutation(text, rng)
        else:
            text = csv_mutation(text, rng)
    write(os.path.join(run, name), text)
    if surface == "geo":
        write(os.path.join(run, "self.geo"), 'Include "self.geo";\n')
    case = os.path.join(run, "case.toml")
    out = os.path.join(run, "out")
    command = ([frictopt, "identify", case, "-o", out] if surface == "csv"
               else [frictopt, "solve", case, "-o", out, "--max-memory", "1"])
    try:
        done = subprocess.run(command, capture_output=True, timeout=timeout, text=True, errors="replace")
        code, output = done.returncode, done.stdout + done.stderr
    except subprocess.TimeoutExpired:
        code, output = None, ""
    ran = [os.path.basename(p) for p in glob.glob(mark + "*")]
    if surface == "geo" and not os.path.exists(other):
        ran.append("case.toml deleted or renamed")
    return index, surface, name, run, text, command, code, output, judge(code, output, ran)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frictopt", required=True)
    parser.add_argument("--source", required=True, help="the repository root (seed files)")
    parser.add_argument("--seconds", type=float, default=90.0, help="time budget for launching mutants")
    parser.add_argument("--seed", type=int, default=int(os.environ.get("FRICTOPT_FUZZ_SEED", "17")))
    parser.add_argument("--timeout", type=float, default=30.0, help="limit per mutant [s]")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--keep-dir", default=None, help="where failing mutants are kept")
    args = parser.parse_args()

    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="frictopt_input_fuzz_")
    keep = args.keep_dir or os.path.join(tempfile.gettempdir(), "frictopt_input_fuzz_failures")
    seeds = make_seeds(args.source, work)
    # The seeds themselves must pass: a broken seed would only test the error path.
    for surface, folder, name, text in seeds:
        write(os.path.join(folder, name), text)
        command = ([args.frictopt, "identify"] if surface == "csv" else [args.frictopt, "solve"]) + \
            [os.path.join(folder, "case.toml"), "-o", os.path.join(folder, "out")]
        done = subprocess.run(command, capture_output=True, text=True, errors="replace", timeout=120)
        if done.returncode != 0:
            print("input files fuzzer: the seed %s/%s failed:\n%s" % (folder, name, done.stdout + done.stderr))
            return 1
        shutil.rmtree(os.path.join(folder, "out"))
    deadline = time.monotonic() + args.seconds
    outcomes, failures, index = {}, [], 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        pending = set()
        while time.monotonic() < deadline or pending:
            while time.monotonic() < deadline and len(pending) < 2 * args.jobs:
                seed = seeds[index % len(seeds)]  # every surface in turn
                pending.add(pool.submit(run_one, args.frictopt, work, index, seed, rng.getrandbits(64), args.timeout))
                index += 1
            finished, pending = concurrent.futures.wait(pending, return_when=concurrent.futures.FIRST_COMPLETED)
            for future in finished:
                i, surface, name, run, text, command, code, output, reason = future.result()
                key = "%s exit %s" % (surface, code)
                outcomes[key] = outcomes.get(key, 0) + 1
                if reason is not None:
                    os.makedirs(keep, exist_ok=True)
                    kept = os.path.join(keep, "seed%d_%06d" % (args.seed, i))
                    shutil.rmtree(kept, ignore_errors=True)
                    shutil.copytree(run, kept, ignore=shutil.ignore_patterns("out"))
                    with open(os.path.join(kept, "command.log"), "w", encoding="utf-8") as f:
                        f.write(" ".join(command) + "\n" + output)
                    failures.append((kept, name, reason, output.strip().splitlines()[-1:] if output else []))
                shutil.rmtree(run, ignore_errors=True)
    shutil.rmtree(work, ignore_errors=True)
    summary = ", ".join("%s: %d" % kv for kv in sorted(outcomes.items()))
    print("input files fuzzer: seed %d, %d mutants in %.0f s (%s)" % (args.seed, index, args.seconds, summary))
    for kept, name, reason, last in failures:
        print("FAILURE %s (%s): %s %s" % (kept, name, reason, last))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
