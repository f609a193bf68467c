// SPDX-License-Identifier: MIT
// One optimization run in a run directory: what `frictopt optimize` does between parsing its
// arguments and printing, so that the command stays thin and another front end (a Python
// module, a batch driver) runs the same thing.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "frictopt/io/run_directory.hpp"
#include "frictopt/optim/bundle_trust.hpp"

namespace frictopt::io {

struct OptimizationRunResult {
  optim::BundleTrust::Summary summary;  ///< the method's (this process's counters)
  double initial_cost = kNaN;           ///< Θ(α⁰)
  double final_cost = kNaN;             ///< Θ at the final design
};

/// Runs the bundle trust method on the case of `run` (its case.toml, RunDirectory::store_case)
/// — or, when `run` was opened with kResume, continues it from its checkpoint after checking
/// the fingerprint — writing history.csv (one flushed row per outer iteration),
/// checkpoint.json (after each iteration: the method's whole state, the contact warm start,
/// counters, fingerprint), the VTK series, final_design.json and summary.json.
/// `report` receives each progress line (the header, one per iteration, the final report).
/// Throws InvalidInput for a case without [contact] or [cost], an initial design outside Υ or
/// a refused resume; NumericalFailure when a state the cost needs does not solve.
[[nodiscard]] OptimizationRunResult run_optimization(RunDirectory& run, const std::filesystem::path& case_path,
                                                     bool resume, const std::function<void(const std::string&)>& report);

}  // namespace frictopt::io
