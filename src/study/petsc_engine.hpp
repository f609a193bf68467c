// SPDX-License-Identifier: MIT
// The PETSc engine (study/state_engine.hpp; docs/petsc-engine.md): an adapter over
// petsc::ContactNewtonSolver — distributed assembly, a semismooth Newton method with Krylov
// steps, and the subgradient of its Newton piece by one transposed Krylov solve. Compiled only
// when PETSc is found (src/study/CMakeLists.txt); made by make_state_engine.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string_view>

#include "frictopt/petsc/contact_newton_solver.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/state_engine.hpp"

namespace frictopt::study {

class PetscEngine final : public StateEngine {
 public:
  /// Throws InvalidInput for what this engine does not solve (no contact, a floating body,
  /// [[force]] tables, a tilted foundation, the orientation as a design).
  PetscEngine(const BodyDefinition& definition, const EngineSetup& setup);
  std::string_view name() const override { return "petsc"; }

  /// The Newton piece's ξ (docs/petsc-engine.md, "Subgradient"): psi_u, psi_z and
  /// friction_gradient stay empty (the engine's adjoint lives on the displacements). Collective.
  [[nodiscard]] sensitivity::AdjointSensitivity::Result evaluation_subgradient(
      const BodyState& state, const sensitivity::Piece& piece, const sensitivity::CostPartials& j,
      const Eigen::MatrixXd& gap_matrix) override;

 protected:
  std::optional<double> solve_state(BodyState& state, const StateRequest& request) override;

 private:
  std::shared_ptr<petsc::ContactNewtonSolver> solver_;
  Eigen::VectorXd displacement_;  // the last converged u: the next solve's start
};

}  // namespace frictopt::study
