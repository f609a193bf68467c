#!/usr/bin/env bash
# Scale bench of the PETSc engine (docs/scaling.md): one Coulomb state of the
# shipped punch (cases3d/punch: 16-gon, μ = 0.3) at a given grid, solved by `frictopt solve`
# with engine = "direct" or "petsc" on N ranks. Prints one line: engine, ranks, cells, unknowns,
# contact nodes, wall time, CPU time of all processes (robust to other load on the machine),
# max RSS of the largest process (GNU time), Newton/Krylov (petsc) or fixed-point/QP iterations.
#   bench/petsc/scale.sh petsc 2 110 110 26      # ≈ 1.0e6 unknowns, 12,321 contact nodes
#   bench/petsc/scale.sh direct 1 40 40 10       # ≈ 5.5e4 unknowns
# FRICTOPT_BIN overrides the binary (default build/apps/frictopt/frictopt); FRICTOPT_PETSC_OPTIONS
# becomes the case's petsc_options.
set -euo pipefail
engine="$1"; ranks="$2"; nx="$3"; ny="$4"; nz="$5"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
bin="${FRICTOPT_BIN:-$root/build/apps/frictopt/frictopt}"
work="$(mktemp -d "${TMPDIR:-/tmp}/frictopt-scale-XXXXXX")"
trap 'rm -rf "$work"' EXIT
sed "s/cells = \[24, 24, 12\]/cells = [$nx, $ny, $nz]/" "$root/cases3d/punch/case.toml" > "$work/case.toml"
printf '\n[output]\nvtk = false\n\n[solver]\nengine = "%s"\n' "$engine" >> "$work/case.toml"
if [ -n "${FRICTOPT_PETSC_OPTIONS:-}" ]; then printf 'petsc_options = "%s"\n' "$FRICTOPT_PETSC_OPTIONS" >> "$work/case.toml"; fi
if [ "$engine" = petsc ]; then
  launch=(mpiexec -n "$ranks" --oversubscribe --allow-run-as-root --mca btl_vader_single_copy_mechanism none)
else
  launch=()
fi
/usr/bin/time -f "%e %M %U %S" -o "$work/time" "${launch[@]}" "$bin" solve "$work/case.toml" -o "$work/out" > "$work/log" 2>&1 \
  || { cat "$work/log"; exit 1; }
read -r wall rss_kb user_s sys_s < "$work/time"
unknowns=$(( (nx + 1) * (ny + 1) * (nz + 1) * 3 ))
contact=$(( (nx + 1) * (ny + 1) ))
iters=$(grep -o '[0-9]* Newton / [0-9]* Krylov' "$work/log" || grep -o '[0-9]* fixed-point it, [0-9]* QP it' "$work/log" || true)
solve=$(grep -o 'solve [0-9.]* s' "$work/log" | tail -1)
echo "$engine ranks=$ranks cells=${nx}x${ny}x${nz} unknowns=$unknowns contact_nodes=$contact wall=${wall}s cpu=$(echo "$user_s + $sys_s" | bc)s max_rss=$((rss_kb / 1024))MB [$iters] [$solve]"
