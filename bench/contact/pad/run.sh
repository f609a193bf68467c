#!/usr/bin/env bash
# The slip-heavy pad (docs/scaling.md, "Many slipping contact nodes") solved by each state engine
# and Coulomb method, one after the other, with a table of unknowns, contact nodes, slipping
# nodes, the factorization, the contact solve and the CPU time of the whole command.
#   bench/contact/pad/run.sh [BUILD_DIR] [SIZE]     (defaults: ./build, the case's 0.008 m)
#   PAD_VARIANTS="direct:semismooth_newton petsc:-" bench/contact/pad/run.sh   (a subset)
# CPU time (user + system) is the fair measure on a shared machine; the load average is printed.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../../../build}"
size="${2:-}"
frictopt="$build/apps/frictopt/frictopt"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$here/pad.geo" "$work/"
# PAD_VARIANTS="direct:automatic petsc:-" runs a subset.
read -r -a variants <<<"${PAD_VARIANTS:-direct:fixed_point direct:semismooth_newton direct:automatic petsc:-}"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-28s %9s %8s %6s %8s %10s %10s %8s\n' engine/method unknowns contact slip fact[s] contact[s] cpu[s] method
for v in "${variants[@]}"; do
  IFS=: read -r engine method <<<"$v"
  case_file="$work/case_${engine}_${method}.toml"
  if [ -n "$size" ]; then sed -e "s/^size = .*/size = $size/" "$here/case.toml" >"$case_file"; else cp "$here/case.toml" "$case_file"; fi
  { echo; echo "[solver]"; echo "engine = \"$engine\""
    if [ "$method" != "-" ]; then echo; echo "[solver.coulomb]"; echo "method = \"$method\""; fi; } >>"$case_file"
  out="$work/out_${engine}_${method}"
  if ! /usr/bin/time -f '%U %S' -o "$work/time" "$frictopt" solve "$case_file" -o "$out" >"$work/log" 2>&1; then
    printf '%-28s failed: %s\n' "$engine/$method" "$(tail -1 "$work/log")"
    continue
  fi
  python3 - "$out/summary.json" "$work/time" "$engine/$method" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
c = s["contact"]
user, system = map(float, open(sys.argv[2]).read().split())
print(f"{sys.argv[3]:<28} {s['num_unknowns']:>9} {c['num_contact_nodes']:>8} {c['num_slip']:>6} "
      f"{s.get('factorization_seconds', float('nan')):>8.2f} {c.get('time_seconds', float('nan')):>10.2f} "
      f"{user + system:>8.1f} {c.get('method_used', '?'):>8}")
PY
done
