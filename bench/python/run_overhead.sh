#!/usr/bin/env bash
# The call overhead of the Python module (docs/python.md, "Performance: call overhead"): Body.solve and one oracle evaluation
# on the demo case from Python vs the same C++ calls, alternated call by call
# (docs/python.md, "Performance: call overhead").
#   bash bench/python/run_overhead.sh [REPETITIONS]
# One OpenBLAS thread per process unless OPENBLAS_NUM_THREADS is set: on a loaded machine the
# scheduling of BLAS worker threads moves either side's times by ±20% from run to run, which
# hides a per-call cost of microseconds (docs/python.md).
set -euo pipefail
export OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
cmake --build "$build" -j "${FRICTOPT_JOBS:-$(nproc)}" --target _frictopt python_overhead_bench >/dev/null
PYTHONPATH="$build/python" /usr/bin/python3 "$root/bench/python/overhead.py" \
  "$root/cases3d/punch-anisotropic/case.toml" "${1:-30}" "$build/python/python_overhead_bench"
