// SPDX-License-Identifier: MIT
// A case's loading program as a run (`frictopt solve` of a case with [[program.step]] tables,
// Python `frictopt.solve_program`): the steps solved in order at the initial design, a console
// line per step, and with a run directory the VTK series of the steps and summary.json
// (docs/experiments.md). One implementation for the CLI and the Python module.
#pragma once

#include <functional>
#include <string>

#include "frictopt/io/case_description.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/study/loading_program.hpp"

namespace frictopt::io {

struct ProgramRunRequest {
  const CaseDescription& description;  ///< must hold [[program.step]] tables
  std::string case_name;               ///< in summary.json's "case"
  /// Opens the run directory once the program is accepted (a refused case creates no directory);
  /// empty, or returning null: nothing written.
  std::function<RunDirectory*()> open_run;
  std::function<void(const std::string&)> report;  ///< console lines (may be empty)
};

struct ProgramRunResult {
  study::LoadingProgram::Summary summary;
  JsonValue summary_json;  ///< summary.json's content (written when there is a run directory)
  std::string series;      ///< the .pvd file written (empty without VTK output or run directory)
};

/// Runs the program. Throws InvalidInput for a case without [[program.step]] tables or a program
/// that does not fit the body; FileSystemError when a file cannot be written. A step that does
/// not converge ends the run: the summary's status, not an exception.
[[nodiscard]] ProgramRunResult run_loading_program(const ProgramRunRequest& request);

}  // namespace frictopt::io
