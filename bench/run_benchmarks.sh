#!/usr/bin/env bash
# Runs the FE and contact benchmarks and prints Markdown tables for
# docs/benchmarks.md. Needs a Release build in ./build (scripts/build.sh). The largest sizes
# take minutes and ~3 GB of memory: run on an otherwise idle machine; timings on a loaded
# machine are not comparable (the tables print the load average next to them).
#   bench/run_benchmarks.sh            all sizes
#   bench/run_benchmarks.sh quick      the ~20k-unknown size only
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
out="${TMPDIR:-/tmp}/frictopt-bench"
mkdir -p "$out"
filter_fem='.*' filter_contact='.*'
if [ "${1:-}" = quick ]; then filter_fem='n:18/'; filter_contact='cells:24/'; fi
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
"$build/bench/fem/elasticity_benchmark" --benchmark_filter="$filter_fem" --benchmark_format=json > "$out/fem.json"
"$build/bench/study/contact_benchmark" --benchmark_filter="$filter_contact" --benchmark_format=json > "$out/contact.json"
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
/usr/bin/python3 - "$out/fem.json" "$out/contact.json" <<'PY'
import json, sys
fem = json.load(open(sys.argv[1]))["benchmarks"]
print("\n| unknowns | contact DOFs last | assembly [s] | analysis [s] | factorization [s] | solve [s] | assembly/factorization | nnz(L) [M] | peak RSS [MB] |")
print("|---:|:---:|---:|---:|---:|---:|---:|---:|---:|")
for b in fem:
    last = "yes" if "contact_last:1" in b["name"] else "no"
    print(f"| {b['unknowns']:.0f} | {last} | {b['assembly_s']:.3f} | {b['analysis_s']:.3f} | {b['factorization_s']:.2f} | "
          f"{b['solve_s']:.3f} | {b['assembly_over_factorization']:.3f} | {b['factor_nnz_M']:.1f} | {b['peak_rss_MB']:.0f} |")
contact = json.load(open(sys.argv[2]))["benchmarks"]
print("\n| unknowns | contact nodes | floor: Cholesky + solve [s] | Coulomb state [s] | state/floor | fixed-point its | QP its | M applies | KKT | subgradient [s] | subgradient/state | peak RSS [MB] |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for b in contact:
    print(f"| {b['unknowns']:.0f} | {b['contact_nodes']:.0f} | {b['floor_s']:.2f} | {b['state_s']:.2f} | {b['state_over_floor']:.2f} | "
          f"{b['fixed_point_its']:.0f} | {b['qp_its']:.0f} | {b['applies']:.0f} | {b['kkt']:.1e} | {b['subgradient_s']:.2f} | "
          f"{b['subgradient_over_state']:.2f} | {b['peak_rss_MB']:.0f} |")
PY
