#!/usr/bin/env bash
# The README's main job: set-up, build, then optimize the default 3D case (a punch pressed onto
# the foundation with anisotropic Coulomb friction — a 4-gon with coefficients 0.4/0.2 along the
# diagonals, thesis remark 6.2.1 — toward a uniform contact pressure), certify the result and
# write VTK series, history, summary, certificate and PNG pictures into ./demo-output.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
FRICTOPT_BUILD_TARGETS=frictopt bash "$root/scripts/build.sh"  # the CLI only; scripts/test.sh builds the rest in the same tree
build="${FRICTOPT_BUILD_DIR:-$root/build}"
out="${1:-$root/demo-output}"
case_file="$root/cases3d/punch-anisotropic/case.toml"
"$build/apps/frictopt/frictopt" optimize "$case_file" -o "$out" --force
"$build/apps/frictopt/frictopt" certify "$out"
bash "$root/viz/run_headless.sh" /usr/bin/python3 "$root/viz/render_run.py" "$out"
echo "demo: VTK series $out/*.pvd (open in ParaView), pictures in $out/pictures/, summary $out/summary.json"
