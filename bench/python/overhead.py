#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The Python side of the call-overhead comparison (run_overhead.sh): the call sequence of
overhead_bench.cpp through the frictopt module, alternating one C++ call (served by that
program) and the same call from Python, so both see the same machine load; then medians of
each side and of the per-pair ratios.

    python3 bench/python/overhead.py CASE.toml REPETITIONS CPP_BENCH_BINARY
"""
from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

import frictopt


def main() -> None:
    case_path, repetitions, binary = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    case = frictopt.load_case(case_path)
    cpp = subprocess.Popen([binary, case_path], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert cpp.stdout.readline().strip() == "ready"

    def cpp_call(request: str) -> tuple[float, float]:
        cpp.stdin.write(request + "\n")
        cpp.stdin.flush()
        wall, cpu = cpp.stdout.readline().split()
        return float(wall), float(cpu)

    def timed(call):
        """(wall, process CPU) seconds of call(); CPU time is robust to the machine's load."""
        wall, cpu = time.perf_counter(), time.process_time()
        result = call()
        return time.perf_counter() - wall, time.process_time() - cpu, result

    alpha0 = case.initial_design
    body = frictopt.Body(case)
    body.solve(alpha0)  # warm-up, as the C++ side
    oracle = frictopt.Oracle(case)
    oracle.evaluate(alpha0)

    def py_solve(k: int) -> tuple[float, float]:
        alpha = 1.001 * alpha0 if k % 2 else alpha0
        wall, cpu, state = timed(lambda: body.solve(alpha))
        assert state.converged
        return wall, cpu

    def py_oracle(k: int) -> tuple[float, float]:
        alpha = (1.0 + 1e-4 * k) * alpha0
        wall, cpu, e = timed(lambda: oracle.evaluate(alpha))
        assert e.ok
        return wall, cpu

    def py_cached(_: int) -> tuple[float, float]:
        wall, cpu, _ = timed(lambda: oracle.evaluate(alpha0))
        return wall, cpu

    rows = {}
    for key, label, count, python_call in (("solve", "Body.solve", repetitions, py_solve),
                                           ("oracle", "Oracle.evaluate (Θ and ξ)", repetitions, py_oracle),
                                           ("cached", "Oracle.evaluate, cached", 2000, py_cached)):
        pairs = [(cpp_call(f"{key} {k}"), python_call(k)) for k in range(1, count + 1)]
        row = {"label": label, "calls": count}
        for clock, index in (("wall", 0), ("cpu", 1)):
            row[f"cpp_{clock}_median"] = statistics.median(c[index] for c, _ in pairs)
            row[f"python_{clock}_median"] = statistics.median(p[index] for _, p in pairs)
            row[f"{clock}_ratio"] = row[f"python_{clock}_median"] / row[f"cpp_{clock}_median"]
        rows[key] = row
    cpp.stdin.close()
    cpp.wait()

    print(f"case {case_path}: C++ and Python calls alternated; medians (wall time / process CPU time)")
    print(f"{'call':<28} {'calls':>6} {'C++ wall [ms]':>14} {'Py wall [ms]':>13} {'ratio':>7} "
          f"{'C++ CPU [ms]':>13} {'Py CPU [ms]':>12} {'ratio':>7}")
    for r in list(rows.values())[:2]:
        print(f"{r['label']:<28} {r['calls']:>6} {1e3 * r['cpp_wall_median']:>14.2f} {1e3 * r['python_wall_median']:>13.2f} "
              f"{r['wall_ratio']:>7.4f} {1e3 * r['cpp_cpu_median']:>13.2f} {1e3 * r['python_cpu_median']:>12.2f} "
              f"{r['cpu_ratio']:>7.4f}")
    cached = rows["cached"]
    print(f"fixed cost of one call (cached evaluation, {cached['calls']} calls, wall): C++ "
          f"{1e6 * cached['cpp_wall_median']:.2f} µs, Python {1e6 * cached['python_wall_median']:.2f} µs")
    print(json.dumps(rows))


if __name__ == "__main__":
    main()
