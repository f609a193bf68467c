#!/usr/bin/env bash
# The README's main job: set-up, build, then run the default 3D case and write VTK (and,
# when the viz scripts apply, PNG pictures) into ./demo-output.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
out="${1:-$root/demo-output}"
"$build/apps/frictopt/frictopt" solve "$root/cases3d/punch/case.toml" -o "$out"
if [ -f "$root/viz/render_vtu.py" ]; then
  bash "$root/viz/run_headless.sh" /usr/bin/python3 "$root/viz/render_vtu.py" "$out" || {
    echo "demo: picture rendering failed (VTK files are in $out)" >&2; exit 1; }
fi
echo "demo: outputs in $out"
