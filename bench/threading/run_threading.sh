#!/usr/bin/env bash
# BLAS threads on an idle and on a busy machine, side by side (docs/benchmarks.md §2b).
#
#   bench/threading/run_threading.sh [--binary PATH] [--repeat N] [--case CASE_TOML] [--nice N] [--out DIR]
#
# For each threading mode — OPENBLAS_NUM_THREADS=1 (one thread everywhere),
# FRICTOPT_BLAS_THREADS=<cores> (the BLAS' threads in every call: what frictopt did before the
# automatic rule) and the default (automatic: docs/benchmarks.md, "BLAS threads on a shared
# machine") — `frictopt solve CASE` runs N times with nothing else started ("idle") and N times
# while one `yes > /dev/null` keeps a core busy ("busy"); runs of the modes are interleaved so
# that drifting background load hits all modes alike. The table gives medians of the
# factorization and of the Coulomb state solve (as frictopt prints them), of the wall and CPU
# (user + sys) time of the whole command, and the ratio busy/idle of the wall time: the target
# is at most 2 on two cores (a busy second core costs at most the lost core).
# --nice N runs frictopt and the busy loop at nice N (e.g. -10, as root) so that other users of
# a shared machine disturb the comparison less; the load average is printed either way.
# Default case: cases3d/punch-anisotropic (the demo); cases3d/punch-large takes minutes per run.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
binary="$root/build/apps/frictopt/frictopt"
repeat=5
case_file="$root/cases3d/punch-anisotropic/case.toml"
nice_level=0
out="${TMPDIR:-/tmp}/frictopt-threading"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --repeat) repeat="$2"; shift 2 ;;
    --case) case_file="$2"; shift 2 ;;
    --nice) nice_level="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    -h|--help) sed -n 2,19p "$0"; exit 0 ;;
    *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -x "$binary" ]] || { echo "no frictopt binary at $binary (build it or pass --binary)" >&2; exit 2; }
[[ -f "$case_file" ]] || { echo "no case file $case_file" >&2; exit 2; }
mkdir -p "$out"
cores=$(nproc)
modes=("OPENBLAS_NUM_THREADS=1" "FRICTOPT_BLAS_THREADS=$cores" "default")
raw="$out/raw.txt"
: > "$raw"

busy_pid=""
cleanup() { [[ -n "$busy_pid" ]] && kill "$busy_pid" 2>/dev/null || true; }
trap cleanup EXIT

one_run() {  # condition mode
  local env_args=()
  [[ "$2" != default ]] && env_args=("$2")
  local log="$out/run.log" times="$out/time.txt"
  env -u OPENBLAS_NUM_THREADS -u OMP_NUM_THREADS -u GOTO_NUM_THREADS -u FRICTOPT_BLAS_THREADS "${env_args[@]}" \
    /usr/bin/time -f "%e %U %S" -o "$times" nice -n "$nice_level" "$binary" solve "$case_file" -o "$out/solve" > "$log" 2>&1
  local fact solve
  fact=$(grep -o 'factorization [0-9.e+-]* s' "$log" | awk '{print $2}' | tail -1)
  solve=$(grep '^Coulomb ' "$log" | awk '{print $(NF - 1)}' | tail -1)
  [[ -z "$solve" ]] && solve=$(grep -o ', solve [0-9.e+-]* s' "$log" | awk '{print $2}' | tail -1)
  read -r wall user sys < "$times"
  echo "$1 $2 $fact $solve $wall $(awk -v u="$user" -v s="$sys" 'BEGIN {print u + s}')" >> "$raw"
}

echo "frictopt threading benchmark: $(date -u +%FT%TZ), $cores cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "binary: $binary ($(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')), case: $case_file, $repeat runs per cell, nice $nice_level"
for condition in idle busy; do
  if [[ $condition == busy ]]; then
    nice -n "$nice_level" yes > /dev/null &
    busy_pid=$!
    sleep 1
  fi
  for ((k = 1; k <= repeat; ++k)); do
    for mode in "${modes[@]}"; do one_run "$condition" "$mode"; done
  done
  if [[ $condition == busy ]]; then kill "$busy_pid"; wait "$busy_pid" 2>/dev/null || true; busy_pid=""; fi
  echo "load average after the $condition runs: $(cut -d' ' -f1-3 /proc/loadavg)"
done

median() { sort -g | awk '{a[NR] = $1} END {if (NR % 2) print a[(NR + 1) / 2]; else print (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }
printf '\n| mode | condition | factorization [s] | Coulomb state [s] | wall [s] | CPU [s] | wall busy / idle |\n|---|---|---:|---:|---:|---:|---:|\n'
for mode in "${modes[@]}"; do
  idle_wall=$(awk -v m="$mode" '$1 == "idle" && $2 == m {print $5}' "$raw" | median)
  for condition in idle busy; do
    col() { awk -v c="$condition" -v m="$mode" -v k="$1" '$1 == c && $2 == m {print $k}' "$raw" | median; }
    wall=$(col 5)
    ratio=$(awk -v a="$wall" -v b="$idle_wall" 'BEGIN {printf "%.2f", a / b}')
    printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$mode" "$condition" "$(col 3)" "$(col 4)" "$wall" "$(col 6)" "$ratio"
  done
done
echo
echo "raw runs (condition mode factorization state wall cpu): $raw"
