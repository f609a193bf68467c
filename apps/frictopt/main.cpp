// SPDX-License-Identifier: MIT
// The frictopt command line: parses arguments (CLI11), loads the case through io, calls study,
// prints one-line reports and maps statuses to exit codes. No numerics live here.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/fclib_export.hpp"
#include "frictopt/io/checkpoint.hpp"
#include "frictopt/io/csv_writer.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/pvd_writer.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/measurements.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/io/study_setup.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInvalidInput = 2;
constexpr int kExitNumericalFailure = 3;

int run_solve(const std::filesystem::path& case_path, const std::filesystem::path& out_dir) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::ElasticBody body(io::make_body_definition(description));
  const auto& mesh = body.mesh();
  fmt::print("{}: {}D body, {} nodes, {} elements, {} unknowns, {} design variables\n", case_path.string(),
             mesh.dim(), mesh.num_nodes(), mesh.num_elements(), body.elasticity().dofs().num_free(),
             body.definition().shape.num_controls());
  const std::string violation = body.admissible_set().describe_violation(body.definition().initial_design, 1e-9);
  if (!violation.empty()) fmt::print("warning: the initial design is outside the admissible set: {}\n", violation);

  study::BodyState state = body.solve(body.definition().initial_design, "initial design");
  if (state.contact) fmt::print("{}\n", state.contact->summary.brief_report());
  fmt::print("{}\n", state.summary.brief_report());
  if (state.summary.status != Status::kConverged) return kExitNumericalFailure;
  fmt::print("strain energy {:.6e} J, work of loads {:.6e} J, volume {:.6e}, max von Mises {:.6e} Pa\n",
             state.strain_energy, state.external_work, state.volume, state.stress.nodal_von_mises.maxCoeff());

  std::filesystem::create_directories(out_dir);
  const std::string name = body.definition().name;
  if (description.output.vtk) {
    const auto vtu = out_dir / (name + ".vtu");
    io::write_state_vtu(vtu, body, state);
    fmt::print("wrote {}\n", vtu.string());
  }
  if (state.contact && mesh.dim() == 2) {
    const auto csv = out_dir / (name + "_contact.csv");
    io::write_contact_csv(csv, body, *state.contact);
    fmt::print("wrote {}\n", csv.string());
  }
  io::JsonValue summary = io::JsonValue::object();
  summary["case"] = case_path.string();
  summary["command"] = "solve";
  summary["status"] = std::string(to_string(state.summary.status));
  summary["message"] = state.summary.message;
  summary["dim"] = mesh.dim();
  summary["num_nodes"] = mesh.num_nodes();
  summary["num_unknowns"] = body.elasticity().dofs().num_free();
  summary["alpha"] = state.alpha;
  summary["relative_residual"] = state.summary.relative_residual;
  summary["strain_energy"] = state.strain_energy;
  summary["external_work"] = state.external_work;
  summary["volume"] = state.volume;
  if (state.contact) {
    const auto& c = *state.contact;
    io::JsonValue contact = io::JsonValue::object();
    contact["status"] = std::string(to_string(c.summary.status));
    contact["message"] = c.summary.message;
    contact["fixed_point_iterations"] = c.summary.iterations;
    contact["qp_iterations"] = c.summary.qp_iterations;
    contact["kkt_residual"] = c.summary.kkt_residual;
    contact["complementarity_gap"] = c.summary.complementarity_gap;
    contact["num_contact_nodes"] = static_cast<int>(c.state.num_nodes());
    contact["dense_delassus"] = c.dense_delassus;
    contact["total_normal_force"] = c.state.normal_forces().sum();
    summary["contact"] = contact;
  }
  summary["max_von_mises"] = state.stress.nodal_von_mises.maxCoeff();
  summary["assembly_seconds"] = state.summary.assembly_seconds;
  summary["factorization_seconds"] = state.summary.factorization_seconds;
  summary["solve_seconds"] = state.summary.solve_seconds;
  io::write_json(out_dir / "summary.json", summary);
  return kExitOk;
}

