#!/usr/bin/env bash
# The quick tests under AddressSanitizer and UndefinedBehaviorSanitizer, in a second
# build tree ./build-asan (-O1 -g1: the optimization AddressSanitizer's authors recommend, with
# line tables for the reports; it compiles about half as long as -O2 -g, which CI's time needs;
# -fno-sanitize-recover makes any undefined behaviour fail its test). CI runs it after
# scripts/test.sh.
#   scripts/test-sanitizers.sh            the quick tests (label quick, without the slow ones)
#   scripts/test-sanitizers.sh -R Cli     any ctest arguments pass through
# What is instrumented: the library and the command line, which every test here runs. The test
# programs' own code is compiled without the sanitizers (FRICTOPT_SANITIZE_TEST_CODE=OFF; the
# programs link the sanitizer runtimes): it is checks and calls, and a test unit took 2.7× its
# Release compile time instrumented. The programs labelled slow or end_to_end are not built (FRICTOPT_BUILD_SLOW_TESTS=OFF,
# FRICTOPT_BUILD_END_TO_END_TESTS=OFF): whole studies through the library or the command line
# took 2–10× their Release time here (the longest 6 min) and reach code the unit-level tests reach;
# they run in the Release suite. Measured on a clean clone: 38 min (build ~30, 639 tests 7.6).
# The Python module is not built here: an instrumented extension needs libasan preloaded into
# the (uninstrumented) interpreter, and LeakSanitizer would then report CPython's own
# allocations; the pytest suite runs in the normal build (scripts/test.sh). The PETSc engine is
# left out too (FRICTOPT_WITH_PETSC=OFF): OpenMPI's and PETSc's own allocations under
# LeakSanitizer are noise; its tests run in the normal build.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
build="${FRICTOPT_ASAN_BUILD_DIR:-$root/build-asan}"
jobs="${FRICTOPT_JOBS:-$(nproc)}"
# EIGEN_MALLOC_ALREADY_ALIGNED=1: Eigen turns "glibc malloc is 16-byte aligned" off under
# __SANITIZE_ADDRESS__ and then frees with its own aligned allocator what Debian's
# uninstrumented libceres allocated with malloc (Ceres' GradientChecker returns Eigen
# matrices): ASan reported a heap-buffer-overflow in handmade_aligned_free. glibc's malloc
# is 16-byte aligned on x86-64, which is all Eigen needs without -march (RelWithDebInfo).
# Warnings are not errors here: GCC's manual warns that the sanitizers raise the rate of false
# -Wmaybe-uninitialized reports and advises against combining them with -Werror (GCC 12 reported
# an Eigen vector inside a std::optional as maybe uninitialized in this build only). The Release
# build of scripts/test.sh, which CI runs first, keeps warnings as errors.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DFRICTOPT_SANITIZE="address;undefined" \
  -DCMAKE_CXX_FLAGS="-fno-sanitize-recover=all -DEIGEN_MALLOC_ALREADY_ALIGNED=1" -DFRICTOPT_WARNINGS_AS_ERRORS=OFF \
  -DFRICTOPT_BUILD_BENCHMARKS=OFF -DFRICTOPT_BUILD_PYTHON=OFF -DFRICTOPT_WITH_PETSC=OFF \
  -DFRICTOPT_BUILD_SLOW_TESTS=OFF -DFRICTOPT_BUILD_END_TO_END_TESTS=OFF -DFRICTOPT_SANITIZE_TEST_CODE=OFF >/dev/null
cmake --build "$build" -j "$jobs"
export ASAN_OPTIONS="${ASAN_OPTIONS:-abort_on_error=1:detect_leaks=1:strict_string_checks=1}"
# Leaks inside Gmsh/OpenCASCADE (not frictopt's) are suppressed by name (the file says why).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/scripts/lsan-suppressions.txt:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
cd "$build"
# The install test (a consumer project configured and built against the installed package) checks
# packaging, not memory: the Release suite runs it. So does a resumed run repeated bit for bit
# (61 s here, 10x its Release time): the shorter run-file tests resume through the same code.
heavy='^RunFiles\.AResumeAcrossTheAggregateAndThePiecesCutsRepeatsTheRunBitForBit$'
if [ "$#" -eq 0 ]; then set -- -L quick -LE "slow|viz|install|end_to_end" -E "$heavy"; fi
ctest --output-on-failure -j "$jobs" "$@"
