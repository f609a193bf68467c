// SPDX-License-Identifier: MIT
#include "frictopt/io/program_run.hpp"

#include <fmt/format.h>

#include <optional>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

ProgramRunResult run_loading_program(const ProgramRunRequest& request) {
  const CaseDescription& description = request.description;
  const auto report = [&](const std::string& line) {
    if (request.report) request.report(line);
  };
  if (!description.program)
    throw InvalidInput(fmt::format("{}: no [[program.step]] tables; expected a loading program (docs/experiments.md)",
                                   request.case_name));
  study::ElasticBody body(description.body);
  study::LoadingProgram program(body, *description.program);
  RunDirectory* run = request.open_run ? request.open_run() : nullptr;
  const std::string name = body.definition().name;
  const bool vtk = run != nullptr && description.output.vtk;
  std::vector<std::string> notes;
  if (vtk) run->start_series(name, 0, notes);
  JsonValue steps = JsonValue::array();
  ProgramRunResult result;
  result.summary = program.run(body.definition().initial_design, [&](const study::LoadStepResult& r) {
    report(fmt::format("{} ({}): {}", r.label, r.step, r.state.summary.brief_report()));
    JsonValue step = solve_summary(request.case_name, body, r.state);
    step["command"] = "solve (loading program)";
    step["step"] = r.step;
    step["label"] = r.label;
    step["external_work"] = r.external_work;
    if (r.state.contact)
      report(fmt::format("  {}\n  {}", r.state.contact->summary.brief_report(), r.state.contact->resultants.brief_report()));
    steps.push_back(step);
    if (vtk && r.state.summary.status == Status::kConverged)
      run->add_to_series(r.step, [&](const std::filesystem::path& vtu) { write_state_vtu(vtu, body, r.state); });
  });
  report(result.summary.brief_report());
  JsonValue& json = result.summary_json = JsonValue::object();
  json["case"] = request.case_name;
  json["command"] = "solve";
  add_members(json, run_environment());
  add_members(json, to_json(result.summary));
  json["steps"] = steps;
  if (run) {
    run->write_json_file(RunDirectory::kSummary, json);
    if (vtk) result.series = run->file(name + ".pvd").string();
  }
  return result;
}

}  // namespace frictopt::io