// `frictopt export-fclib CASE OUT.hdf5`: the contact problem at the initial design in FCLIB's
// local format, with our solution (docs/contact.md, "FCLIB export").
int run_export_fclib(const std::filesystem::path& case_path, const std::filesystem::path& out_path,
                     bool normalize_units, bool include_solution) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::ElasticBody body(io::make_body_definition(description));
  if (!body.contact_boundary())
    throw InvalidInput(fmt::format("{}: the case has no [contact]; there is no contact problem to export",
                                   case_path.string()));
  study::BodyState state = body.solve(body.definition().initial_design, "initial design");
  if (!state.contact) {  // the elasticity factorization failed before the contact solve
    fmt::print("{}\n", state.summary.brief_report());
    return kExitNumericalFailure;
  }
  fmt::print("{}\n", state.contact->summary.brief_report());
  io::FclibExportOptions options;
  options.case_name = case_path.string();
  options.normalize_units = normalize_units;
  options.include_solution = include_solution;
  const io::FclibLocalProblem problem = io::export_fclib_local(out_path, body, state, options);
  fmt::print("wrote {}: FCLIB local problem, spacedim {}, {} contacts, mu = {:.6g}, units {:.6g} N / {:.6g} m; {}\n",
             out_path.string(), problem.spacedim, problem.num_contacts(),
             problem.mu.size() > 0 ? problem.mu(0) : 0.0, problem.force_unit, problem.length_unit,
             !include_solution ? "no solution stored"
             : problem.solution_is_exact
                 ? fmt::format("solution stored (natural-map residual {:.2e})",
                               io::fclib_natural_map_residual(problem, problem.r))
                 : "our solution stored as initial guess only (not exact for this problem)");
  if (!state.contact->summary.converged())
    fmt::print("warning: the contact solve did not converge; the problem is exported, our solution only as a guess\n");
  return kExitOk;
}

