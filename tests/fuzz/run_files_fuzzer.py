#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Mutation-based fuzzer of a run directory's files, run by ctest (labels `fuzz`, `slow`).

A real run of the thesis' example 5.2.1 (two iterations, 2D) is made once; each mutant damages
one of its files — checkpoint.json, history.csv or final_design.json — or a design file for
`check-gradient --design`: byte flips, truncation, deleted, duplicated or swapped lines, values
replaced by boundary values, NaN, huge numbers, NUL bytes, deeply nested JSON, a FIFO or a
directory in place of the file. The command that reads it (`optimize --resume` with a longer
iteration limit, `certify`, `check-gradient --design`) must then

  - exit 0 or 3 (the damage left a valid file: e.g. white space), or
  - exit 2 with an "error: " line naming the damaged file,

and never crash (signal, exit 134), hang, exit 1 (internal error) or 4, nor echo more than a
bounded excerpt of the file. Failing mutants are kept in --keep-dir with the command's output.

    run_files_fuzzer.py --frictopt build/apps/frictopt/frictopt --source . --seconds 60 [--seed 1]
"""

import argparse
import os
import random
import re
import shutil
import stat
import subprocess
import sys
import tempfile
import time

INTERESTING = ["0", "-1", "1", "2147483648", "9223372036854775807", "1e308", "-1e308", "1e-320",
               "NaN", "null", "true", '"x"', "[]", "{}", "[[[[[[]]]]]]", '"' + "a" * 300 + '"']


def mutate_text(text, rng):
    kind = rng.randrange(9)
    if kind == 0 and text:  # flip bytes
        data = bytearray(text.encode("utf-8", "surrogateescape"))
        for _ in range(rng.randrange(1, 5)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        return data.decode("utf-8", "surrogateescape")
    if kind == 1:  # truncate
        return text[: rng.randrange(len(text) + 1)]
    lines = text.split("\n")
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
    elif kind == 7:  # deep nesting
        depth = rng.choice([65, 1000, 200000])
        i = rng.randrange(len(text) + 1)
        return text[:i] + "[" * depth + "]" * rng.choice([0, depth]) + text[i:]
    elif kind == 8:  # random bytes appended
        return text + "".join(chr(rng.randrange(1, 256)) for _ in range(rng.randrange(1, 64)))
    return "\n".join(lines)


def judge(damaged, code, output):
    if code in (0, 3):
        return None
    if code == 2:
        # "error: ..." from frictopt, or CLI11's usage message naming the option's file.
        errors = [l for l in output.splitlines() if l.startswith("error: ") or l.startswith("--design: ")]
        if not errors:
            return "exit 2 without an 'error:' line"
        # The file, or (a damaged design that still parses) the field and its expectation.
        if os.path.basename(damaged) not in errors[0] and "expected" not in errors[0]:
            return "exit 2 naming neither the damaged file nor an expectation"
        if len(errors[0]) > 2000:
            return "an error line of %d characters (unbounded echo of the file)" % len(errors[0])
        return None
    if code is None:
        return "no result in time"
    if code < 0:
        return "killed by signal %d" % -code
    return "exit %d" % code


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--frictopt", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--seed", type=int, default=int(os.environ.get("FRICTOPT_FUZZ_SEED", "17")))
    parser.add_argument("--timeout", type=float, default=30.0)
    parser.add_argument("--keep-dir", default=None)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="frictopt_run_fuzz_")
    keep = args.keep_dir or os.path.join(tempfile.gettempdir(), "frictopt_run_fuzz_failures")
    with open(os.path.join(args.source, "cases2d/ex521-target-pressure/case.toml"), encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"^max_iterations\s*=[^\n]*", "max_iterations = 2", text, flags=re.M)
    text = re.sub(r"^every\s*=[^\n]*", "every = 100", text, flags=re.M)
    case = os.path.join(work, "case.toml")
    with open(case, "w", encoding="utf-8") as f:
        f.write(text)
    pristine = os.path.join(work, "pristine")
    done = subprocess.run([args.frictopt, "optimize", case, "-o", pristine], capture_output=True, text=True)
    if done.returncode != 0:
        print("run files fuzzer: the seed run failed:\n" + done.stdout + done.stderr)
        return 1
    with open(os.path.join(pristine, "case.toml"), encoding="utf-8") as f:
        longer = re.sub(r"^max_iterations\s*=[^\n]*", "max_iterations = 3", f.read(), flags=re.M)
    with open(os.path.join(pristine, "case.toml"), "w", encoding="utf-8") as f:
        f.write(longer)
    targets = ["checkpoint.json", "history.csv", "final_design.json", "design.json"]
    deadline = time.monotonic() + args.seconds
    outcomes, failures, index = {}, [], 0
    while time.monotonic() < deadline:
        run = os.path.join(work, "run%06d" % index)
        shutil.copytree(pristine, run)
        target = rng.choice(targets)
        if target == "design.json":
            damaged = os.path.join(work, "design%06d.json" % index)
            shutil.copy(os.path.join(pristine, "final_design.json"), damaged)
            command = [args.frictopt, "check-gradient", case, "--design", damaged]
        else:
            damaged = os.path.join(run, target)
            command = ([args.frictopt, "certify", run] if target == "final_design.json"
                       else [args.frictopt, "optimize", os.path.join(run, "case.toml"), "-o", run, "--resume"])
        special = rng.random() < 0.05
        if special:  # a FIFO or a directory in place of the file
            os.remove(damaged)
            os.mkfifo(damaged) if rng.random() < 0.5 else os.mkdir(damaged)
        else:
            with open(damaged, encoding="utf-8", errors="surrogateescape", newline="") as f:
                content = f.read()
            for _ in range(rng.randrange(1, 3)):
                content = mutate_text(content, rng)
            with open(damaged, "w", encoding="utf-8", errors="surrogateescape", newline="") as f:
                f.write(content)
        try:
            result = subprocess.run(command, capture_output=True, timeout=args.timeout, text=True, errors="replace")
            code, output = result.returncode, result.stdout + result.stderr
        except subprocess.TimeoutExpired:
            code, output = None, ""
        reason = judge(damaged, code, output)
        outcomes[code] = outcomes.get(code, 0) + 1
        if reason is not None:
            os.makedirs(keep, exist_ok=True)
            kept = os.path.join(keep, "seed%d_%06d_%s" % (args.seed, index, os.path.basename(damaged)))
            if not special:
                shutil.copy(damaged, kept)
            with open(kept + ".log", "w", encoding="utf-8") as f:
                f.write(" ".join(command) + "\n" + output)
            failures.append((kept, reason, output.strip().splitlines()[-1:] if output else []))
        if os.path.exists(damaged) and stat.S_ISFIFO(os.lstat(damaged).st_mode):
            os.remove(damaged)
        shutil.rmtree(run, ignore_errors=True)
        if target == "design.json" and os.path.lexists(damaged):
            shutil.rmtree(damaged) if os.path.isdir(damaged) else os.remove(damaged)
        index += 1
    shutil.rmtree(work, ignore_errors=True)
    summary = ", ".join("exit %s: %d" % (k, v) for k, v in sorted(outcomes.items(), key=lambda kv: str(kv[0])))
    print("run files fuzzer: seed %d, %d mutants in %.0f s (%s)" % (args.seed, index, args.seconds, summary))
    for kept, reason, last in failures:
        print("FAILURE %s: %s %s" % (kept, reason, last))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
