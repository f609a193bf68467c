#!/usr/bin/env bash
# The call overhead of the Python module (issue 15 item 7): Body.solve and one oracle evaluation
# on the demo case, from Python vs the same C++ calls (docs/python.md, "Performance").
#   bash bench/python/run_overhead.sh [REPETITIONS] [ROUNDS]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
cmake --build "$build" -j "${FRICTOPT_JOBS:-$(nproc)}" --target _frictopt python_overhead_bench >/dev/null
PYTHONPATH="$build/python" /usr/bin/python3 "$root/bench/python/overhead.py" \
  "$root/cases3d/punch-anisotropic/case.toml" "${1:-10}" "$build/python/python_overhead_bench" "${2:-3}"
