#!/usr/bin/env bash
# The README's main job: set-up, build, then optimize the default 3D case (a punch pressed onto
# the foundation with isotropic Coulomb friction, target uniform contact pressure) and write
# VTK series, history, summary and PNG pictures into ./demo-output (or the directory given).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
out="${1:-$root/demo-output}"
case_file="$root/cases3d/punch-target-pressure/case.toml"
"$build/apps/frictopt/frictopt" optimize "$case_file" -o "$out" --force
"$build/apps/frictopt/frictopt" certify "$out"
bash "$root/viz/run_headless.sh" /usr/bin/python3 "$root/viz/render_run.py" "$out"
echo "demo: VTK series $out/*.pvd (open in ParaView), pictures in $out/pictures/, summary $out/summary.json"
