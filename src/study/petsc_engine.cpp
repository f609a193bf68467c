// SPDX-License-Identifier: MIT
#include "petsc_engine.hpp"

#include <fmt/format.h>

#include "frictopt/core/error.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {

PetscEngine::PetscEngine(const BodyDefinition& definition, const EngineSetup& setup) : StateEngine(setup) {
  if (definition.friction_orientation)
    throw InvalidInput("design.friction_orientation = true: the PETSc engine keeps its law fixed and has no friction "
                       "gradient; expected solver.engine = \"direct\"");
  if (!boundary_)
    throw InvalidInput("solver.engine = \"petsc\": the PETSc engine solves contact problems; expected a [contact] table");
  // Tied DOFs (PᵀAP) are not in the distributed assembly.
  if (!definition.plates.empty())
    throw InvalidInput(fmt::format("{}: solver.engine = \"petsc\" does not solve loading plates (the distributed "
                                   "stiffness has no tied unknowns); expected engine = \"direct\" for a case with "
                                   "[[plate]] tables",
                                   definition.plates.front().field));
  // The PETSc engine solves the static clamped problem; point forces and floating bodies exist
  // in the direct engine only so far.
  if (!setup.fixing_dofs.empty() || !definition.forces.empty())
    throw InvalidInput(fmt::format("solver.engine = \"petsc\": {} supported by the direct engine only; expected "
                                   "engine = \"direct\" for this case",
                                   setup.fixing_dofs.empty() ? "[[force]] tables are" : "a floating body is"));
  if (!boundary_->standard_foundation())
    throw InvalidInput(
        "foundation: solver.engine = \"petsc\" supports the default foundation only (normal = e_dim, offset = 0, "
        "axis1 = e1); expected engine = \"direct\" for a tilted or offset foundation (docs/petsc-engine.md)");
  petsc::ContactNewtonSolver::Options options;
  options.petsc_options = definition.engine.petsc_options;
  options.relative_tolerance = definition.engine.relative_tolerance;
  options.max_iterations = definition.engine.max_iterations;
  options.classification_tolerance = definition.contact->coulomb.tresca.classification_tolerance;
  solver_ = std::make_shared<petsc::ContactNewtonSolver>(elasticity_, *boundary_, definition.contact->law, options);
  // The engine's A⁻¹ (Krylov solves) behind the FE problem's solver: the dual adjoint of
  // pieces other than the Newton one, and the certificate, solve with it. No factorization:
  // the direct engine's trailing-DOF ordering is not needed.
  elasticity_.set_factorization(solver_->stiffness_solver());
}

std::optional<double> PetscEngine::solve_state(BodyState& state, const StateRequest& request) {
  if (request.step != nullptr)
    throw InvalidInput(request.design_label + ": solver.engine = \"petsc\": loading programs are supported by the "
                                              "direct engine only; expected engine = \"direct\"");
  ContactResult result;
  result.gaps = boundary_->gaps(state.positions);
  Eigen::VectorXd u = displacement_;
  const petsc::ContactNewtonSolver::Summary s = solver_->solve(state.positions, result.gaps, u, result.state);
  if (s.converged()) displacement_ = u;
  // The engine's report in the contact summary's terms (iterations = Newton, QP = Krylov).
  result.summary.status = s.status;
  result.summary.message = s.brief_report();
  result.summary.iterations = s.newton_iterations;
  result.summary.qp_iterations = s.krylov_iterations;
  result.summary.kkt_residual = s.kkt_residual;
  result.summary.complementarity_gap = s.complementarity_gap;
  result.summary.last_relative_increment = s.last_relative_increment;
  result.summary.time_seconds = s.solve_seconds;
  result.summary.method_given = result.summary.method_used = contact::CoulombMethod::kSemismoothNewton;
  result.delassus = solver_->delassus();  // Krylov solves; valid until the next solve
  state.summary.assembly_seconds = s.assembly_seconds;
  state.summary.solve_seconds = s.solve_seconds;
  state.summary.relative_residual = s.relative_residual;
  state.summary.status = s.status;
  state.summary.message =
      (s.converged() ? "contact with Coulomb friction solved by the " : "contact: the ") + s.brief_report();
  state.displacement = std::move(u);
  state.contact = std::move(result);
  return 0.0;  // no point loads (refused above)
}

sensitivity::AdjointSensitivity::Result PetscEngine::evaluation_subgradient(const BodyState& state,
                                                                            const sensitivity::Piece& /*piece*/,
                                                                            const sensitivity::CostPartials& j,
                                                                            const Eigen::MatrixXd& gap_matrix) {
  // The Newton piece is the default piece wherever the classification is strict (tests/petsc).
  const petsc::ContactNewtonSolver::SubgradientResult r = solver_->subgradient(
      state.positions, state.displacement, j.d_alpha, j.d_displacement, j.d_contact, gap_matrix);
  sensitivity::AdjointSensitivity::Result result;
  result.subgradient = r.subgradient;
  result.summary.status = r.summary.status;
  result.summary.message = r.summary.brief_report();
  result.summary.relative_residual = r.summary.relative_residual;
  result.summary.time_seconds = r.summary.seconds;
  return result;
}

}  // namespace frictopt::study
