#!/usr/bin/env bash
# The die of cases3d/gmsh-die at every Gmsh size from 4 to 8 mm, subdivided into hexahedra
# (element = "hex8") and kept as tetrahedra (element = "tet4"): nodes, cells, the smallest scaled
# Jacobian at α⁰, and whether the state solves (docs/meshes.md, "Tetrahedra and triangles").
# The tetrahedra are also meshed finer (TET_SIZES), to the unknowns of the subdivided hexahedra.
# With OPTIMIZE=1 each tetrahedral size is also optimized (seconds to minutes per size).
#
#   bash bench/mesh/die_sizes.sh [build-dir]        # default ./build
#   OPTIMIZE=1 TET_SIZES="0.008 0.004 0.0025" bash bench/mesh/die_sizes.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
frictopt="$build/apps/frictopt/frictopt"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
echo "| element | size [m] | nodes | cells | smallest scaled Jacobian | unknowns | solve | contact P [N] | optimize: Θ, status, evaluations |"
echo "|---|---|---|---|---|---|---|---|---|"
hex_sizes="${HEX_SIZES:-0.004 0.005 0.006 0.007 0.008}"
tet_sizes="${TET_SIZES:-0.004 0.005 0.006 0.007 0.008 0.003 0.0025 0.002}"
for element in hex8 tet4; do
  sizes="$hex_sizes"
  [[ "$element" == tet4 ]] && sizes="$tet_sizes"
  for size in $sizes; do
    dir="$work/$element-$size"
    mkdir -p "$dir"
    sed -e "s|^file = .*|file = \"$root/cases3d/gmsh-die/die.geo\"\nelement = \"$element\"|" \
        -e "s|^size = .*|size = $size|" "$root/cases3d/gmsh-die/case.toml" > "$dir/case.toml"
    if out="$("$frictopt" solve "$dir/case.toml" -o "$dir/solve" 2>&1)"; then
      head="$(printf '%s\n' "$out" | head -1)"
      nodes="$(sed -E 's/.*body, ([0-9]+) nodes.*/\1/' <<<"$head")"
      cells="$(sed -E 's/.* ([0-9]+) elements.*/\1/' <<<"$head")"
      jac="$(sed -E 's/.*scaled Jacobian ([^ ]+) at.*/\1/' <<<"$head")"
      unknowns="$(sed -E 's/.*, ([0-9]+) unknowns.*/\1/' <<<"$head")"
      load="$(printf '%s\n' "$out" | sed -nE 's/^contact forces: P = ([^ ]+) N.*/\1/p')"
      opt="—"
      if [[ "${OPTIMIZE:-0}" == 1 && "$element" == tet4 ]]; then
        if "$frictopt" optimize "$dir/case.toml" -o "$dir/opt" > "$dir/opt.log" 2>&1; then
          theta="$(grep -oE '^Θ: [^;]*' "$dir/opt.log" | head -1 || true)"
          status="$(grep -oE 'BundleTrust: [a-z_]+ \([a-z_]+\)' "$dir/opt.log" | head -1 | cut -d' ' -f2- || true)"
          evaluations="$(grep -oE 'evaluations [0-9]+' "$dir/opt.log" | head -1 || true)"
          opt="$theta, $status, $evaluations"
        else
          opt="exit $? ($(tail -1 "$dir/opt.log"))"
        fi
      fi
      echo "| $element | $size | $nodes | $cells | $jac | $unknowns | yes | $load | $opt |"
    else
      reason="$(printf '%s\n' "$out" | grep -m1 -oE 'is (inverted|degenerate) for the mesh as read' || printf '%s\n' "$out" | head -1 | cut -c1-80)"
      echo "| $element | $size | | | | | refused: $reason | | — |"
    fi
  done
done
