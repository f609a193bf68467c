// SPDX-License-Identifier: MIT
// `frictopt optimize`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>
#include <iostream>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/pvd_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// frictopt optimize: the bundle trust method on Θ over Υ. Writes, as it goes, history.csv (one
// row per outer iteration, flushed), checkpoint.json (the method's state, atomically replaced)
// and a VTK series; an interrupted run loses at most the current iteration and continues with
// --resume. The case is copied into the run directory so a resumed run solves the same problem.
int run_optimize(const std::filesystem::path& case_argument, const std::filesystem::path& out_dir, bool resume,
                 bool force) {
  using namespace frictopt;
  namespace fs = std::filesystem;
  const fs::path case_copy = out_dir / "case.toml";
  const fs::path checkpoint_path = out_dir / "checkpoint.json";
  const bool existing_run = fs::exists(checkpoint_path) || fs::exists(out_dir / "history.csv");
  if (resume && !existing_run)
    throw InvalidInput(fmt::format("--resume: {} holds no run to resume (no checkpoint.json)", out_dir.string()));
  if (!resume && existing_run && !force)
    throw InvalidInput(fmt::format("{} already holds a run; pass --resume to continue it or --force to replace it",
                                   out_dir.string()));
  if (!resume && force && existing_run)
    for (const auto& entry : fs::directory_iterator(out_dir)) fs::remove_all(entry.path());
  fs::create_directories(out_dir);
  if (!resume) fs::copy_file(case_argument, case_copy, fs::copy_options::overwrite_existing);
  const fs::path case_path = resume ? case_copy : case_argument;

  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition& definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": optimize needs a [contact] table");
  study::ElasticBody body(definition);
  const std::string violation = body.admissible_set().describe_violation(definition.initial_design, 1e-9);
  if (!violation.empty())
    throw InvalidInput(fmt::format("{}: the initial design is outside the admissible set: {}", case_path.string(), violation));
  study::ShapeOracle oracle(body, description.required_cost());

  optim::BundleTrust::Options options = description.optimization;

  const std::string name = definition.name;
  const int every = description.output.every;
  std::vector<io::PvdEntry> series;
  if (resume)  // rebuild the series from the files already written
    for (const auto& entry : fs::directory_iterator(out_dir)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind(name + "_iter", 0) == 0 && entry.path().extension() == ".vtu")
        series.push_back({std::stod(file.substr(name.size() + 5, 4)), entry.path().filename()});
    }
  std::sort(series.begin(), series.end(), [](const auto& a, const auto& b) { return a.time < b.time; });
  const auto write_design_vtu = [&](int iteration, const Eigen::VectorXd& alpha) {
    if (!description.output.vtk) return;
    const fs::path file = fmt::format("{}_iter{:04d}.vtu", name, iteration);
    // The oracle's recent states: the iterate was solved by the method, no state solve here.
    io::write_state_vtu(out_dir / file, body, oracle.state(alpha));
    series.push_back({static_cast<double>(iteration), file});
    io::write_pvd(out_dir / (name + ".pvd"), series);
  };

  // A resumed run continues the counters of the interrupted one (elapsed time, state solves),
  // read from the last row of its history.
  double elapsed_offset = 0.0;
  std::int64_t solves_offset = 0;
  if (resume) {
    std::ifstream previous(out_dir / "history.csv");
    std::string line, header, last;
    std::getline(previous, header);
    while (std::getline(previous, line))
      if (!line.empty()) last = line;
    const auto split = [](const std::string& text) {
      std::vector<std::string> fields;
      std::stringstream stream(text);
      for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
      return fields;
    };
    const std::vector<std::string> names = split(header), values = split(last);
    for (std::size_t k = 0; k < names.size() && k < values.size(); ++k) {
      if (names[k] == "elapsed_seconds") elapsed_offset = std::stod(values[k]);
      if (names[k] == "state_solves") solves_offset = std::stoll(values[k]);
    }
  }
  io::CsvWriter history(out_dir / "history.csv",
                        {"iteration", "evaluations", "step", "theta", "t", "stationarity_relative", "aggregate_error_relative",
                         "bundle_size", "serious_steps", "null_steps", "state_solves", "coulomb_iterations",
                         "qp_iterations", "weak_nodes", "state_seconds", "subgradient_seconds", "elapsed_seconds"},
                        resume ? io::CsvWriter::Mode::kAppend : io::CsvWriter::Mode::kTruncate);
  fmt::print("{}: {} design variables, {} contact nodes, cost {}, {} of Υ\n", case_path.string(),
             definition.shape.num_controls(), body.contact_boundary()->num_nodes(), oracle.cost().name(),
             fmt::format("{} inequalities and {} equalities", body.admissible_set().A_in.rows(),
                         body.admissible_set().A_eq.rows()));
  // The method minimizes Θ/|Θ(α⁰)| (study defaults): its stationarity measure ‖z + ω‖ and
  // aggregate error are relative to |Θ(α⁰)| per unit of α; summary.json also gives them in Θ's units.
  fmt::print("{:>5} {:>6} {:>14} {:>14} {:>10} {:>12} {:>8} {:>9}\n", "iter", "evals", "theta", "step", "t",
             "stat. (rel)", "QP its", "elapsed");
  const auto on_progress = [&](const study::OptimizationProgress& p) {
    const auto& m = p.method;
    history.write_row({static_cast<std::int64_t>(m.iteration), static_cast<std::int64_t>(m.evaluations),
                       std::string(optim::to_string(m.step)), m.f, m.t, m.stationarity, m.aggregate_error,
                       static_cast<std::int64_t>(m.bundle.size()), static_cast<std::int64_t>(m.serious_steps),
                       static_cast<std::int64_t>(m.null_steps), solves_offset + static_cast<std::int64_t>(p.state_solves),
                       static_cast<std::int64_t>(p.center.contact.iterations),
                       static_cast<std::int64_t>(p.center.contact.qp_iterations),
                       static_cast<std::int64_t>(p.center.index_sets.num_weak_nodes()), p.center.state_seconds,
                       p.center.subgradient_seconds, elapsed_offset + p.elapsed_seconds});
    io::write_json(checkpoint_path, io::checkpoint_to_json(m));
    fmt::print("{:>5} {:>6} {:>14.6e} {:>14} {:>10.3e} {:>12.3e} {:>8} {:>8.1f}s\n", m.iteration, m.evaluations, m.f,
               optim::to_string(m.step), m.t, m.stationarity, p.center.contact.qp_iterations,
               elapsed_offset + p.elapsed_seconds);
    std::fflush(stdout);
    if (m.iteration % every == 0) write_design_vtu(m.iteration, m.x);
    return CallbackResult::kContinue;
  };

  optim::BundleTrust::IterationSummary checkpoint;
  if (resume) {
    checkpoint = io::read_checkpoint(checkpoint_path);
    fmt::print("resuming at iteration {} (Θ = {:.6e}, {} evaluations so far)\n", checkpoint.iteration, checkpoint.f,
               checkpoint.evaluations);
  } else {
    write_design_vtu(0, definition.initial_design);
  }
  // Θ(α⁰) for the summary, now: the method's first evaluation (fresh run) then hits the cache,
  // and no cache eviction of a long run can make it a state solve at the end.
  const double initial_value = oracle.evaluate_design(definition.initial_design, !resume).value;
  const optim::BundleTrust::Summary summary = study::optimize(oracle, options, on_progress, resume ? &checkpoint : nullptr);
  fmt::print("{}\n", summary.brief_report());

  const study::Evaluation& final = oracle.evaluate_design(summary.x, true);
  if (series.empty() || series.back().time != summary.iterations) write_design_vtu(summary.iterations, summary.x);
  io::JsonValue design = io::JsonValue::object();
  design["alpha"] = summary.x;
  io::write_json(out_dir / "final_design.json", design);
  io::JsonValue json = io::JsonValue::object();
  json["case"] = case_path.string();
  json["command"] = "optimize";
  json["cost"] = oracle.cost().name();
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  // status "max_iterations" covers both limits (core::Status); this names the one that stopped.
  json["stopped_by"] = summary.status == Status::kMaxIterations
                           ? std::string(summary.evaluation_limit ? "max_evaluations" : "max_iterations")
                           : std::string(to_string(summary.status));
  json["initial_cost"] = initial_value;
  json["final_cost"] = final.value;
  json["alpha"] = summary.x;
  json["initial_alpha"] = definition.initial_design;
  json["iterations"] = summary.iterations;
  json["serious_steps"] = summary.serious_steps;
  json["null_steps"] = summary.null_steps;
  json["evaluations"] = summary.evaluations;
  json["failed_evaluations"] = summary.failed_evaluations;
  json["stationarity"] = summary.stationarity;  // ‖z + ω‖ in units of Θ per unit of α
  json["aggregate_error"] = summary.aggregate_error;
  json["objective_scale"] = summary.objective_scale;  // |Θ(α⁰)|: history.csv's columns are relative to it
  json["stationarity_relative"] = summary.stationarity / summary.objective_scale;
  json["cost_kind"] = std::string(cost::to_string(description.cost->kind));
  json["state_solves"] = solves_offset + oracle.num_state_solves();  // over all resumes, as history.csv
  json["time_seconds"] = summary.time_seconds;                      // this process's optimizer
  json["elapsed_seconds"] = elapsed_offset + summary.time_seconds;   // over all resumes
  json["final_index_sets"] = final.index_sets.summary();
  json["final_contact"] = final.contact.brief_report();
  io::write_json(out_dir / "summary.json", json);
  fmt::print("Θ: {:.6e} -> {:.6e}; outputs in {}\n", initial_value, final.value, out_dir.string());
  return summary.status == Status::kConverged || summary.status == Status::kMaxIterations ? kExitOk
                                                                                           : kExitNumericalFailure;
}

}  // namespace frictopt::app
