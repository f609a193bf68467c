#!/usr/bin/env bash
# Installs the Debian packages (scripts/install-deps.sh) and builds frictopt in ./build
# (Release, -O2 -march=x86-64-v2). Extra arguments go to the CMake configure step.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
jobs="${FRICTOPT_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j "$jobs"
# `import frictopt` for Debian's python3 without PYTHONPATH (a .pth naming $build/python; docs/python.md).
if grep -q '^FRICTOPT_BUILD_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then cmake --build "$build" --target python_user_path; fi
