// SPDX-License-Identifier: MIT
// The BLAS thread rule (docs/benchmarks.md, "BLAS threads on a shared machine"): one thread for
// small work and whenever no core is idle; never more threads than idle cores; fixed and user modes
// as documented.
#include "frictopt/linalg/blas_threads.hpp"

#include <gtest/gtest.h>
#include <sched.h>

namespace fl = frictopt::linalg;
using fl::BlasThreadMode;

TEST(BlasThreads, SmallWorkRunsOnOneThreadEvenOnAnIdleMachine) {
  EXPECT_EQ(fl::choose_blas_threads(0.99 * fl::kMinFlopsForThreads, 8, 8, BlasThreadMode::kAutomatic, 0), 1);
  EXPECT_EQ(fl::choose_blas_threads(0.0, 8, 8, BlasThreadMode::kAutomatic, 0), 1);
}

TEST(BlasThreads, LargeWorkUsesTheIdleCoresOnly) {
  const double big = 100 * fl::kMinFlopsForThreads;
  EXPECT_EQ(fl::choose_blas_threads(big, 2, 2, BlasThreadMode::kAutomatic, 0), 2);  // idle machine
  EXPECT_EQ(fl::choose_blas_threads(big, 2, 1, BlasThreadMode::kAutomatic, 0), 1);  // a build on core 2
  EXPECT_EQ(fl::choose_blas_threads(big, 2, 0, BlasThreadMode::kAutomatic, 0), 1);  // overloaded
  EXPECT_EQ(fl::choose_blas_threads(big, 4, 16, BlasThreadMode::kAutomatic, 0), 4); // never above the BLAS' max
  EXPECT_EQ(fl::choose_blas_threads(big, 2, -1, BlasThreadMode::kAutomatic, 0), 1); // load unknown
}

TEST(BlasThreads, FixedAndUserModes) {
  EXPECT_EQ(fl::choose_blas_threads(1.0, 8, 0, BlasThreadMode::kFixed, 3), 3);
  EXPECT_EQ(fl::choose_blas_threads(1.0, 2, 0, BlasThreadMode::kFixed, 3), 2);
  EXPECT_EQ(fl::choose_blas_threads(1.0, 8, 0, BlasThreadMode::kUser, 0), 8);
}

TEST(BlasThreads, IdleCoresAreBoundedByTheAffinityMask) {
  const int idle = fl::idle_cores_now();
  EXPECT_GE(idle, -1);
  cpu_set_t set;
  CPU_ZERO(&set);
  ASSERT_EQ(sched_getaffinity(0, sizeof(set), &set), 0);
  EXPECT_LE(idle, CPU_COUNT(&set));
}

TEST(BlasThreads, ACallSiteChoosesWithinTheLimits) {
  // Whatever the mode, a call site reports a count in [0, max]; small work runs on one thread
  // in the automatic mode.
  const fl::BlasThreadsForCall large(1e12);
  EXPECT_GE(large.threads(), 0);
  const fl::BlasThreadsForCall small(1.0);
  EXPECT_GE(small.threads(), 0);
  if (fl::blas_thread_mode() == BlasThreadMode::kAutomatic) {
    EXPECT_EQ(small.threads(), 1);
  }
  EXPECT_FALSE(fl::describe_blas_threads().empty());
}

// The BLAS behind CHOLMOD's supernodal factorization and the LAPACK wrappers is OpenBLAS, not
// the reference BLAS or ATLAS that another dependency may bring (cmake/FrictoptModule.cmake,
// docs/benchmarks.md "Which BLAS"): the loaded implementation names itself, and the symbols
// CHOLMOD and LAPACK call resolve into an OpenBLAS library file.
TEST(LoadedBlas, IsOpenBlas) {
  const fl::LoadedBlas blas = fl::loaded_blas();
  EXPECT_TRUE(blas.is_openblas()) << fl::describe_loaded_blas();
  EXPECT_EQ(blas.implementation.rfind("OpenBLAS", 0), 0U) << blas.implementation;
  for (const char* symbol : {"dgemm_", "dsyrk_", "dtrsm_", "dgemv_", "dpotrf_", "dgesdd_"}) {
    const std::string library = fl::library_of_symbol(symbol);
    EXPECT_NE(library.find("openblas"), std::string::npos) << symbol << " resolves to '" << library << "'";
  }
  EXPECT_NE(fl::describe_loaded_blas().find(blas.dgemm_library), std::string::npos);
}

TEST(LoadedBlas, AnUnknownSymbolResolvesNowhere) {
  EXPECT_EQ(fl::library_of_symbol("frictopt_no_such_blas_routine_"), "");
}
