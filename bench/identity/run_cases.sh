#!/usr/bin/env bash
# The outputs bench/compare_runs.py compares: for every case given (default: every shipped
# study case in cases2d/ and cases3d/ that optimizes), what `solve`, `check-gradient`,
# `optimize` and `certify` write, into OUT/solve-NAME/, OUT/grad-NAME.log, OUT/opt-NAME/ and
# OUT/opt-NAME.log, OUT/cert-NAME.log. One BLAS thread, so that the numbers do not depend on the
# machine's load (docs/benchmarks.md §0).
#   bash bench/identity/run_cases.sh FRICTOPT_BINARY OUT [CASE_DIR ...]
# Then: python3 bench/compare_runs.py OUT_BEFORE OUT_AFTER
set -uo pipefail
binary="$(realpath "$1")"; out="$2"; shift 2
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
mkdir -p "$out"
if [ "$#" -eq 0 ]; then
  # The tribometer and identification cases have no design to optimize (experiment, identify).
  set -- $(ls -d "$root"/cases2d/*/ "$root"/cases3d/*/ | grep -v -e tribometer -e identify)
fi
for dir in "$@"; do
  name="$(basename "$dir")"; case_file="$dir/case.toml"
  [ -f "$case_file" ] || continue
  start=$(date +%s)
  "$binary" solve "$case_file" -o "$out/solve-$name" > "$out/solve-$name.log" 2>&1
  "$binary" check-gradient "$case_file" > "$out/grad-$name.log" 2>&1
  "$binary" optimize "$case_file" -o "$out/opt-$name" > "$out/opt-$name.log" 2>&1
  "$binary" certify "$out/opt-$name" > "$out/cert-$name.log" 2>&1
  echo "$name: $(( $(date +%s) - start )) s"
done
