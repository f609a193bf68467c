#!/usr/bin/env bash
# Bundle-trust iterations of a large case with the PETSc engine
# (docs/scaling.md): cases3d/punch-anisotropic (4-gon, target-pressure cost) at a given grid,
# `frictopt optimize` with max_iterations = ITERATIONS and no VTK, under mpiexec on RANKS ranks.
# Prints one line: unknowns, contact nodes, iterations, evaluations (state solves), wall and CPU
# (all processes, GNU time) of the run, wall per evaluation, the last centre's state and
# subgradient seconds, max RSS of the largest process; the run's history.csv is kept in OUT.
#   bench/petsc/optimize.sh 2 88 88 20 10 /tmp/opt500k     # 499,023 unknowns, 7,921 contact nodes
# FRICTOPT_BIN overrides the binary (default build/apps/frictopt/frictopt).
set -euo pipefail
ranks="$1"; nx="$2"; ny="$3"; nz="$4"; iterations="$5"; out="$6"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${FRICTOPT_BIN:-$root/build/apps/frictopt/frictopt}"
mkdir -p "$out"
sed -e "s/cells = \[16, 16, 8\]/cells = [$nx, $ny, $nz]/" -e "s/^max_iterations = [0-9]*/max_iterations = $iterations/" \
    -e 's/^\[output\]/[output]\nvtk = false/' "$root/cases3d/punch-anisotropic/case.toml" > "$out/bench_case.toml"
printf '\n[solver]\nengine = "petsc"\n' >> "$out/bench_case.toml"
launch=(mpiexec -n "$ranks" --oversubscribe --allow-run-as-root --mca btl_vader_single_copy_mechanism none)
/usr/bin/time -f "%e %M %U %S" -o "$out/time" "${launch[@]}" "$bin" optimize "$out/bench_case.toml" -o "$out/run" --force \
  > "$out/log" 2>&1 || { cat "$out/log"; exit 1; }
read -r wall rss_kb user_s sys_s < "$out/time"
python3 - "$out/run/history.csv" "$out/run/summary.json" "$wall" "$(echo "$user_s + $sys_s" | bc)" "$((rss_kb / 1024))" \
  "$(( (nx + 1) * (ny + 1) * (nz + 1) * 3 ))" "$(( (nx + 1) * (ny + 1) ))" "$ranks" <<'PY'
import csv, json, sys
history, summary = list(csv.DictReader(open(sys.argv[1]))), json.load(open(sys.argv[2]))
wall, cpu, rss, unknowns, contact, ranks = sys.argv[3:9]
last = history[-1]
solves = int(last["state_solves"])
print(f"ranks={ranks} unknowns={unknowns} contact_nodes={contact} iterations={last['iteration']} "
      f"state_solves={solves} wall={float(wall):.0f}s cpu={float(cpu):.0f}s wall/evaluation={float(wall) / max(solves, 1):.1f}s "
      f"last centre: state={float(last['state_seconds']):.1f}s subgradient={float(last['subgradient_seconds']):.1f}s "
      f"Newton={last['coulomb_iterations']} Krylov={last['qp_iterations']} max_rss={rss}MB "
      f"theta {history[0]['theta']} -> {last['theta']} status={summary.get('status', '?')}")
PY