// frictopt check-gradient: the adjoint subgradient ξ against central differences of Θ, per
// component, with the index sets and |𝕃| at the design (spec 03 §17.1). Differences are only
// meaningful where every index set is strict; the report says when it is not.
int run_check_gradient(const std::filesystem::path& case_path, const std::filesystem::path& design_path,
                       double relative_step) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::BodyDefinition definition = io::make_body_definition(description);
  if (!definition.contact) throw InvalidInput(case_path.string() + ": check-gradient needs a [contact] table");
  // Finite differences need a state far more accurate than the step: tighten the solvers
  // unless the case asks for even tighter tolerances.
  auto& coulomb = definition.contact->coulomb;
  coulomb.relative_tolerance = std::min(coulomb.relative_tolerance, 1e-13);
  coulomb.tresca.relative_tolerance = std::min(coulomb.tresca.relative_tolerance, 1e-13);
  coulomb.max_iterations = std::max(coulomb.max_iterations, 200);
  coulomb.tresca.max_iterations = std::max(coulomb.tresca.max_iterations, 200000);
  study::ElasticBody body(definition);
  const Eigen::VectorXd alpha = design_path.empty() ? definition.initial_design
                                                    : io::read_design_file(design_path, definition.shape.num_controls());
  study::ShapeOracle oracle(body, study::make_cost(io::make_cost_definition(description), body));
  const study::Evaluation e = oracle.evaluate_design(alpha);
  fmt::print("{}: cost {}, Θ = {:.10e}\n", case_path.string(), oracle.cost().name(), e.value);
  fmt::print("{}\n{}\n", e.contact.brief_report(), e.adjoint.brief_report());
  if (!e.ok) {
    fmt::print("error: {}\n", e.message);
    return kExitNumericalFailure;
  }
  const sensitivity::PieceEnumeration pieces = oracle.pieces(alpha, 1);
  fmt::print("index sets: {}; |L| = {:.0f}\n", e.index_sets.summary(), pieces.cardinality);
  if (e.index_sets.num_weak_nodes() > 0)
    fmt::print("note: {} weak node(s): Θ has a kink here and the difference quotients need not match ξ "
               "(compare one-sided quotients with the pieces of L instead)\n",
               e.index_sets.num_weak_nodes());
  const double h = relative_step * std::max(alpha.cwiseAbs().maxCoeff(), 1e-12);
  fmt::print("central differences with h = {:.3e} (relative step {:.1e} of max|α|)\n", h, relative_step);
  fmt::print("{:>4} {:>20} {:>20} {:>12}\n", "k", "finite difference", "adjoint", "rel. error");
  double worst = 0.0;
  const double scale = std::max(e.subgradient.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index k = 0; k < alpha.size(); ++k) {
    Eigen::VectorXd a = alpha;
    a(k) += h;
    const double plus = oracle.evaluate_design(a, false).value;
    a(k) -= 2 * h;
    const double minus = oracle.evaluate_design(a, false).value;
    const double fd = (plus - minus) / (2 * h);
    // Relative to the largest component, so near-zero components do not inflate the error.
    const double error = std::abs(fd - e.subgradient(k)) / scale;
    worst = std::max(worst, error);
    fmt::print("{:>4} {:>20.10e} {:>20.10e} {:>12.2e}\n", k, fd, e.subgradient(k), error);
  }
  fmt::print("largest error relative to max|ξ|: {:.2e}\n", worst);
  if (e.friction_gradient.size()) {
    const auto params = sensitivity::friction_parameters(body.definition().contact->law);
    for (Eigen::Index k = 0; k < e.friction_gradient.size(); ++k)
      fmt::print("dΘ/d{} = {:.10e}\n", params.names[static_cast<std::size_t>(k)], e.friction_gradient(k));
  }
  return kExitOk;
}

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
  study::BodyDefinition definition = io::make_body_definition(description);
  if (!definition.contact) throw InvalidInput(case_path.string() + ": optimize needs a [contact] table");
  study::ElasticBody body(definition);
  const std::string violation = body.admissible_set().describe_violation(definition.initial_design, 1e-9);
  if (!violation.empty())
    throw InvalidInput(fmt::format("{}: the initial design is outside the admissible set: {}", case_path.string(), violation));
  study::ShapeOracle oracle(body, study::make_cost(io::make_cost_definition(description), body));

  optim::BundleTrust::Options options = study::default_study_options(body);
  const auto& o = description.optimization;
  if (o.max_iterations) options.max_iterations = *o.max_iterations;
  if (o.max_evaluations) options.max_evaluations = *o.max_evaluations;
  if (o.epsilon) options.epsilon = *o.epsilon;
  if (o.max_step_length) options.max_step_length = *o.max_step_length;
  if (o.bundle_size) options.max_bundle_size = *o.bundle_size;

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
    const study::BodyState state = body.solve(alpha, fmt::format("iterate {}", iteration));
    io::write_state_vtu(out_dir / file, body, state);
    series.push_back({static_cast<double>(iteration), file});
    io::write_pvd(out_dir / (name + ".pvd"), series);
  };

  io::CsvWriter history(out_dir / "history.csv",
                        {"iteration", "evaluations", "step", "theta", "t", "stationarity_relative", "aggregate_error_relative",
                         "bundle_size", "serious_steps", "null_steps", "state_solves", "coulomb_iterations",
                         "qp_iterations", "weak_nodes", "elapsed_seconds"},
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
                       static_cast<std::int64_t>(m.null_steps), static_cast<std::int64_t>(p.state_solves),
                       static_cast<std::int64_t>(p.center.contact.iterations),
                       static_cast<std::int64_t>(p.center.contact.qp_iterations),
                       static_cast<std::int64_t>(p.center.index_sets.num_weak_nodes()), p.elapsed_seconds});
    io::write_json(checkpoint_path, io::checkpoint_to_json(m));
    fmt::print("{:>5} {:>6} {:>14.6e} {:>14} {:>10.3e} {:>12.3e} {:>8} {:>8.1f}s\n", m.iteration, m.evaluations, m.f,
               optim::to_string(m.step), m.t, m.stationarity, p.center.contact.qp_iterations, p.elapsed_seconds);
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
  const optim::BundleTrust::Summary summary = study::optimize(oracle, options, on_progress, resume ? &checkpoint : nullptr);
  fmt::print("{}\n", summary.brief_report());

  const study::Evaluation& initial = oracle.evaluate_design(definition.initial_design, false);
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
  json["initial_cost"] = initial.value;
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
  json["cost_kind"] = std::string(io::to_string(description.cost->kind));
  json["state_solves"] = oracle.num_state_solves();
  json["time_seconds"] = summary.time_seconds;
  json["final_index_sets"] = final.index_sets.summary();
  json["final_contact"] = final.contact.brief_report();
  io::write_json(out_dir / "summary.json", json);
  fmt::print("Θ: {:.6e} -> {:.6e}; outputs in {}\n", initial.value, final.value, out_dir.string());
  return summary.status == Status::kConverged || summary.status == Status::kMaxIterations ? kExitOk
                                                                                           : kExitNumericalFailure;
}

