#!/usr/bin/env bash
# Installs the Debian packages (scripts/install-deps.sh) and builds frictopt in ./build
# (Release, -O2 -march=x86-64-v2, warnings as errors). Extra arguments go to the CMake configure
# step. FRICTOPT_BUILD_TARGETS="a b" builds only those targets (scripts/demo.sh: the CLI alone).
#
# Every entry point configures ./build with the same options, so that scripts/demo.sh and
# scripts/test.sh share one build tree: the second command compiles only what the first did not
# (a different -Werror setting would change every compile line and rebuild everything).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
jobs="${FRICTOPT_JOBS:-$(nproc)}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DFRICTOPT_WARNINGS_AS_ERRORS="${FRICTOPT_WARNINGS_AS_ERRORS:-ON}" "$@" >/dev/null
if [ -n "${FRICTOPT_BUILD_TARGETS:-}" ]; then
  # shellcheck disable=SC2086
  cmake --build "$build" -j "$jobs" --target ${FRICTOPT_BUILD_TARGETS}
  exit 0
fi
cmake --build "$build" -j "$jobs"
# `import frictopt` for Debian's python3 without PYTHONPATH (a .pth naming $build/python; docs/python.md).
if grep -q '^FRICTOPT_BUILD_PYTHON:BOOL=ON' "$build/CMakeCache.txt"; then cmake --build "$build" --target python_user_path; fi
