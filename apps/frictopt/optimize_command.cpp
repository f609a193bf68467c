// SPDX-License-Identifier: MIT
// `frictopt optimize`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "frictopt/io/optimization_run.hpp"
#include "frictopt/io/run_directory.hpp"

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
  const Status status = result.summary.status;
  return status == Status::kConverged || status == Status::kMaxIterations ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
