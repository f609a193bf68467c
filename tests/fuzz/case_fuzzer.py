#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Mutation-based fuzzer of frictopt's case files, run by ctest (label `fuzz`).

Seeds are the shipped cases and the test cases, coarsened to a small grid so that a valid
mutant solves in a fraction of a second. Each mutant (a few line- and value-level mutations:
deleted, duplicated or swapped lines, values replaced by boundary values, NaN, huge numbers,
control characters, misspelt keys, unknown tables, truncation, random bytes, a byte order
mark) is run through `frictopt solve`; the outcome must be

  - exit 0 (a valid case), or exit 3 (a valid case whose solve did not converge), or
  - exit 2 with one "error: <case path>..." line that names the problem (a field, "missing",
    "unknown", "expected", a syntax error or an empty file),

and never a crash (signal, abort, exit 134), an internal error (exit 1), an out-of-memory
(exit 4) or a run beyond the per-case time limit. Failing mutants are kept in --keep-dir
with the command's output, to be turned into regression tests.

    case_fuzzer.py --frictopt build/apps/frictopt/frictopt --source . --seconds 60 [--seed 1]
"""

import argparse
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

# Values a mutation may put in place of a TOML value: the edges of every documented range
# (docs/case-format.md), non-finite and huge numbers, wrong types and hostile strings.
INTERESTING = [
    "0", "-1", "1", "2", "3", "64", "65", "256", "257", "1024", "2147483647", "2147483648",
    "9223372036854775807", "-9223372036854775808", "1000000", "0.0", "-0.0", "1e-300", "1e308",
    "-1e308", "1e-15", "0.49", "0.49999999", "0.5", "nan", "inf", "-inf", "+nan", "1e400",
    '""', '"x"', '"top"', '"bottom"', '"a\\u0000b"', '"../x"', '"\\n"', "true", "false", "[]",
    "[1]", "[1, 2]", "[1, 2, 3]", "[1, 2, 3, 4]", "[0, 0, 0]", "[1e308, 1e308, 1e308]",
    "[100000, 100000]", "[300, 300, 300]", "{}", "1979-05-27", '"initial_mean"',
]
TABLE_HEADERS = ["[study]", "[foo]", "[solver.fem]", "[[load]]", "[[dirichlet]]", "[contact]",
                 "[contact.friction]", "[cost]", "[optimization]", "[output]", "[identification]"]
COARSE_CELLS = {2: "[8, 4]", 3: "[4, 3, 2]"}


def coarsened(text):
    """The seed with a small grid (the mutations, not the mesh size, are under test)."""
    dim = 3 if re.search(r"^dim\s*=\s*3", text, re.M) else 2
    return re.sub(r"^cells\s*=[^\n]*", "cells = " + COARSE_CELLS[dim], text, count=1, flags=re.M)


def load_seeds(source):
    seeds = []
    for folder in ("cases2d", "cases3d", "tests/cli/data", "tests/io/data"):
        root = os.path.join(source, folder)
        for dirpath, _, files in os.walk(root):
            for name in sorted(files):
                if name.endswith(".toml"):
                    with open(os.path.join(dirpath, name), encoding="utf-8") as f:
                        text = f.read()
                    if "[identification]" in text:  # its measurement path is relative to the seed
                        text = re.sub(r"\[identification\][^\[]*(\[\[?identification\.[^\n]*\n[^\[]*)*", "", text)
                    seeds.append(coarsened(text))
    return seeds


def mutate_once(text, rng):
    lines = text.split("\n")
    kind = rng.randrange(11)
    value_lines = [i for i, l in enumerate(lines) if re.match(r"^\s*[A-Za-z_]+\s*=", l)]
    if kind == 0 and lines:  # delete a line
        del lines[rng.randrange(len(lines))]
    elif kind == 1 and lines:  # duplicate a line (duplicate keys, tables)
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
    elif kind == 2 and len(lines) > 1:  # swap two lines (keys into other tables)
        i, j = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif kind in (3, 4, 5) and value_lines:  # a boundary or hostile value
        i = rng.choice(value_lines)
        key = lines[i].split("=", 1)[0]
        lines[i] = key + "= " + rng.choice(INTERESTING)
    elif kind == 6 and value_lines:  # a misspelt key
        i = rng.choice(value_lines)
        key, rest = lines[i].split("=", 1)
        key = key.strip()
        if key:
            p = rng.randrange(len(key))
            key = key[:p] + rng.choice("abcxyz_") + key[p + 1:]
        lines[i] = key + " =" + rest
    elif kind == 7:  # a table header anywhere
        lines.insert(rng.randrange(len(lines) + 1), rng.choice(TABLE_HEADERS))
    elif kind == 8:  # truncation
        return text[: rng.randrange(len(text) + 1)]
    elif kind == 9:  # random bytes
        p = rng.randrange(len(text) + 1)
        # Raw bytes, invalid UTF-8 included (kept as surrogate escapes until written).
        junk = bytes(rng.randrange(1, 256) for _ in range(rng.randrange(1, 8))).decode("utf-8", "surrogateescape")
        return text[:p] + junk + text[p:]
    else:  # a byte order mark, or CRLF line ends
        return ("\ufeff" + text) if rng.random() < 0.5 else text.replace("\n", "\r\n")
    return "\n".join(lines)


def mutant(seeds, rng):
    text = rng.choice(seeds)
    for _ in range(rng.randrange(1, 4)):
        text = mutate_once(text, rng)
    return text


NAMING = re.compile(r"=|missing|unknown|expected|syntax error|is empty|not allowed|reserved|needs|"
                    r"could not be read|not a regular file")


def judge(case_path, code, output):
    """None when the outcome is acceptable, else the reason."""
    if code in (0, 3):
        return None
    if code == 2:
        errors = [l for l in output.splitlines() if l.startswith("error: ")]
        if not errors:
            return "exit 2 without an 'error:' line"
        if case_path not in errors[0]:
            return "exit 2 without the case path in the message"
        if not NAMING.search(errors[0]):
            return "exit 2 with a message that names no field or expectation"
        return None
    if code < 0:
        return "killed by signal %d" % -code
    return "exit %d" % code


def run_one(frictopt, work, index, text, timeout):
    case_path = os.path.join(work, "case%06d.toml" % index)
    with open(case_path, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
        f.write(text)
    out_dir = os.path.join(work, "out%06d" % index)
    try:
        done = subprocess.run([frictopt, "solve", case_path, "-o", out_dir], capture_output=True,
                              timeout=timeout, text=True, errors="replace")
        code, output = done.returncode, done.stdout + done.stderr
        reason = judge(case_path, code, output)
    except subprocess.TimeoutExpired:
        code, output, reason = None, "", "no result within %g s" % timeout
    shutil.rmtree(out_dir, ignore_errors=True)
    return index, case_path, code, output, reason


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frictopt", required=True)
    parser.add_argument("--source", required=True, help="the repository root (seed cases)")
    parser.add_argument("--seconds", type=float, default=60.0, help="time budget for launching mutants")
    parser.add_argument("--seed", type=int, default=int(os.environ.get("FRICTOPT_FUZZ_SEED", "17")))
    parser.add_argument("--timeout", type=float, default=30.0, help="limit per mutant [s]")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--keep-dir", default=None, help="where failing mutants are kept")
    args = parser.parse_args()

    rng = random.Random(args.seed)
    seeds = load_seeds(args.source)
    if not seeds:
        print("no seed cases found under", args.source)
        return 1
    work = tempfile.mkdtemp(prefix="frictopt_fuzz_")
    keep = args.keep_dir or os.path.join(tempfile.gettempdir(), "frictopt_fuzz_failures")
    deadline = time.monotonic() + args.seconds
    outcomes, failures, index = {}, [], 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        pending = set()
        while time.monotonic() < deadline or pending:
            while time.monotonic() < deadline and len(pending) < 2 * args.jobs:
                pending.add(pool.submit(run_one, args.frictopt, work, index, mutant(seeds, rng), args.timeout))
                index += 1
            finished, pending = concurrent.futures.wait(pending, return_when=concurrent.futures.FIRST_COMPLETED)
            for future in finished:
                i, case_path, code, output, reason = future.result()
                outcomes[code] = outcomes.get(code, 0) + 1
                if reason is None:
                    os.remove(case_path)
                    continue
                os.makedirs(keep, exist_ok=True)
                kept = os.path.join(keep, "seed%d_case%06d.toml" % (args.seed, i))
                shutil.move(case_path, kept)
                with open(kept + ".log", "w", encoding="utf-8") as f:
                    f.write(output)
                failures.append((kept, reason, output.strip().splitlines()[-1:] if output else []))
    shutil.rmtree(work, ignore_errors=True)
    summary = ", ".join("exit %s: %d" % (k, v) for k, v in sorted(outcomes.items(), key=lambda kv: str(kv[0])))
    print("case fuzzer: seed %d, %d seeds, %d mutants in %.0f s (%s)" % (args.seed, len(seeds), index,
                                                                       args.seconds, summary))
    for kept, reason, last in failures:
        print("FAILURE %s: %s %s" % (kept, reason, last))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
