#!/usr/bin/env bash
# `mpiexec -n N frictopt optimize --resume` with engine = "petsc" (docs/petsc-engine.md, "Use"): a run
# stopped after 1 bundle-trust iteration (its checkpoint) and resumed to 3 ends at the design
# and cost of an uninterrupted 3-iteration run, to the engine's tolerance (1e-6 relative: the
# Newton warm start is not part of the checkpoint, so the states agree to the solver tolerance
# rather than bit for bit); rank 0 alone writes the run directory; no rank's scratch directory
# is left behind. Arguments: MPIEXEC FRICTOPT_BINARY SOURCE_DIR RANKS.
set -euo pipefail
mpiexec="$1"; bin="$2"; src="$3"; ranks="$4"
work="$(mktemp -d "${TMPDIR:-/tmp}/frictopt-resume-mpi-XXXXXX")"
trap 'rm -rf "$work"' EXIT
# A private TMPDIR for the ranks' scratch directories: the check that none is left behind must
# not see those of another test (or run) going on at the same time.
scratch="$work/tmp"
mkdir "$scratch"
launch=(env TMPDIR="$scratch" "$mpiexec" -n "$ranks" --oversubscribe --allow-run-as-root --mca btl_vader_single_copy_mechanism none)
make_case() {  # $1: max_iterations
  sed -e 's/cells = \[16, 16, 8\]/cells = [8, 8, 4]/' -e "s/^max_iterations = [0-9]*/max_iterations = $1/" \
    "$src/cases3d/punch-anisotropic/case.toml"
  printf '\n[solver]\nengine = "petsc"\n'
}
make_case 3 > "$work/full.toml"
make_case 1 > "$work/part.toml"
"${launch[@]}" "$bin" optimize "$work/full.toml" -o "$work/a" > "$work/log_a" 2>&1 || { cat "$work/log_a"; exit 1; }
"${launch[@]}" "$bin" optimize "$work/part.toml" -o "$work/b" > "$work/log_b" 2>&1 || { cat "$work/log_b"; exit 1; }
grep -q '"iterations": 1' "$work/b/summary.json" || { echo "the first part did not stop at 1 iteration"; cat "$work/b/summary.json"; exit 1; }
sed -i 's/^max_iterations = 1/max_iterations = 3/' "$work/b/case.toml"
"${launch[@]}" "$bin" optimize "$work/b/case.toml" -o "$work/b" --resume > "$work/log_r" 2>&1 || { cat "$work/log_r"; exit 1; }
[ -z "$(ls -d "$scratch"/frictopt-rank-* 2>/dev/null)" ] || { echo "a rank's scratch directory was left behind"; exit 1; }
python3 - "$work/a/summary.json" "$work/b/summary.json" "$work/b/history.csv" <<'PY'
import json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["iterations"] == 3 and b["iterations"] == 3, (a["iterations"], b["iterations"])
cost = abs(a["final_cost"] - b["final_cost"]) / abs(a["final_cost"])
da = math.sqrt(sum((x - y) ** 2 for x, y in zip(a["alpha"], b["alpha"])))
na = math.sqrt(sum(x * x for x in a["alpha"]))
assert len(a["alpha"]) == len(b["alpha"])
assert cost <= 1e-6 and da <= 1e-6 * na, f"resumed run differs: cost {cost:.2e}, alpha {da / na:.2e}"
rows = [line.split(",")[0] for line in open(sys.argv[3]).read().split("\n")[1:] if line]
assert rows == ["1", "2", "3"], rows
print(f"resumed = uninterrupted: cost {cost:.2e}, alpha {da / na:.2e} relative")
PY
echo "ok: $ranks ranks"
