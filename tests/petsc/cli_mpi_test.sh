#!/usr/bin/env bash
# `mpiexec -n N frictopt solve` with engine = "petsc" (docs/petsc-engine.md, "Use"): exit 0, rank 0's
# output directory holds the .vtu and summary.json, one progress block is printed (rank 0
# only), no scratch directory of the other ranks is left behind; an unknown PETSc option is
# exit 2 naming the option. Arguments: MPIEXEC FRICTOPT_BINARY SOURCE_DIR RANKS.
set -euo pipefail
mpiexec="$1"; bin="$2"; src="$3"; ranks="$4"
work="$(mktemp -d "${TMPDIR:-/tmp}/frictopt-cli-mpi-XXXXXX")"
trap 'rm -rf "$work"' EXIT
# A private TMPDIR for the ranks' scratch directories: the check that none is left behind must
# not see those of another test (or run) going on at the same time.
scratch="$work/tmp"
mkdir "$scratch"
launch=(env TMPDIR="$scratch" "$mpiexec" -n "$ranks" --oversubscribe --allow-run-as-root --mca btl_vader_single_copy_mechanism none)
sed 's/cells = \[24, 24, 12\]/cells = [8, 8, 4]/' "$src/cases3d/punch/case.toml" > "$work/case.toml"
printf '\n[solver]\nengine = "petsc"\n' >> "$work/case.toml"
"${launch[@]}" "$bin" solve "$work/case.toml" -o "$work/out" > "$work/log" 2>&1
test -s "$work/out/case.vtu" && test -s "$work/out/summary.json"
[ "$(grep -c '^elasticity: converged' "$work/log")" -eq 1 ] || { echo "expected one report (rank 0 only):"; cat "$work/log"; exit 1; }
grep -q "$ranks ranks" "$work/log" || { echo "the report does not name $ranks ranks:"; cat "$work/log"; exit 1; }
[ -z "$(ls -d "$scratch"/frictopt-rank-* 2>/dev/null)" ] || { echo "a rank's scratch directory was left behind"; exit 1; }
printf 'petsc_options = "-ksp_typo gmres"\n' >> "$work/case.toml"
set +e
"${launch[@]}" "$bin" solve "$work/case.toml" -o "$work/out2" > "$work/log2" 2>&1
code=$?
set -e
[ "$code" -eq 2 ] || { echo "unknown option: exit $code, expected 2"; cat "$work/log2"; exit 1; }
grep -q -- "-ksp_typo" "$work/log2" || { echo "the message does not name the option"; cat "$work/log2"; exit 1; }
echo "ok: $ranks ranks"
