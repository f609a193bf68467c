// SPDX-License-Identifier: MIT
// `frictopt experiment` (the virtual tribometer) and `frictopt solve` of a case with a loading
// program: see apps/frictopt/commands.hpp and docs/experiments.md.
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "commands.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/experiment_run.hpp"
#include "frictopt/io/program_run.hpp"
#include "frictopt/io/run_directory.hpp"

namespace frictopt::app {

int run_program(const std::filesystem::path& case_path, const std::filesystem::path& out_dir,
                const io::CaseDescription& description) {
  std::optional<io::RunDirectory> run;
  io::ProgramRunRequest request{description, case_path.string(), {}, {}};
  request.open_run = [&] { return &run.emplace(out_dir, io::RunOpening::kOutput, case_path); };
  request.report = [](const std::string& line) { fmt::print("{}\n", line); };
  const io::ProgramRunResult result = io::run_loading_program(request);
  if (!result.series.empty()) fmt::print("wrote {}\n", result.series);
  return result.summary.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

int run_experiment(const std::filesystem::path& case_path, const std::filesystem::path& out_dir) {
  const io::CaseDescription description = io::load_case(case_path);
  std::optional<io::RunDirectory> run;
  io::ExperimentRunRequest request{description, case_path.string(), {}, {}};
  request.open_run = [&] { return &run.emplace(out_dir, io::RunOpening::kOutput, case_path); };
  request.report = [](const std::string& line) { fmt::print("{}\n", line); };
  const io::ExperimentRunResult result = io::run_experiment(request);
  return result.summary.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace frictopt::app
