// SPDX-License-Identifier: MIT
// How many threads the BLAS behind CHOLMOD and the dense kernels may use, chosen per call from
// the size of the work and the cores other processes leave idle
// (docs/benchmarks.md, "BLAS threads on a shared machine"). OpenBLAS' pthread workers spin while
// they wait; with another process on the second core a threaded call waited for a descheduled
// worker, and the demo's factorization took 2.0 s with two threads against 0.23 s with one.
#pragma once

#include <string>

namespace frictopt::linalg {

/// Where the thread count comes from.
enum class BlasThreadMode {
  kAutomatic,  ///< per call: 1 below kMinFlopsForThreads, else the cores other processes leave idle
  kFixed,      ///< FRICTOPT_BLAS_THREADS = N: always N (capped at the BLAS' own maximum)
  kUser,       ///< OPENBLAS_NUM_THREADS / OMP_NUM_THREADS set: the BLAS' own setting, never changed
  kUnavailable ///< the BLAS has no thread control (reference BLAS, ATLAS): nothing to choose
};

/// Work (flops) below which a call runs on one thread even on an idle machine: a parallel
/// region costs tens of µs when the cores are free and up to a scheduler time slice when one is
/// not, while 2e8 flops take ~50 ms on one core (measured in docs/benchmarks.md).
inline constexpr double kMinFlopsForThreads = 2e8;

/// The pure rule: threads for a call of `flops` work, with at most `max_threads` (the BLAS'
/// count at start-up, normally the cores), `idle_cores` cores not used by other processes,
/// mode and, for kFixed, `fixed_threads`. Always in [1, max_threads].
[[nodiscard]] int choose_blas_threads(double flops, int max_threads, int idle_cores, BlasThreadMode mode,
                                      int fixed_threads);

/// Cores usable by this process (affinity mask) minus the runnable threads of other processes
/// (/proc/stat procs_running minus this process' running threads), at least 0. -1 if /proc is
/// not readable.
[[nodiscard]] int idle_cores_now();

/// The mode read once from the environment: FRICTOPT_BLAS_THREADS ("auto" or an integer >= 1;
/// anything else throws InvalidInput naming the variable, value and expectation), else kUser if
/// OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS or OMP_NUM_THREADS is set, else kAutomatic.
[[nodiscard]] BlasThreadMode blas_thread_mode();

/// One line for logs and benchmarks: "BLAS threads: automatic (max 2)" etc.
[[nodiscard]] std::string describe_blas_threads();

/// The BLAS this process (or this module, inside a host that loaded it) actually calls: the
/// library the dynamic linker binds a BLAS/LAPACK symbol to is the one CHOLMOD's and LAPACK's
/// calls reach, which need not be the one the alternatives name (a dependency such as Ceres may
/// bring ATLAS ahead of it; cmake/FrictoptModule.cmake links OpenBLAS first for that reason).
struct LoadedBlas {
  std::string implementation;  ///< openblas_get_config(), e.g. "OpenBLAS 0.3.21 DYNAMIC_ARCH ..."; else "unknown"
  std::string dgemm_library;   ///< the file dgemm_ resolves to (dladdr, links resolved), "" if it does not resolve
  /// The implementation reports OpenBLAS and dgemm_ resolves into an OpenBLAS library file.
  [[nodiscard]] bool is_openblas() const;
};

/// Looks the BLAS up as above (dlsym from this library's own scope, then dladdr).
[[nodiscard]] LoadedBlas loaded_blas();

/// The file a BLAS/LAPACK symbol (e.g. "dsyrk_", "dpotrf_") resolves to in this process, with
/// symbolic links (Debian's alternatives) resolved; "" if it does not resolve.
[[nodiscard]] std::string library_of_symbol(const char* symbol);

/// One line for logs, `frictopt --version` and summaries: "OpenBLAS 0.3.21 ... (dgemm_ from
/// /usr/lib/.../libopenblasp-r0.3.21.so)".
[[nodiscard]] std::string describe_loaded_blas();

/// Sets the BLAS thread count for the BLAS call that follows, from the rule above, when it
/// differs from the current one. The count is not restored afterwards (each change wakes
/// OpenBLAS' spinning workers): it stays until the next call site chooses. Every BLAS/LAPACK
/// call in src/linalg is preceded by one. A no-op in modes kUser and kUnavailable. Not
/// thread-safe: the count is process-wide (frictopt calls the BLAS from one thread).
class BlasThreadsForCall {
 public:
  explicit BlasThreadsForCall(double flops);
  /// Threads chosen for the call (0 when the count is not ours to set).
  [[nodiscard]] int threads() const { return threads_; }

 private:
  int threads_ = 0;
};

}  // namespace frictopt::linalg
