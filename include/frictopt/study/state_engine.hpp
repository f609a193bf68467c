// SPDX-License-Identifier: MIT
// The state engine: what solves the state of one body at a design (elasticity, and with a
// foundation the Coulomb contact problem), its subgradient, and the operators the certificate
// reads. ElasticBody owns one, made by make_state_engine (study/state_engine_factory.hpp) from
// the case's [solver] engine; docs/architecture.md, "State engines", says what a new one touches.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/fem/material.hpp"
#include "frictopt/linalg/spd_solver.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/piece.hpp"

namespace frictopt::study {

struct BodyState;
struct StepLoads;

/// The parts of a body an engine solves on (ElasticBody owns them; they outlive the engine) and
/// the loads the FE problem does not hold.
struct EngineSetup {
  const mesh::Mesh& mesh;
  fem::LinearElasticity& elasticity;        ///< A(α), l(α), the stiffness solver
  fem::IsotropicMaterial material;
  const contact::ContactBoundary* boundary;  ///< null without a foundation
  Eigen::VectorXd nodal_forces;              ///< free-DOF load of the [[force]] tables (empty: none)
  Eigen::VectorXd nodal_forces_full;         ///< the same, full DOF vector
  std::vector<int> user_prescribed_dofs;     ///< the DOFs the Dirichlet conditions prescribe
  std::vector<int> fixing_dofs;              ///< floating body: the DOFs held at 0 so that A⁺ is a generalized inverse
};

/// One state solve's inputs besides the design's geometry.
struct StateRequest {
  /// The friction law to solve with (the definition's, turned to the design's orientation with
  /// [design] friction_orientation); the state records it (ContactResult::law). Null without contact.
  std::shared_ptr<const contact::FrictionLaw> law;
  const StepLoads* step = nullptr;  ///< a loading program's step (null: the definition's loads)
  std::string design_label = "design";
  /// The contact state the solve starts from and, when it converges, the new one (an engine
  /// that starts otherwise leaves it alone).
  std::optional<contact::ContactState>* warm_start = nullptr;
};

/// The interface of a state engine. `solve` is the one path every engine's state goes through:
/// the engine computes u and z (solve_state), then the recorded law, the contact resultants,
/// stresses and energies are filled here, the same for every engine.
class StateEngine {
 public:
  /// The engines a case can choose ([solver] engine; docs/case-format.md).
  enum Kind {
    kDirect,  ///< sparse Cholesky of A + dual QP fixed point on the Delassus matrix (default)
    kPetsc    ///< PETSc: distributed assembly, semismooth Newton with Krylov steps (MPI)
  };

  virtual ~StateEngine() = default;
  StateEngine(const StateEngine&) = delete;
  StateEngine& operator=(const StateEngine&) = delete;

  /// "direct", "petsc".
  virtual std::string_view name() const = 0;

  /// Fills `state` (whose alpha, positions, volume and min_scaled_jacobian the body has set):
  /// displacement, contact, summary, stress and energies. A failed factorization or contact
  /// solve is a status in state.summary; bad input throws InvalidInput naming request.design_label.
  void solve(BodyState& state, const StateRequest& request);

  /// ξ_i for each of `pieces` at `state` (the last state solve() returned; state.contact->law is
  /// the law), for the cost's partials `j`; `gap_matrix` is B̃ (p × d). Default: the dual
  /// adjoint (sensitivity::AdjointSensitivity) on the state's Delassus operator and the stiffness
  /// solver; a singular piece is a status in its result.
  [[nodiscard]] virtual std::vector<sensitivity::AdjointSensitivity::Result> subgradients(
      const BodyState& state, const std::vector<sensitivity::Piece>& pieces, const sensitivity::CostPartials& j,
      const Eigen::MatrixXd& gap_matrix);
  /// The subgradient an evaluation reports, for the default piece `piece`: subgradients()' unless
  /// the engine linearizes otherwise (the PETSc engine: its Newton piece, one transposed Krylov
  /// solve; docs/petsc-engine.md, "Subgradient").
  [[nodiscard]] virtual sensitivity::AdjointSensitivity::Result evaluation_subgradient(
      const BodyState& state, const sensitivity::Piece& piece, const sensitivity::CostPartials& j,
      const Eigen::MatrixXd& gap_matrix) {
    return subgradients(state, {piece}, j, gap_matrix).front();
  }
  /// R h: the state derivative of `piece` at `state` along h (the dual adjoint's).
  [[nodiscard]] sensitivity::AdjointSensitivity::StateDerivative state_derivative(
      const BodyState& state, const sensitivity::Piece& piece, const Eigen::MatrixXd& gap_matrix,
      const Eigen::Ref<const Eigen::VectorXd>& h) const;

  /// A⁻¹ on the free DOFs at the last solved design: what the certificate's (MF1′) columns and
  /// the Delassus matrix by solves use.
  const linalg::SpdSolver& stiffness_solver() const { return elasticity_.factorization(); }

 protected:
  explicit StateEngine(const EngineSetup& setup)
      : mesh_(setup.mesh), elasticity_(setup.elasticity), material_(setup.material), boundary_(setup.boundary) {}
  /// The engine's part of solve(): u, and with contact ContactResult's state, gaps, summary and
  /// Delassus operator, and state.summary. Returns nullopt when the state stopped before u (a
  /// failed factorization: nothing to finish), else the work lᵀu of the loads that A(α)'s
  /// assembly does not hold (the [[force]] tables; 0 without).
  virtual std::optional<double> solve_state(BodyState& state, const StateRequest& request) = 0;

  const mesh::Mesh& mesh_;
  fem::LinearElasticity& elasticity_;
  fem::IsotropicMaterial material_;
  const contact::ContactBoundary* boundary_;
};

}  // namespace frictopt::study
