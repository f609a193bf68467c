#!/usr/bin/env bash
# Measures the bundle trust BEFORE the adaptive step bound (commit 47d6906, fixed step bound T = 10/‖g1‖,
# absolute stopping test) on the CURRENT Lukšan–Vlček problem set, for the "previous" column
# of docs/optim-testset.md. Exports the old optim/core sources, adds the current problem files
# and compiles them with bench/optim/previous_table.cpp. Usage (from the repository root):
#   bench/optim/measure_previous.sh [COMMIT] [OUT_DIR]
# Prints two SUMMARY lines: old defaults, and the old docs' raised limits (3000 / 10 000).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
commit="${1:-47d6906}"
out="${2:-${TMPDIR:-/tmp}/frictopt-previous-optim}"
mkdir -p "$out"
rm -rf "$out/src" "$out/include"
git -C "$root" archive "$commit" src/optim src/core include/frictopt/optim include/frictopt/core | tar -x -C "$out"
mkdir -p "$out/testset"
cp "$root"/tests/support/testset/* "$out/testset/"
g++ -std=c++20 -O2 -DNDEBUG -I "$out/include" -I "$out" -I /usr/include/eigen3 "$root/bench/optim/previous_table.cpp" \
  "$out"/src/optim/{bundle_trust,dense_qp,linear_constraints,stationarity}.cpp "$out"/testset/*.cpp \
  "$out"/src/core/*.cpp -o "$out/previous_table"
"$out/previous_table" > "$out/defaults.txt"
"$out/previous_table" raised > "$out/raised.txt"
echo "old defaults:      $(tail -1 "$out/defaults.txt")"
echo "old raised limits: $(tail -1 "$out/raised.txt")"
echo "per-problem lines: $out/defaults.txt, $out/raised.txt"
