// SPDX-License-Identifier: MIT
// `frictopt optimize`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::app {
namespace {

const std::vector<std::string> kHistoryColumns = {
    "iteration",    "evaluations",        "step",          "theta",      "t",           "stationarity_relative",
    "aggregate_error_relative", "bundle_size", "serious_steps", "null_steps", "state_solves", "coulomb_iterations",
    "qp_iterations", "weak_nodes",        "state_seconds", "subgradient_seconds", "elapsed_seconds"};

}  // namespace

// frictopt optimize: the bundle trust method on Θ over Υ. The run directory (io::RunDirectory)
// holds, as the run goes, history.csv (one row per outer iteration, flushed), checkpoint.json
// (the method's whole state, atomically replaced) and a VTK series; an interrupted run loses
// at most the current iteration and continues with --resume, repeating the uninterrupted run
// bit for bit. The case is copied into the run directory; a resume refuses another problem.
int run_optimize(const std::filesystem::path& case_argument, const std::filesystem::path& out_dir, bool resume,
                 bool force) {
  using namespace frictopt;
  const io::RunOpening opening = resume ? io::RunOpening::kResume
                                 : force ? io::RunOpening::kForce
                                         : io::RunOpening::kNewRun;
  io::RunDirectory run(out_dir, opening, case_argument);
  const std::filesystem::path case_path = run.store_case();

  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition& definition = description.body;
  if (!definition.contact) throw InvalidInput(case_path.string() + ": optimize needs a [contact] table");
  study::ElasticBody body(definition);
  study::require_admissible_design(body, definition.initial_design, 1e-9,
                                   case_path.string() + ": design.initial");
  const io::CaseFingerprint fingerprint = io::fingerprint_of(description, body);
  std::optional<io::RunCheckpoint> checkpoint;
  if (resume) {
    checkpoint = run.read_checkpoint();
    run.check_resume(description, *checkpoint, fingerprint);
  }
  study::ShapeOracle oracle(body, description.required_cost());
  const optim::BundleTrust::Options& options = description.optimization;

  std::vector<std::string> notes;
  io::CsvWriter history = run.open_history(kHistoryColumns, checkpoint ? checkpoint->method.iteration : 0, notes);
  run.start_series(definition.name, checkpoint ? checkpoint->method.iteration : 0, notes);
  for (const std::string& note : notes) fmt::print("note: {}\n", note);

  const int every = description.output.every;
  const auto write_design_vtu = [&](int iteration, const Eigen::VectorXd& alpha) {
    if (!description.output.vtk) return;
    // Output must not change the numbers: a state solved here for the picture would move the
    // warm start of the next solve, so it is restored afterwards.
    const auto warm_start = body.warm_start();
    run.add_to_series(iteration, [&](const std::filesystem::path& vtu) { io::write_state_vtu(vtu, body, oracle.state(alpha)); });
    body.set_warm_start(warm_start);
  };

  // The run's counters continue over resumes (history.csv's and summary.json's alike).
  const double elapsed_offset = checkpoint ? checkpoint->elapsed_seconds : 0.0;
  const std::int64_t solves_offset = checkpoint ? checkpoint->state_solves : 0;
  double initial_value = kNaN;
  if (checkpoint) {
    initial_value = checkpoint->initial_cost;
    if (checkpoint->warm_start.size() > 0) {
      contact::ContactState warm(checkpoint->warm_start_dim, checkpoint->warm_start.size() / checkpoint->warm_start_dim);
      warm.z = checkpoint->warm_start;
      body.set_warm_start(std::move(warm));
    } else {
      body.set_warm_start(std::nullopt);
    }
    fmt::print("resuming at iteration {} (Θ = {:.6e}, {} evaluations so far)\n", checkpoint->method.iteration,
               checkpoint->method.f, checkpoint->method.evaluations);
  } else {
    // Θ(α⁰) for the summary, now: the method's first evaluation then hits the cache.
    initial_value = oracle.evaluate_design(definition.initial_design, true).value;
    write_design_vtu(0, definition.initial_design);
  }

  fmt::print("{}: {} design variables, {} contact nodes, cost {}, {} inequalities and {} equalities of Υ\n",
             case_path.string(), definition.shape.num_controls(), body.contact_boundary()->num_nodes(),
             oracle.cost().name(), body.admissible_set().A_in.rows(), body.admissible_set().A_eq.rows());
  // The method minimizes Θ/|Θ(α⁰)| (study defaults): its stationarity measure ‖z + ω‖ and
  // aggregate error are relative to |Θ(α⁰)| per unit of α; summary.json also gives them in Θ's units.
  fmt::print("{:>5} {:>6} {:>14} {:>14} {:>10} {:>12} {:>8} {:>9}\n", "iter", "evals", "theta", "step", "t",
             "stat. (rel)", "QP its", "elapsed");
  const auto on_progress = [&](const study::OptimizationProgress& p) {
    const auto& m = p.method;
    const double elapsed = elapsed_offset + p.elapsed_seconds;
    const std::int64_t solves = solves_offset + p.state_solves;
    history.write_row({static_cast<std::int64_t>(m.iteration), static_cast<std::int64_t>(m.evaluations),
                       std::string(optim::to_string(m.step)), m.f, m.t, m.stationarity, m.aggregate_error,
                       static_cast<std::int64_t>(m.bundle.size()), static_cast<std::int64_t>(m.serious_steps),
                       static_cast<std::int64_t>(m.null_steps), solves,
                       static_cast<std::int64_t>(p.center.contact.iterations),
                       static_cast<std::int64_t>(p.center.contact.qp_iterations),
                       static_cast<std::int64_t>(p.center.index_sets.num_weak_nodes()), p.center.state_seconds,
                       p.center.subgradient_seconds, elapsed});
    fmt::print("{:>5} {:>6} {:>14.6e} {:>14} {:>10.3e} {:>12.3e} {:>8} {:>8.1f}s\n", m.iteration, m.evaluations, m.f,
               optim::to_string(m.step), m.t, m.stationarity, p.center.contact.qp_iterations, elapsed);
    std::fflush(stdout);
    if (m.iteration % every == 0) write_design_vtu(m.iteration, m.x);
    // Last, so the checkpoint holds the state the next iteration starts from.
    io::RunCheckpoint c;
    c.method = m;
    c.fingerprint = fingerprint;
    if (const auto& warm = body.warm_start()) {
      c.warm_start = warm->z;
      c.warm_start_dim = warm->dim;
    }
    c.initial_cost = initial_value;
    c.elapsed_seconds = elapsed;
    c.state_solves = solves;
    run.write_checkpoint(c);
    return CallbackResult::kContinue;
  };

  const optim::BundleTrust::Summary summary =
      study::optimize(oracle, options, on_progress, checkpoint ? &checkpoint->method : nullptr);
  fmt::print("{}\n", summary.brief_report());

  const study::Evaluation& final = oracle.evaluate_design(summary.x, true);
  if (!run.series_has(summary.iterations)) write_design_vtu(summary.iterations, summary.x);
  io::JsonValue design = io::JsonValue::object();
  design["alpha"] = summary.x;
  run.write_json_file(io::RunDirectory::kFinalDesign, design);

  io::JsonValue json = io::JsonValue::object();
  json["case"] = case_path.string();
  json["command"] = "optimize";
  json["cost"] = oracle.cost().name();
  json["status"] = std::string(to_string(summary.status));
  json["message"] = summary.message;
  json["stopped_by"] = io::to_json(summary).at("stopped_by");
  json["initial_cost"] = initial_value;
  json["final_cost"] = final.value;
  json["alpha"] = summary.x;
  json["initial_alpha"] = definition.initial_design;
  json["iterations"] = summary.iterations;
  json["serious_steps"] = summary.serious_steps;
  json["null_steps"] = summary.null_steps;
  json["evaluations"] = summary.evaluations;
  json["failed_evaluations"] = summary.failed_evaluations;  // this process's
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
  json["final_contact_solve"] = io::to_json(final.contact);
  json["optimizer"] = io::to_json(summary);
  run.write_json_file(io::RunDirectory::kSummary, json);
  fmt::print("Θ: {:.6e} -> {:.6e}; outputs in {}\n", initial_value, final.value, out_dir.string());
  return summary.status == Status::kConverged || summary.status == Status::kMaxIterations ? kExitOk
                                                                                           : kExitNumericalFailure;
}

}  // namespace frictopt::app
