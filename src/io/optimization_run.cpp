// SPDX-License-Identifier: MIT
#include "frictopt/io/optimization_run.hpp"

#include <fmt/format.h>

#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/load_change.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::io {

const std::vector<std::string>& optimization_history_columns() {
  static const std::vector<std::string> columns = {
      "iteration",     "evaluations", "step",          "theta",      "t",
      "stationarity_relative",        "aggregate_error_relative",    "bundle_size",
      "serious_steps", "null_steps",  "state_solves",  "coulomb_iterations",
      "qp_iterations", "weak_nodes",
      // The centre's load: a design must not lower Θ by carrying less (study/load_change.hpp).
      "normal_force",  "tangential_force", "contact_area", "stick_nodes", "slip_nodes", "separated_nodes",
      // The timings last (they alone differ between a run and its resumed copy).
      "state_seconds", "subgradient_seconds", "elapsed_seconds"};
  return columns;
}

OptimizationRunResult run_optimization(const OptimizationRunRequest& request) {
  const CaseDescription& description = request.description;
  const std::string& case_name = request.case_name;
  RunDirectory* const run = request.run;
  const auto report = [&](const std::string& line) {
    if (request.report) request.report(line);
  };
  if (request.resume && run == nullptr) throw InvalidInput(case_name + ": a resume needs a run directory");
  const study::BodyDefinition& definition = description.body;
  if (!definition.contact) throw InvalidInput(case_name + ": optimize needs a [contact] table");
  optim::BundleTrust::Options options = request.options.value_or(description.optimization);
  options.validate();
  study::ElasticBody body(definition);
  study::require_admissible_design(body, body.initial_design(), 1e-9, case_name + ": design.initial");
  const CaseFingerprint fingerprint = fingerprint_of(description, body);
  std::optional<RunCheckpoint> checkpoint;
  if (request.resume) {
    checkpoint = run->read_checkpoint();
    run->check_resume(description, *checkpoint, fingerprint);
  }
  study::ShapeOracle oracle(body, description.required_cost());
  // The loading programs' warm starts (load cases, a cost along a program): with the body's,
  // what makes the resumed run repeat the uninterrupted one.
  if (checkpoint && !checkpoint->history_warm_starts.empty()) {
    std::vector<std::optional<contact::ContactState>> states;
    for (const Eigen::VectorXd& z : checkpoint->history_warm_starts) {
      if (z.size() == 0) {
        states.emplace_back();
        continue;
      }
      contact::ContactState warm(fingerprint.dim, z.size() / fingerprint.dim);
      warm.z = z;
      states.emplace_back(std::move(warm));
    }
    try {
      oracle.set_history_warm_starts(states);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: run.history_warm_starts does not fit the run's loading programs ({})",
                                     run->file(RunDirectory::kCheckpoint).string(), e.what()));
    }
  }
  // Before the first evaluation (Θ(α⁰) for the summary): with case_cuts off, the other load
  // cases' adjoints are not paid for even once.
  oracle.set_case_cuts(options.use_piece_cuts);

  OptimizationRunResult result;
  // friction_orientation (docs/theory/friction-design.md): x = (α, s), s = k φ; φ of x in degrees.
  const auto orientation_deg = [&](const Eigen::VectorXd& x) {
    return body.orientation_design()->angle(x(x.size() - 1)) * 180.0 / std::numbers::pi;
  };
  std::optional<CsvWriter> history;
  if (run) {
    const int start_iteration = checkpoint ? checkpoint->method.iteration : 0;
    // friction_orientation: one more column, φ of x_k in degrees.
    std::vector<std::string> columns = optimization_history_columns();
    if (body.orientation_design()) columns.push_back("friction_orientation_deg");
    history.emplace(run->open_history(columns, start_iteration, result.notes,
                                      checkpoint ? std::optional<double>(checkpoint->method.f) : std::nullopt));
    run->start_series(definition.name, start_iteration, result.notes);
  }
  for (const std::string& note : result.notes) report(fmt::format("note: {}", note));

  const int every = description.output.every;
  int output_solves = 0;  // solves made for pictures only: not counted as the method's
  const auto write_design_vtu = [&](int iteration, const Eigen::VectorXd& alpha) {
    if (run == nullptr || !description.output.vtk) return;
    // Output must not change the numbers: a state solved here for the picture (the design is
    // not among the oracle's recent states, e.g. right after a resume) would move the warm
    // start of the next solve, so it is restored afterwards.
    const auto warm_start = body.warm_start();
    const int solves = oracle.num_state_solves();
    run->add_to_series(iteration, [&](const std::filesystem::path& vtu) { write_state_vtu(vtu, body, oracle.state(alpha)); });
    output_solves += oracle.num_state_solves() - solves;
    body.set_warm_start(warm_start);
  };

  // The run's counters continue over resumes (history.csv's and summary.json's alike).
  const double elapsed_offset = checkpoint ? checkpoint->elapsed_seconds : 0.0;
  const std::int64_t solves_offset = checkpoint ? checkpoint->state_solves : 0;
  double initial_value = kNaN;
  contact::ContactResultants initial_load = RunCheckpoint::unknown_load();
  std::vector<fem::PlateReading> initial_plates;  // not in a checkpoint: absent after a resume
  if (checkpoint) {
    initial_value = checkpoint->initial_cost;
    initial_load = checkpoint->initial_load;
    if (checkpoint->warm_start.size() > 0) {
      contact::ContactState warm(checkpoint->warm_start_dim, checkpoint->warm_start.size() / checkpoint->warm_start_dim);
      warm.z = checkpoint->warm_start;
      body.set_warm_start(std::move(warm));
    } else {
      body.set_warm_start(std::nullopt);
    }
    report(fmt::format("resuming at iteration {} (Θ = {:.6e}, {} evaluations so far)", checkpoint->method.iteration,
               checkpoint->method.f, checkpoint->method.evaluations));
  } else {
    // Θ(α⁰) for the summary, now: the method's first evaluation then hits the cache.
    const study::Evaluation& initial = oracle.evaluate_design(body.initial_design(), true);
    initial_value = initial.value;
    if (initial.ok) initial_load = initial.resultants;
    if (initial.ok) initial_plates = initial.plates;
    if (!initial_plates.empty()) report("initial design: " + plates_report(initial_plates));
    write_design_vtu(0, body.initial_design());
  }

  report(fmt::format("{}: {} design variables, {} contact nodes, cost {}, {} inequalities and {} equalities of Υ",
             case_name, body.num_design_variables(), body.contact_boundary()->num_nodes(),
             oracle.cost().name(), body.admissible_set().A_in.rows(), body.admissible_set().A_eq.rows()));
  // The method minimizes Θ/|Θ(α⁰)| (study defaults): its stationarity measure ‖z + ω‖ and
  // aggregate error are relative to |Θ(α⁰)| per unit of α; summary.json also gives them in Θ's units.
  report(fmt::format("{:>5} {:>6} {:>14} {:>14} {:>10} {:>12} {:>8} {:>9}", "iter", "evals", "theta", "step", "t",
             "stat. (rel)", "QP its", "elapsed"));
  // State solves this process made before the method started (the oracle's initial state on
  // a resume) were counted by the interrupted process already.
  const std::int64_t solves_before = checkpoint ? oracle.num_state_solves() : 0;
  RunCheckpoint::CenterColumns center = checkpoint ? checkpoint->center : RunCheckpoint::CenterColumns{};
  const auto on_progress = [&](const study::OptimizationProgress& p) {
    const auto& m = p.method;
    const double elapsed = elapsed_offset + p.elapsed_seconds;
    const std::int64_t solves = solves_offset + p.state_solves - solves_before - output_solves;
    if (p.center.ok) {  // else the centre is the checkpoint's, not evaluated by this process
      const contact::ContactResultants& load = p.center.resultants;
      center = {p.center.contact.iterations, p.center.contact.qp_iterations, p.center.index_sets.num_weak_nodes(),
                p.center.state_seconds, p.center.subgradient_seconds, load.normal_force, load.tangential_force_norm,
                load.contact_area, load.num_stick, load.num_slip, load.num_separated};
    }
    std::vector<CsvValue> row = {
        static_cast<std::int64_t>(m.iteration), static_cast<std::int64_t>(m.evaluations),
        std::string(optim::to_string(m.step)), m.f, m.t, m.stationarity, m.aggregate_error,
        static_cast<std::int64_t>(m.bundle.size()), static_cast<std::int64_t>(m.serious_steps),
        static_cast<std::int64_t>(m.null_steps), solves, center.coulomb_iterations, center.qp_iterations,
        center.weak_nodes, center.normal_force, center.tangential_force, center.contact_area, center.stick_nodes,
        center.slip_nodes, center.separated_nodes, center.state_seconds, center.subgradient_seconds, elapsed};
    if (body.orientation_design()) row.emplace_back(orientation_deg(m.x));  // after the fixed columns
    report(fmt::format("{:>5} {:>6} {:>14.6e} {:>14} {:>10.3e} {:>12.3e} {:>8} {:>8.1f}s", m.iteration, m.evaluations, m.f,
               optim::to_string(m.step), m.t, m.stationarity, center.qp_iterations, elapsed));
    if (run) {
      history->write_row(row);
      if (m.iteration % every == 0) write_design_vtu(m.iteration, m.x);
      // Last, so the checkpoint holds the state the next iteration starts from.
      RunCheckpoint c;
      c.method = m;
      c.fingerprint = fingerprint;
      if (const auto& warm = body.warm_start()) {
        c.warm_start = warm->z;
        c.warm_start_dim = warm->dim;
      }
      for (const auto& warm : oracle.history_warm_starts())
        c.history_warm_starts.push_back(warm ? warm->z : Eigen::VectorXd());
      c.initial_cost = initial_value;
      c.initial_load = initial_load;
      c.elapsed_seconds = elapsed;
      c.state_solves = solves;
      c.center = center;
      run->write_checkpoint(c);
    }
    return request.on_iteration ? request.on_iteration(row, p) : CallbackResult::kContinue;
  };

  const optim::BundleTrust::Summary summary =
      study::optimize(oracle, options, on_progress, checkpoint ? &checkpoint->method : nullptr);
  report(summary.brief_report());

  const study::Evaluation& final = oracle.evaluate_design(summary.x, true);
  if (run && !run->series_has(summary.iterations)) write_design_vtu(summary.iterations, summary.x);

  JsonValue json = JsonValue::object();
  json["case"] = case_name;
  json["command"] = "optimize";
  add_members(json, run_environment());
  json["cost"] = oracle.cost().name();
  json["status"] = std::string(to_string(summary.status));
  // What the status means for the user (README "Exit codes"): certified, limit_reached,
  // needs_attention (with the reasons) or failed.
  const study::OptimizationOutcome outcome = study::assess_outcome(summary, final);
  json["outcome"] = std::string(study::to_string(outcome.kind));
  JsonValue attention = JsonValue::array();
  for (const std::string& reason : outcome.attention) attention.push_back(reason);
  json["attention"] = attention;
  // The load the final design carries against the initial one's (docs/optim.md, "Outcomes").
  const std::vector<std::string> load_warnings =
      std::isfinite(initial_load.normal_force) && final.ok ? study::load_change_warnings(initial_load, final.resultants)
                                                           : std::vector<std::string>{};
  for (const std::string& w : load_warnings) report("warning: " + w);
  json["warnings"] = JsonValue::array();
  for (const std::string& w : load_warnings) json["warnings"].push_back(w);
  json["load_warning_fraction"] = study::kLoadChangeWarningFraction;
  if (std::isfinite(initial_load.normal_force)) json["initial_load"] = load_to_json(initial_load);
  if (final.ok) json["final_load"] = load_to_json(final.resultants);
  if (!initial_plates.empty()) json["initial_plates"] = plates_to_json(initial_plates);
  if (final.ok && !final.plates.empty()) {
    json["final_plates"] = plates_to_json(final.plates);
    report("final design: " + plates_report(final.plates));
  }
  json["message"] = summary.message;
  json["stopped_by"] = to_json(summary).at("stopped_by");
  json["initial_cost"] = initial_value;
  json["final_cost"] = final.value;
  json["alpha"] = summary.x;
  json["initial_alpha"] = definition.initial_design;
  json["design_chart"] = design_chart(body);  // rebuilds the surface from alpha
  if (body.orientation_design()) {
    json["initial_friction_orientation_deg"] = orientation_deg(body.initial_design());
    json["friction_orientation_deg"] = orientation_deg(summary.x);
    json["friction_orientation_scale"] = body.orientation_design()->scale();  // k [m/rad]
  }
  json["iterations"] = summary.iterations;
  json["serious_steps"] = summary.serious_steps;
  json["null_steps"] = summary.null_steps;
  json["evaluations"] = summary.evaluations;
  json["failed_evaluations"] = summary.failed_evaluations;  // this process's
  json["stationarity"] = summary.stationarity;  // ‖z + ω‖ in units of Θ per unit of α
  json["aggregate_error"] = summary.aggregate_error;
  json["objective_scale"] = summary.objective_scale;  // |Θ(α⁰)|: history.csv's columns are relative to it
  json["stationarity_relative"] = summary.stationarity / summary.objective_scale;
  json["cost_kind"] = std::string(to_string(description.required_cost().kind));
  json["cost_unit"] = cost_unit(description.required_cost(), body.mesh().dim());  // Θ's unit
  // The method's state solves over all resumes, as history.csv (pictures' solves not counted).
  json["state_solves"] = solves_offset + oracle.num_state_solves() - solves_before - output_solves;
  json["time_seconds"] = summary.time_seconds;                      // this process's optimizer
  json["elapsed_seconds"] = elapsed_offset + summary.time_seconds;   // over all resumes
  json["final_index_sets"] = final.index_sets.summary();
  json["final_contact"] = final.contact.brief_report();
  json["final_contact_solve"] = to_json(final.contact);
  json["optimizer"] = to_json(summary);
  if (run) {
    JsonValue design = JsonValue::object();
    design["alpha"] = summary.x;
    if (body.orientation_design()) design["friction_orientation_deg"] = orientation_deg(summary.x);
    run->write_json_file(RunDirectory::kFinalDesign, design);
    run->write_json_file(RunDirectory::kSummary, json);
  }
  result.summary = summary;
  result.outcome = outcome;
  result.initial_cost = initial_value;
  result.final_cost = final.value;
  result.warnings = load_warnings;
  result.summary_json = std::move(json);
  return result;
}

OptimizationRunResult run_optimization(RunDirectory& run, const std::filesystem::path& case_path, bool resume,
                                       const std::function<void(const std::string&)>& report) {
  // The run solves its own copy of the case, read as the user's file: output names and
  // messages follow the case the user gave, not the run directory's copy.
  OptimizationRunRequest request{
      load_case(case_path, run.case_argument().empty() ? case_path.string() : run.case_argument().string()),
      case_path.string(), &run, resume, std::nullopt, report, {}};
  return run_optimization(request);
}

}  // namespace frictopt::io
