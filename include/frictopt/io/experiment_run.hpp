// SPDX-License-Identifier: MIT
// The virtual tribometer as a run (`frictopt experiment`, Python `frictopt.experiment`): the
// study::Tribometer of a case's [experiment] table, its console lines, and with a run
// directory the files tribometer_ramp.csv, tribometer_polar.csv, tribometer_law.csv and
// summary.json (docs/experiments.md). One implementation for the CLI and the Python module.
#pragma once

#include <functional>
#include <string>

#include "frictopt/io/case_description.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/study/tribometer.hpp"

namespace frictopt::io {

struct ExperimentRunRequest {
  const CaseDescription& description;  ///< must hold an [experiment] table
  std::string case_name;               ///< in messages and summary.json's "case"
  /// Opens the run directory once the experiment is accepted (a refused case creates no
  /// directory); empty, or returning null: nothing written.
  std::function<RunDirectory*()> open_run;
  std::function<void(const std::string&)> report;  ///< console lines (may be empty)
};

struct ExperimentRunResult {
  study::Tribometer::Summary summary;
  JsonValue summary_json;  ///< summary.json's content (written when there is a run directory)
};

/// Runs the experiment. Throws InvalidInput for a case without [experiment] (naming the keys
/// the table needs) or an experiment the tribometer refuses; FileSystemError when a file cannot
/// be written. Non-convergence is the summary's status.
[[nodiscard]] ExperimentRunResult run_experiment(const ExperimentRunRequest& request);

/// The console line of one angle's result (what `frictopt experiment` prints per angle).
[[nodiscard]] std::string describe_angle(const study::TribometerAngleResult& angle, study::TribometerDrive drive);

}  // namespace frictopt::io
