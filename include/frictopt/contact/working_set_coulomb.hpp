// SPDX-License-Identifier: MIT
// The Coulomb problem of CoulombSolver on a working set of contact nodes (docs/contact.md,
// "Large contact surfaces").
// At a Coulomb solution a node without normal force carries no friction force either
// (q_i ∈ λ_i W = {0}), so z vanishes outside the nodes in contact, and z solves the full dual QP
// (docs/theory/state-problem.md §5) iff it solves the QP restricted to any node set W that contains
// them and every node outside W has a non-negative gap w_i = (Mz + c)_ν,i (its KKT conditions are
// then λ_i = 0 ⟂ w_i >= 0, q_i = 0 ∈ 0·W). The restricted QP needs only the principal block M[W, W]
// (from a dense M: read; from the Schur factor: triangular solves for |W|·dim columns, no m³
// work) and is solved by CoulombSolver on that dense block, whose products cost (|W|·dim)²
// instead of m²; one product with the full M checks the gaps outside W, and nodes that would
// penetrate join W until none does.
#pragma once

#include <Eigen/Core>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"

namespace frictopt::contact {

/// CoulombSolver's problem solved on a growing working set of nodes (any DelassusMatrix; the
/// Schur-factor one forms only the block).
/// `delassus` must outlive the solver; after solve() its block cache holds M[W, W] for the final
/// working set W (so that the sensitivity's block of the nodes in contact is free), not the
/// columns L⁻¹E_W.
class WorkingSetCoulombSolver {
 public:
  struct Summary {
    CoulombSolver::Summary coulomb;  ///< summed over the working-set rounds; residuals of the full problem
    int rounds = 0;                  ///< working sets solved (1 when the first one held every contact)
    Eigen::Index initial_nodes = 0;  ///< |W| of the first round
    Eigen::Index final_nodes = 0;    ///< |W| of the last round
    double block_seconds = 0.0;      ///< forming M[W, W] (principal_block)
    double check_seconds = 0.0;      ///< the products with the full M that check the gaps outside W
  };

  WorkingSetCoulombSolver(const DelassusMatrix& delassus, const FrictionLaw& law, CoulombSolver::Options options);

  /// As CoulombSolver::solve (same warm start, same outputs in `state`, residuals of the full
  /// problem). The first working set: the nodes with λ_i > 0 in a warm start and the nodes that
  /// the unloaded body would penetrate (c_ν,i < 0; a node with c_ν,i >= 0 is pushed away by the
  /// contact forces of the others, whose normal columns of M are non-negative in practice).
  /// A round ends the solve when the gaps outside W satisfy ‖min(w, 0)‖ <= ½·tol·‖c‖ (tol the
  /// inner QP's relative tolerance, so the full projected gradient stays at the solver
  /// tolerance); otherwise every node with w_i < 0 joins W.
  [[nodiscard]] Summary solve(const Eigen::Ref<const Eigen::VectorXd>& c, ContactState& state) const;

 private:
  const DelassusMatrix& delassus_;
  FrictionLaw law_;
  CoulombSolver::Options options_;
};

}  // namespace frictopt::contact
