// SPDX-License-Identifier: MIT
// `frictopt experiment` (the virtual tribometer) and `frictopt solve` of a case with a loading
// program: see apps/frictopt/commands.hpp and docs/experiments.md.
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "commands.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/experiment_run.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/loading_program.hpp"

namespace frictopt::app {

int run_program(const std::filesystem::path& case_path, const std::filesystem::path& out_dir,
                const io::CaseDescription& description) {
  study::ElasticBody body(description.body);
  study::LoadingProgram program(body, *description.program);
  io::RunDirectory run(out_dir, io::RunOpening::kOutput, case_path);
  const std::string name = body.definition().name;
  std::vector<std::string> notes;
  if (description.output.vtk) run.start_series(name, 0, notes);
  io::JsonValue steps = io::JsonValue::array();
  const study::LoadingProgram::Summary summary =
      program.run(body.definition().initial_design, [&](const study::LoadStepResult& r) {
        fmt::print("{} ({}): {}\n", r.label, r.step, r.state.summary.brief_report());
        io::JsonValue step = io::solve_summary(case_path.string(), body, r.state);
        step["command"] = "solve (loading program)";
        step["step"] = r.step;
        step["label"] = r.label;
        step["external_work"] = r.external_work;
        if (r.state.contact) {
          fmt::print("  {}\n  {}\n", r.state.contact->summary.brief_report(),
                     r.state.contact->resultants.brief_report());
        }
        steps.push_back(step);
        if (description.output.vtk && r.state.summary.status == Status::kConverged)
          run.add_to_series(r.step, [&](const std::filesystem::path& vtu) {
            io::write_state_vtu(vtu, body, r.state);
          });
      });
  fmt::print("{}\n", summary.brief_report());
  io::JsonValue json = io::JsonValue::object();
  json["case"] = case_path.string();
  json["command"] = "solve";
  io::add_members(json, io::run_environment());
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["steps_solved"] = summary.steps_solved;
  json["factorizations"] = summary.factorizations;
  json["factorization_seconds"] = summary.factorization_seconds;
  json["contact_seconds"] = summary.contact_seconds;
  json["time_seconds"] = summary.time_seconds;
  json["steps"] = steps;
  run.write_json_file(io::RunDirectory::kSummary, json);
  if (description.output.vtk) fmt::print("wrote {}\n", run.file(name + ".pvd").string());
  return summary.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
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
