#!/usr/bin/env bash
# The README's test command: set-up, build (warnings as errors) and the whole test suite.
#   scripts/test.sh            all tests
#   scripts/test.sh -LE slow   the quick loop (any ctest arguments pass through)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
build="${FRICTOPT_BUILD_DIR:-$root/build}"
cd "$build"
ctest --output-on-failure -j "${FRICTOPT_JOBS:-$(nproc)}" "$@"
