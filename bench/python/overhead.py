#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Python side of the call-overhead comparison (run_overhead.sh): the same call sequence as
overhead_bench.cpp through the frictopt module, then medians and ratios against the C++ times.

    python3 bench/python/overhead.py CASE.toml REPETITIONS CPP_BENCH_BINARY ROUNDS
Rounds alternate the C++ program and the Python calls so that both see the same machine load.
"""
from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

import numpy as np

import frictopt


def python_round(case: frictopt.Case, repetitions: int) -> dict[str, list[float]]:
    alpha0 = case.initial_design
    body = frictopt.Body(case)
    body.solve(alpha0)
    solve = []
    for k in range(repetitions):
        alpha = 1.001 * alpha0 if k % 2 else alpha0
        start = time.perf_counter()
        state = body.solve(alpha)
        solve.append(time.perf_counter() - start)
        assert state.converged
    oracle = frictopt.Oracle(case)
    oracle.evaluate(alpha0)
    evaluations = []
    for k in range(1, repetitions + 1):
        alpha = (1.0 + 1e-4 * k) * alpha0
        start = time.perf_counter()
        e = oracle.evaluate(alpha)
        evaluations.append(time.perf_counter() - start)
        assert e.ok
    cached = []
    for _ in range(1000):
        start = time.perf_counter()
        oracle.evaluate(alpha0)
        cached.append(time.perf_counter() - start)
    return {"solve_seconds": solve, "oracle_seconds": evaluations, "cached_oracle_seconds": cached}


def main() -> None:
    case_path, repetitions, binary, rounds = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4])
    case = frictopt.load_case(case_path)
    cpp: dict[str, list[float]] = {}
    py: dict[str, list[float]] = {}
    for _ in range(rounds):
        out = subprocess.run([binary, case_path, str(repetitions)], check=True, capture_output=True, text=True)
        for key, values in json.loads(out.stdout).items():
            cpp.setdefault(key, []).extend(values)
        for key, values in python_round(case, repetitions).items():
            py.setdefault(key, []).extend(values)
    print(f"case {case_path}: {rounds} rounds × {repetitions} calls (cached: × 1000); medians")
    print(f"{'call':<28} {'C++ [ms]':>12} {'Python [ms]':>12} {'ratio':>8} {'overhead [µs]':>14}")
    report = {}
    for key, label in (("solve_seconds", "Body.solve"), ("oracle_seconds", "Oracle.evaluate (Θ and ξ)"),
                       ("cached_oracle_seconds", "Oracle.evaluate, cached")):
        c, p = statistics.median(cpp[key]), statistics.median(py[key])
        report[key] = {"cpp_median": c, "python_median": p, "ratio": p / c}
        print(f"{label:<28} {1e3 * c:>12.4f} {1e3 * p:>12.4f} {p / c:>8.4f} {1e6 * (p - c):>14.1f}")
    print(json.dumps(report))


if __name__ == "__main__":
    main()
