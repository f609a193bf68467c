// SPDX-License-Identifier: MIT
// `frictopt optimize`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include "frictopt/core/error.hpp"
#include "frictopt/io/file_error.hpp"
#include "frictopt/io/optimization_run.hpp"
#include "frictopt/io/run_directory.hpp"
#ifdef FRICTOPT_HAVE_PETSC
#include "frictopt/petsc/petsc_session.hpp"
#endif

namespace frictopt::app {

// frictopt optimize: the bundle trust method on Θ over Υ in a run directory (io::RunDirectory,
// io::run_optimization): history.csv, checkpoint.json and a VTK series as the run goes; an
// interrupted run loses at most the current iteration and continues with --resume, repeating
// the uninterrupted run bit for bit; --force replaces a run of frictopt's files only.
int run_optimize(const std::filesystem::path& case_argument, const std::filesystem::path& out_dir, bool resume,
                 bool force) {
  const io::RunOpening opening = resume ? io::RunOpening::kResume
                                 : force ? io::RunOpening::kForce
                                         : io::RunOpening::kNewRun;
  io::RunDirectory run(out_dir, opening, case_argument);
  const std::filesystem::path case_path = run.store_case();
  const io::OptimizationRunResult result = io::run_optimization(run, case_path, resume, [](const std::string& line) {
    fmt::print("{}\n", line);
    std::fflush(stdout);
  });
  fmt::print("Θ: {:.6e} -> {:.6e}; outputs in {}\n", result.initial_cost, result.final_cost, out_dir.string());
  // Exit codes (README): 0 certified or at the case's iteration limit, 6 a written result that
  // needs attention (not certified, or no contact at the final design), 3 a failure.
  switch (result.outcome.kind) {
    case study::OptimizationOutcome::Kind::kCertified:
    case study::OptimizationOutcome::Kind::kLimitReached: return kExitOk;
    case study::OptimizationOutcome::Kind::kNeedsAttention:
      for (const std::string& reason : result.outcome.attention) fmt::print("attention: {}\n", reason);
      fmt::print("the result is written ({}) but needs attention before it is used (exit {})\n",
                 out_dir.string(), kExitNeedsAttention);
      return kExitNeedsAttention;
    case study::OptimizationOutcome::Kind::kFailed: break;
  }
  return kExitNumericalFailure;
}

#ifdef FRICTOPT_HAVE_PETSC
void mirror_run_for_resume(const std::filesystem::path& out_dir) {
  const bool root = petsc::PetscSession::launcher_rank() == 0;
  if (!root) std::filesystem::create_directories(out_dir);
  for (const std::string_view name : {io::RunDirectory::kCaseCopy, io::RunDirectory::kCheckpoint, io::RunDirectory::kHistory}) {
    // "1" + content for a file rank 0 has, "0" for one it has not (the other ranks then lack it
    // too, and refuse the resume as rank 0 does).
    std::string message = "0";
    if (root) {
      std::ifstream in(out_dir / name, std::ios::binary);
      if (in) message = "1" + std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    petsc::PetscSession::broadcast_from_rank0(message);
    if (!root && message[0] == '1') {
      std::ofstream out(out_dir / name, std::ios::binary);
      out << std::string_view(message).substr(1);
      if (!out)
        throw io::FileSystemError(fmt::format("{}: could not write a rank's copy of {}", (out_dir / name).string(), name),
                                  out_dir / name, errno);
    }
  }
}
#endif

}  // namespace frictopt::app
