#!/usr/bin/env bash
# Wall times of the study cases end to end (`frictopt optimize`, then `frictopt certify`), with
# medians over repeated runs, and the costs, iterations and evaluations of the last run.
#
#   bench/studies/run_studies.sh [--binary PATH] [--repeat N] [--repeat-3d N] [--out DIR]
#                                [--cases "cases2d/ex521-target-pressure ..."] [--large]
#
# Defaults: the 2D thesis cases 3 times each, the 3D demo (cases3d/punch-anisotropic) and the
# other 3D studies once each. --large adds cases3d/punch-large (about 100k unknowns; tens of
# minutes: run it under nohup). Targets (docs/studies.md §3): each 2D thesis case < 5 s, the 3D demo
# < 2 min, punch-large < 30 min on 2 cores.
#
# Besides the wall time the table shows the CPU time (user + sys) of the optimize run: on a shared
# machine the wall time includes waiting for the CPU, the CPU time does not (frictopt runs one
# thread unless the BLAS behind CHOLMOD starts more). The load average at the start is printed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
binary="$root/build/apps/frictopt/frictopt"
repeat=3
repeat3d=1
out="${TMPDIR:-/tmp}/frictopt-studies"
cases2d="cases2d/ex521-target-pressure cases2d/ex522-force-power cases2d/ex523-compliance"
cases3d="cases3d/punch-anisotropic cases3d/punch-target-pressure cases3d/punch-elliptic cases3d/punch-compliance cases3d/punch-traction-uniformity"
custom=""
large=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --repeat) repeat="$2"; shift 2 ;;
    --repeat-3d) repeat3d="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --cases) custom="$2"; shift 2 ;;
    --large) large=1; shift ;;
    -h|--help) sed -n 2,17p "$0"; exit 0 ;;
    *) echo "unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -x "$binary" ]] || { echo "no frictopt binary at $binary (build it or pass --binary)" >&2; exit 2; }
mkdir -p "$out"
cd "$root"

runs=()
if [[ -n "$custom" ]]; then
  for c in $custom; do runs+=("$c:$repeat"); done
else
  for c in $cases2d; do runs+=("$c:$repeat"); done
  for c in $cases3d; do runs+=("$c:$repeat3d"); done
  [[ $large == 1 ]] && runs+=("cases3d/punch-large:1")
fi

echo "frictopt studies benchmark: $(date -u +%FT%TZ), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "binary: $binary ($(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'))"
table="$out/table.txt"
printf '%-32s %4s %10s %10s %9s %9s %13s %13s %6s %6s %-16s %10s %s\n' case runs "wall med" "wall min" "cpu med" certify \
  "J initial" "J final" iters evals status "Clarke rel" "weak/|L|" | tee "$table"
for entry in "${runs[@]}"; do
  case_dir="${entry%%:*}"; n="${entry##*:}"
  name="$(basename "$case_dir")"
  walls=(); cpus=()
  for ((k = 1; k <= n; ++k)); do
    run_dir="$out/$name"
    tfile="$out/$name.time"
    /usr/bin/time -f "%e %U %S" -o "$tfile" "$binary" optimize "$case_dir/case.toml" -o "$run_dir" --force \
      > "$out/$name.log" 2>&1 || echo "  ($name: optimize exit code $?, see $out/$name.log)" >&2
    read -r wall user sys < <(tail -1 "$tfile")
    walls+=("$wall"); cpus+=("$(python3 -c "print($user + $sys)")")
  done
  cert_wall="-"
  if "$binary" certify --help > /dev/null 2>&1; then
    /usr/bin/time -f "%e" -o "$out/$name.certify.time" "$binary" certify "$run_dir" > "$out/$name.certify.log" 2>&1 \
      || echo "  ($name: certify exit code $?, see $out/$name.certify.log)" >&2
    cert_wall="$(tail -1 "$out/$name.certify.time")"
  fi
  python3 - "$run_dir" "$name" "$cert_wall" "${walls[*]}" "${cpus[*]}" <<'PY' | tee -a "$table"
import json, os, statistics, sys
run_dir, name, cert_wall, walls, cpus = sys.argv[1:6]
walls = [float(w) for w in walls.split()]
cpus = [float(c) for c in cpus.split()]
s = json.load(open(os.path.join(run_dir, "summary.json")))
rel, weak = "-", "-"
cert = os.path.join(run_dir, "certificate.json")
if os.path.exists(cert):
    c = json.load(open(cert))
    clarke = c.get("clarke", {})
    if "relative_distance" in clarke:
        rel = f"{clarke['relative_distance']:.2e}"
    weak = f"{c.get('cardinality_L', '-')}"
print(f"{name:<32} {len(walls):>4} {statistics.median(walls):>9.2f}s {min(walls):>9.2f}s {statistics.median(cpus):>8.2f}s "
      f"{cert_wall:>8}s {s['initial_cost']:>13.5e} {s['final_cost']:>13.5e} {s['iterations']:>6} {s['evaluations']:>6} "
      f"{s['status']:<16} {rel:>10} {weak}")
PY
done
echo "table: $table; run directories, logs and certificates under $out"