// frictopt certify: the optimality certificate (thesis §5.3; spec 06 §6) of a run's final design,
// printed and written to RUN_DIR/certificate.json. Reads RUN_DIR/case.toml (the copy `optimize`
// made) and RUN_DIR/final_design.json.
int run_certify(const std::filesystem::path& run_dir, int cap) {
  using namespace frictopt;
  namespace fs = std::filesystem;
  const fs::path case_path = run_dir / "case.toml", design_path = run_dir / "final_design.json";
  if (!fs::is_directory(run_dir)) throw InvalidInput(run_dir.string() + ": the run directory does not exist");
  for (const fs::path& file : {case_path, design_path})
    if (!fs::exists(file))
      throw InvalidInput(fmt::format("{}: missing; expected a run directory written by `frictopt optimize`",
                                     file.string()));
  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition definition = io::make_body_definition(description);
  if (!definition.contact) throw InvalidInput(case_path.string() + ": certify needs a [contact] table");
  study::ElasticBody body(definition);
  const Eigen::VectorXd alpha = io::read_design_file(design_path, definition.shape.num_controls());
  study::ShapeOracle oracle(body, study::make_cost(io::make_cost_definition(description), body));
  study::CertifyOptions options;
  options.cap = cap;
  const study::Certificate c = study::certify(oracle, alpha, options);
  fmt::print("{}: {} design variables, {} contact nodes, cost {}\n{}", run_dir.string(),
             definition.shape.num_controls(), body.contact_boundary()->num_nodes(), oracle.cost().name(), c.report());

  io::JsonValue json = io::JsonValue::object();
  json["command"] = "certify";
  json["case"] = case_path.string();
  json["design"] = design_path.string();
  json["cost"] = oracle.cost().name();
  json["status"] = std::string(to_string(c.status));
  json["message"] = c.message;
  json["alpha"] = alpha;
  json["value"] = c.value;
  io::JsonValue sets = io::JsonValue::object();
  sets["summary"] = c.index_sets.summary();
  sets["weak_nodes"] = c.index_sets.num_weak_nodes();
  for (auto n : {sensitivity::NormalSet::kStrongContact, sensitivity::NormalSet::kNoContact,
                 sensitivity::NormalSet::kWeakContact})
    sets[sensitivity::to_string(n)] = c.index_sets.count(n);
  io::JsonValue tangential = io::JsonValue::object();
  for (int t = 0; t <= static_cast<int>(sensitivity::TangentialSet::kZeroForce); ++t) {
    const auto set = static_cast<sensitivity::TangentialSet>(t);
    if (c.index_sets.count(set)) tangential[sensitivity::to_string(set)] = c.index_sets.count(set);
  }
  sets["tangential"] = tangential;
  sets["force_tolerance"] = c.index_sets.force_tolerance;
  sets["displacement_tolerance"] = c.index_sets.displacement_tolerance;
  json["index_sets"] = sets;
  json["cardinality_L"] = c.cardinality;
  json["sampled"] = c.sampled;
  json["cap"] = cap;
  io::JsonValue pieces = io::JsonValue::array();
  for (Eigen::Index j = 0; j < c.subgradients.cols(); ++j) {
    io::JsonValue piece = io::JsonValue::object();
    piece["summary"] = c.piece_summaries[static_cast<std::size_t>(j)];
    piece["xi"] = Eigen::VectorXd(c.subgradients.col(j));
    piece["weight"] = c.clarke.weights.size() ? c.clarke.weights(j) : 0.0;
    pieces.push_back(piece);
  }
  json["pieces"] = pieces;
  json["default_piece_column"] = c.default_piece_column;
  json["scale_max_xi_norm"] = c.scale;
  io::JsonValue clarke = io::JsonValue::object();
  clarke["distance"] = c.clarke.distance;
  clarke["relative_distance"] = c.relative_distance;
  clarke["stationary"] = c.clarke_stationary;
  clarke["stationary_tolerance_relative"] = options.stationary_tolerance;
  clarke["distinct_subgradients"] = c.clarke.num_distinct_subgradients;
  if (c.clarke.subgradient_part.size()) {
    clarke["subgradient_part"] = c.clarke.subgradient_part;
    clarke["normal_cone_part"] = c.clarke.normal_part;
  }
  io::JsonValue active = io::JsonValue::array();
  for (const std::string& name : c.active_constraints) active.push_back(name);
  clarke["active_constraints"] = active;
  json["clarke"] = clarke;
  io::JsonValue single = io::JsonValue::object();
  single["distance"] = c.default_piece.distance;
  single["relative_distance"] = c.default_relative_distance;
  json["default_piece"] = single;
  io::JsonValue mf1 = io::JsonValue::object();
  mf1["computed"] = c.mf1.computed;
  mf1["rows"] = c.mf1.rows;
  mf1["cols"] = c.mf1.cols;
  mf1["extra_conditions_m0"] = c.mf1.extra_conditions;
  mf1["rank"] = c.mf1.rank;
  mf1["full_row_rank"] = c.mf1.full_row_rank;
  mf1["sigma_min_over_max"] = c.mf1.sigma_min / c.mf1.sigma_max;
  mf1["rank_tolerance_relative"] = options.rank_tolerance;
  mf1["spec_table_rows"] = c.mf1.spec_rows;
  mf1["spec_table_rank"] = c.mf1.spec_rank;
  mf1["spec_table_full_row_rank"] = c.mf1.spec_full_row_rank;
  json["mf1"] = mf1;
  io::JsonValue m = io::JsonValue::object();
  m["computed"] = c.mordukhovich.computed;
  m["message"] = c.mordukhovich.message;
  m["num_extreme_points"] = static_cast<std::int64_t>(c.mordukhovich.extreme.size());
  m["distance_delta_M"] = c.mordukhovich.distance;
  m["attaining_column"] = c.mordukhovich.attaining;
  m["clarke_minimizer_is_extreme"] = c.mordukhovich.clarke_minimizer_is_extreme;
  m["stationary"] = c.mordukhovich.stationary;
  json["mordukhovich"] = m;
  json["time_seconds"] = c.time_seconds;
  io::write_json(run_dir / "certificate.json", json);
  fmt::print("wrote {}\n", (run_dir / "certificate.json").string());
  return c.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}


