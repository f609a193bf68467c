// SPDX-License-Identifier: MIT
// One optimization run, optionally in a run directory: what `frictopt optimize` and the Python
// module's frictopt.optimize do between parsing their inputs and presenting the result, so that
// both front ends stay thin and write the same files, columns and summary.json.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/io/case_description.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/study/shape_optimization.hpp"

namespace frictopt::io {

/// The columns of history.csv, one row per outer iteration (also the fields of the progress
/// object the Python module gives its callbacks).
const std::vector<std::string>& optimization_history_columns();

/// What to run and where. The front end parses the case (and on a resume reads the run
/// directory's copy of it); run_optimization does everything else.
struct OptimizationRunRequest {
  CaseDescription description;
  /// How messages and summary.json name the case (the CLI: the run directory's copy).
  std::string case_name;
  /// Null: no files (the Python module without a run_directory); else history.csv,
  /// checkpoint.json, the VTK series, final_design.json and summary.json are written there.
  RunDirectory* run = nullptr;
  /// Continue from the run directory's checkpoint (needs `run`) after checking the fingerprint.
  bool resume = false;
  /// The method's options; empty: the case's [optimization] table.
  std::optional<optim::BundleTrust::Options> options;
  /// Receives each progress line (the header, one per iteration, the final report); may be empty.
  std::function<void(const std::string&)> report;
  /// Called after each outer iteration once its history row and checkpoint are written, with
  /// the row (optimization_history_columns()) and the progress; kStop ends the run cleanly.
  std::function<CallbackResult(const std::vector<CsvValue>& history_row, const study::OptimizationProgress&)>
      on_iteration;
};

struct OptimizationRunResult {
  optim::BundleTrust::Summary summary;  ///< the method's (this process's counters)
  study::OptimizationOutcome outcome;   ///< certified / limit reached / needs attention / failed
  double initial_cost = kNaN;           ///< Θ(α⁰)
  double final_cost = kNaN;             ///< Θ at the final design
  JsonValue summary_json;               ///< summary.json's content (written when there is a run directory)
  std::vector<std::string> notes;       ///< what the run directory reported on opening the series/history
  /// The final design carries another load than the initial one (study::load_change_warnings);
  /// printed as "warning: ..." and in summary.json's "warnings". They do not change the outcome.
  std::vector<std::string> warnings;
};

/// Runs the bundle trust method on the request's case — or, with `resume`, continues the run
/// of `run` from its checkpoint — writing (with a run directory) history.csv (one flushed row per
/// outer iteration), checkpoint.json (after each iteration: the method's whole state, the
/// contact warm start, counters, fingerprint), the VTK series, final_design.json and summary.json.
/// Throws InvalidInput for a case without [contact] or [cost], an initial design outside Υ, a
/// resume without a run directory or a refused resume; NumericalFailure when a state the cost
/// needs does not solve.
[[nodiscard]] OptimizationRunResult run_optimization(const OptimizationRunRequest& request);

/// The CLI's form: the case is the file `case_path` (the run directory's copy), named after the
/// user's argument in messages.
[[nodiscard]] OptimizationRunResult run_optimization(RunDirectory& run, const std::filesystem::path& case_path,
                                                     bool resume, const std::function<void(const std::string&)>& report);

}  // namespace frictopt::io
