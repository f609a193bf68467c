// SPDX-License-Identifier: MIT
// The direct engine (study/state_engine.hpp): a sparse Cholesky factorization of A(α) through
// linalg::SpdSolver, the Delassus operator M = G A⁻¹ Gᵀ, and the Coulomb problem as a fixed
// point over Tresca dual QPs on M (docs/theory/state-problem.md §5–§6; a floating body by the
// kernel-aware augmented Lagrangian of contact::FloatingCoulombSolver).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/state_engine.hpp"

namespace frictopt::study {

class DirectEngine final : public StateEngine {
 public:
  /// Orders the contact DOFs last when the stiffness solver can give the Schur factor of them
  /// (M then comes from the trailing factor, linalg::SpdSolver::trailing_factor).
  DirectEngine(const BodyDefinition& definition, const EngineSetup& setup);
  std::string_view name() const override { return "direct"; }

 protected:
  std::optional<double> solve_state(BodyState& state, const StateRequest& request) override;

 private:
  // Assembles and factorizes A(α); false (the status in state.summary) when that failed.
  bool factorize(BodyState& state);
  // M at this design: the step cache's, from the Schur factor, by solves, or applied.
  void attach_delassus(ContactResult& result, bool reuse);
  // z for the linear term c: the Coulomb problem (on a working set of nodes when large), or the
  // floating body's equilibrium-constrained one.
  void solve_contact(ContactResult& result, const Eigen::VectorXd& c, BodyState& state, const StateRequest& request);
  void solve_floating(ContactResult& result, const Eigen::VectorXd& c, const BodyState& state,
                      const StateRequest& request);

  ContactDefinition contact_;  // the definition's (unused without a boundary)
  Eigen::VectorXd nodal_forces_, nodal_forces_full_;
  std::vector<int> user_prescribed_dofs_, fixing_dofs_;
  // A loading program's reuse: the design whose A is factorized, and its Delassus operator/matrix.
  std::optional<Eigen::VectorXd> step_alpha_;
  std::shared_ptr<const contact::DelassusMatrix> step_delassus_;
  std::shared_ptr<const Eigen::MatrixXd> step_delassus_matrix_;
};

}  // namespace frictopt::study