// frictopt identify: friction coefficients (and E) from the measurements named in the case's
// [identification] table (issue 7, docs/identification.md). Writes fit.csv (measured vs fitted
// per measurement), summary.json (estimates, covariance, correlation, Ceres report) and
// ceres_report.txt. With --generate-synthetic it instead writes measurements.csv: the rows of
// the case's measurement file with values from the case's own law plus N(0, σ²) noise (--seed).
int run_identify(const std::filesystem::path& case_path, const std::filesystem::path& out_dir, bool generate,
                 std::uint64_t seed, bool noise_free) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  if (!description.identification)
    throw InvalidInput(case_path.string() + ": identify needs an [identification] table (docs/identification.md)");
  const std::vector<study::Measurement> measurements = io::read_measurements(description.identification->measurements);
  study::Identification identification(io::make_body_definition(description), measurements,
                                       io::make_identification_options(description));
  const auto& names = identification.parameter_names();
  std::filesystem::create_directories(out_dir);
  if (generate) {
    const Eigen::VectorXd truth = identification.case_parameters();
    const study::Identification::Prediction exact = identification.predict(truth);
    if (!exact.ok) {
      fmt::print("error: the model could not be evaluated at the case's parameters: {}\n", exact.message);
      return kExitNumericalFailure;
    }
    std::string truth_text;
    for (std::size_t k = 0; k < names.size(); ++k)
      truth_text += fmt::format("{}{} = {}", k ? ", " : "", names[k], truth(static_cast<Eigen::Index>(k)));
    const auto synthetic = study::synthetic_measurements(measurements, exact.values, seed, !noise_free);
    const auto path = out_dir / "measurements.csv";
    io::write_measurements(path, synthetic,
                           fmt::format("synthetic: frictopt identify {} --generate-synthetic --seed {}{}; {}; {}",
                                       case_path.filename().string(), seed, noise_free ? " --noise-free" : "",
                                       truth_text, exact.index_sets));
    fmt::print("{}\nwrote {} ({} measurements; truth {})\n", exact.contact.brief_report(), path.string(),
               synthetic.size(), truth_text);
    return kExitOk;
  }
  fmt::print("{}: {} measurements, {} parameters\n", case_path.string(), measurements.size(), names.size());
  const study::Identification::Summary s = identification.run();
  fmt::print("{}\n{}\n", s.ceres_brief_report, s.brief_report());
  fmt::print("{:<18} {:>14} {:>14} {:>12} {:>24}  {}\n", "parameter", "initial", "estimate", "std. dev.", "bounds",
             "identifiability");
  for (const auto& e : s.estimates)
    fmt::print("{:<18} {:>14.8g} {:>14.8g} {:>12} {:>24}  {}{}\n", e.name, e.initial, e.value,
               std::isnan(e.standard_deviation) ? std::string("-") : fmt::format("{:.3g}", e.standard_deviation),
               fmt::format("[{:g}, {:g}]", e.lower, e.upper), study::to_string(e.identifiability),
               e.note.empty() ? "" : ": " + e.note);
  if (s.correlation.size() && names.size() > 1) {
    fmt::print("correlation:\n");
    for (Eigen::Index a = 0; a < s.correlation.rows(); ++a) {
      std::string row;
      for (Eigen::Index b = 0; b < s.correlation.cols(); ++b)
        row += std::isnan(s.correlation(a, b)) ? fmt::format("{:>8}", "-") : fmt::format("{:>8.3f}", s.correlation(a, b));
      fmt::print("  {:<16}{}\n", names[static_cast<std::size_t>(a)], row);
    }
  }
  std::ofstream(out_dir / "ceres_report.txt") << s.ceres_full_report;
  if (s.predictions.size()) {
    io::CsvWriter fit(out_dir / "fit.csv",
                      {"quantity", "node", "x1", "x2", "measured", "sigma", "fitted", "normalized_residual"});
    const Eigen::MatrixXd& xy = identification.contact_coordinates();
    const auto& ms = identification.measurements();
    for (std::size_t r = 0; r < ms.size(); ++r) {
      const auto& m = ms[r];
      const auto R = static_cast<Eigen::Index>(r);
      const double x1 = m.node >= 0 ? xy(m.node, 0) : kNaN;
      const double x2 = m.node >= 0 && xy.cols() > 1 ? xy(m.node, 1) : kNaN;
      fit.write_row({std::string(study::to_string(m.quantity)), std::int64_t{m.node}, x1, x2, m.value, m.sigma,
                     s.predictions(R), s.residuals(R)});
    }
  }
  io::JsonValue summary = io::JsonValue::object();
  summary["case"] = case_path.string();
  summary["command"] = "identify";
  summary["status"] = std::string(to_string(s.status));
  summary["message"] = s.message;
  summary["ceres_brief_report"] = s.ceres_brief_report;
  summary["iterations"] = s.iterations;
  summary["state_solves"] = s.state_solves;
  summary["initial_cost"] = s.initial_cost;
  summary["final_cost"] = s.final_cost;
  summary["chi_square"] = s.chi_square;
  summary["degrees_of_freedom"] = s.degrees_of_freedom;
  summary["time_seconds"] = s.time_seconds;
  summary["index_sets"] = s.index_sets;
  io::JsonValue estimates = io::JsonValue::array();
  for (const auto& e : s.estimates) {
    io::JsonValue j = io::JsonValue::object();
    j["name"] = e.name;
    j["initial"] = e.initial;
    j["value"] = e.value;
    j["lower"] = e.lower;
    j["upper"] = e.upper;
    j["standard_deviation"] = e.standard_deviation;
    j["identifiability"] = std::string(study::to_string(e.identifiability));
    j["note"] = e.note;
    estimates.push_back(j);
  }
  summary["estimates"] = estimates;
  io::JsonValue correlation = io::JsonValue::array();
  for (Eigen::Index a = 0; a < s.correlation.rows(); ++a) correlation.push_back(io::JsonValue(Eigen::VectorXd(s.correlation.row(a).transpose())));
  summary["correlation"] = correlation;
  summary["singular_values"] = s.singular_values;
  io::write_json(out_dir / "summary.json", summary);
  fmt::print("wrote {}, {}, {}\n", (out_dir / "fit.csv").string(), (out_dir / "summary.json").string(),
             (out_dir / "ceres_report.txt").string());
  return s.status == Status::kConverged ? kExitOk : kExitNumericalFailure;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"frictopt: shape optimization of elastic bodies in contact with (anisotropic) Coulomb friction"};
  app.require_subcommand(1);
  std::filesystem::path case_path, out_dir = "out";
  CLI::App* solve = app.add_subcommand("solve", "Solve the state problem of a case at its initial design and write VTK");
  solve->add_option("case", case_path, "case file (TOML), see docs/case-format.md")->required()->check(CLI::ExistingFile);
  solve->add_option("-o,--output", out_dir, "output directory (created if missing)");
  std::filesystem::path fclib_out;
  bool fclib_normalize = false, fclib_no_solution = false;
  CLI::App* export_fclib = app.add_subcommand(
      "export-fclib", "Write the frictional contact problem at the initial design in FCLIB's local format (HDF5)");
  export_fclib->add_option("case", case_path, "case file (TOML) with an isotropic [contact.friction]")
      ->required()
      ->check(CLI::ExistingFile);
  export_fclib->add_option("out", fclib_out, "output file (.hdf5), replaced if it exists")->required();
  export_fclib->add_flag("--normalize", fclib_normalize,
                         "write in units of our solution's largest force and displacement (O(1) data)");
  export_fclib->add_flag("--no-solution", fclib_no_solution, "do not store our solution");
  std::filesystem::path design_path;
  double relative_step = 1e-4;
  CLI::App* check_gradient = app.add_subcommand(
      "check-gradient", "Compare the adjoint subgradient with central differences of the cost, per component");
  check_gradient->add_option("case", case_path, "case file (TOML) with [contact] and [cost]")
      ->required()
      ->check(CLI::ExistingFile);
  check_gradient->add_option("--design", design_path, "design file (JSON with \"alpha\", or numbers); default: the case's initial design")
      ->check(CLI::ExistingFile);
  check_gradient->add_option("--step", relative_step, "finite-difference step relative to max|α|")
      ->check(CLI::Range(1e-10, 1e-1));
  bool resume = false, force = false;
  CLI::App* optimize = app.add_subcommand("optimize", "Minimize the case's cost over the admissible designs (bundle trust method)");
  optimize->add_option("case", case_path, "case file (TOML) with [contact] and [cost]")->required();
  optimize->add_option("-o,--output", out_dir, "run directory (history, checkpoint, VTK series, summary)");
  optimize->add_flag("--resume", resume, "continue the run in the output directory from its checkpoint");
  optimize->add_flag("--force", force, "replace an existing run in the output directory");
  std::filesystem::path run_dir;
  int certify_cap = 4096;
  CLI::App* certify = app.add_subcommand("certify", "Optimality certificate of a run's final design (thesis 5.3)");
  certify->add_option("run_dir", run_dir, "run directory written by `frictopt optimize`")->required();
  certify->add_option("--cap", certify_cap, "largest |L| enumerated in full (else sampled)")->check(CLI::Range(1, 1 << 20));
  bool identify_generate = false, identify_noise_free = false;
  std::uint64_t identify_seed = 1;
  CLI::App* identify = app.add_subcommand(
      "identify", "Identify friction coefficients (and E) from measured contact data (Ceres least squares)");
  identify->add_option("case", case_path, "case file (TOML) with [contact] and [identification]")
      ->required()
      ->check(CLI::ExistingFile);
  identify->add_option("-o,--output", out_dir, "output directory (fit.csv, summary.json, ceres_report.txt)");
  identify->add_flag("--generate-synthetic", identify_generate,
                     "write DIR/measurements.csv: the measurement rows with values from the case's own law plus noise");
  identify->add_option("--seed", identify_seed, "seed of the synthetic noise (std::mt19937_64)");
  identify->add_flag("--noise-free", identify_noise_free, "synthetic values without noise");
  CLI11_PARSE(app, argc, argv);
  try {
    if (*solve) return run_solve(case_path, out_dir);
    if (*optimize) {
      if (!resume && !std::filesystem::exists(case_path))
        throw frictopt::InvalidInput(case_path.string() + ": the case file does not exist");
      return run_optimize(case_path, out_dir, resume, force);
    }
    if (*check_gradient) return run_check_gradient(case_path, design_path, relative_step);
    if (*certify) return run_certify(run_dir, certify_cap);
    if (*identify) return run_identify(case_path, out_dir, identify_generate, identify_seed, identify_noise_free);
    if (*export_fclib) return run_export_fclib(case_path, fclib_out, fclib_normalize, !fclib_no_solution);
  } catch (const frictopt::InvalidInput& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitInvalidInput;
  }
  return kExitOk;
}
