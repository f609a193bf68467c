#!/usr/bin/env bash
# Regenerates pad.step from pad-cad.geo with Gmsh's OpenCASCADE kernel (the STEP file is kept in
# the repository so that the case runs without this step; run it after editing pad-cad.geo).
set -euo pipefail
cd "$(dirname "$0")"
gmsh -0 pad-cad.geo -o pad.step -format step > /dev/null
echo "wrote $(pwd)/pad.step"
