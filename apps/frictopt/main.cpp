// SPDX-License-Identifier: MIT
// The frictopt command line: parses arguments (CLI11), loads the case through io, calls study,
// prints one-line reports and maps statuses to exit codes. No numerics live here.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/fclib_export.hpp"
#include "frictopt/io/design_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
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
  CLI11_PARSE(app, argc, argv);
  try {
    if (*solve) return run_solve(case_path, out_dir);
    if (*check_gradient) return run_check_gradient(case_path, design_path, relative_step);
    if (*export_fclib) return run_export_fclib(case_path, fclib_out, fclib_normalize, !fclib_no_solution);
  } catch (const frictopt::InvalidInput& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitInvalidInput;
  }
  return kExitOk;
}
