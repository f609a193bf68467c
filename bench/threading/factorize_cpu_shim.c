// SPDX-License-Identifier: MIT
// LD_PRELOAD shim: the CPU and wall time of CHOLMOD's numeric factorizations (cholmod_factorize)
// in any process — the frictopt CLI, a benchmark, an older build — printed to stderr per call
// and at exit:
//   factorize_cpu_shim: call K: cpu CPU s, wall WALL s
//   factorize_cpu_shim: CALLS call(s), cpu CPU s, wall WALL s
// Build and use (bench/threading/run_blas_check.sh does both):
//   gcc -O2 -shared -fPIC -o /tmp/factorize_cpu_shim.so bench/threading/factorize_cpu_shim.c -ldl
//   LD_PRELOAD=/tmp/factorize_cpu_shim.so build/apps/frictopt/frictopt solve CASE -o OUT
// CPU time is the process's (CLOCK_PROCESS_CPUTIME_ID): with one BLAS thread
// (FRICTOPT_BLAS_THREADS=1) it is the factorization's own, whatever else the machine runs.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <time.h>

typedef int (*factorize_fn)(void*, void*, void*);

static double cpu_total, wall_total;
static long calls;

static double seconds(clockid_t clock) {
  struct timespec t;
  clock_gettime(clock, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int cholmod_factorize(void* A, void* L, void* common) {
  static factorize_fn real;
  if (!real) real = (factorize_fn)dlsym(RTLD_NEXT, "cholmod_factorize");
  const double c0 = seconds(CLOCK_PROCESS_CPUTIME_ID), w0 = seconds(CLOCK_MONOTONIC);
  const int ok = real(A, L, common);
  const double cpu = seconds(CLOCK_PROCESS_CPUTIME_ID) - c0, wall = seconds(CLOCK_MONOTONIC) - w0;
  cpu_total += cpu;
  wall_total += wall;
  ++calls;
  fprintf(stderr, "factorize_cpu_shim: call %ld: cpu %.3f s, wall %.3f s\n", calls, cpu, wall);
  return ok;
}

__attribute__((destructor)) static void report(void) {
  if (calls > 0)
    fprintf(stderr, "factorize_cpu_shim: %ld call(s), cpu %.3f s, wall %.3f s\n", calls, cpu_total, wall_total);
}
