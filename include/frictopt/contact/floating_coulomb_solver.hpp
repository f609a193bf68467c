// SPDX-License-Identifier: MIT
// Coulomb contact of a floating body (docs/experiments.md §5):
// when the Dirichlet conditions leave rigid-body modes R (A R = 0), the displacement is
// u = A⁺(l + Gᵀz) + Rβ and the contact forces must balance the loads, Rᵀ(l + Gᵀz) = 0. In the
// dual variables this is the equality E z = e, E = (G R)ᵀ (r × dim·p), e = −Rᵀl, added to the
// dual QP min ½zᵀMz + zᵀc over the friction sets, with M = G A⁺ Gᵀ for a generalized inverse A⁺.
// The multiplier of E z = e is β.
//
// Method: the semismooth Newton method of SemismoothNewtonCoulombSolver on (z, β), the balance
// rows bordering its Jacobian (SemismoothNewtonCoulombSolver::solve_balanced), for the Coulomb
// methods semismooth_newton and automatic (when M's entries are at hand or cheap to form); it
// starts from the warm state (β fitted to its touching nodes) or from the frictionless problem
// with the balance as a penalty. When it fails, and for the methods fixed_point and split:
// an augmented Lagrangian on the equality (the outer loop of Dostál's SMALBE) around
// the Coulomb fixed point: iteration k solves the Coulomb problem for the operator M + ρEᵀE and
// the linear term c + Eᵀ(μ_k − ρe) (warm-started), then μ_{k+1} = μ_k + ρ(Ez − e), and ρ grows
// by `penalty_growth` when ‖Ez − e‖ did not fall below `required_decrease` of its last value
// (SMALBE's penalty update in its simplest semimonotonic form). At the returned z the gradient
// Mz + c + Eᵀμ is the kinematics of u with β = μ, so the stick/slip classification is that of
// the floating body. A load the friction cannot carry has no equilibrium: the equality cannot
// be met, the residual stagnates while μ and ρ grow; the solver stops with kDiverged and says
// so (the caller reports the friction capacity, which needs the law and the net load).
#pragma once

#include <Eigen/Core>
#include <string>

#include "frictopt/contact/coulomb_solver.hpp"

namespace frictopt::contact {

class FloatingCoulombSolver {
 public:
  struct Options {
    /// Stop when ‖Ez − e‖ <= equality_tolerance·max(‖e‖, ‖E‖_F·‖z‖) (balance of forces and
    /// moments relative to the loads). In (0, 1).
    double equality_tolerance = 1e-10;
    /// Cap on augmented-Lagrangian iterations. >= 1.
    int max_outer_iterations = 200;
    /// ρ grows by this factor when the residual did not fall enough. > 1.
    double penalty_growth = 10.0;
    /// "Enough": below this fraction of the last residual. In (0, 1).
    double required_decrease = 0.25;
    /// ρ grows up to this multiple of its start, then stays (a larger ρ makes the inner QP
    /// ill-conditioned). > 1. No equilibrium is declared when the residual stalls (less than
    /// 1 % decrease in 5 consecutive iterations, at the finest inner tolerance) above 10⁴ ×
    /// equality_tolerance; a stall below it is accepted as converged (the accuracy floor).
    double max_penalty_ratio = 10.0;
    CoulombSolver::Options coulomb;  ///< the inner fixed point
    void validate() const;           ///< throws InvalidInput naming the field
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "solve() has not been called";
    int outer_iterations = 0;       ///< augmented-Lagrangian iterations (0: Newton solved it)
    int newton_iterations = 0;      ///< Newton steps on (z, β), also those of a failed attempt
    bool solved_by_newton = false;  ///< the state is Newton's (else the augmented Lagrangian's, or none)
    int fixed_point_iterations = 0;  ///< summed over the inner Coulomb solves
    int qp_iterations = 0;
    double equality_residual = kNaN;  ///< ‖Ez − e‖ relative (see Options)
    double penalty = kNaN;            ///< the last ρ
    CoulombSolver::Summary inner;     ///< the last inner solve
    double time_seconds = 0.0;
    bool converged() const { return status == Status::kConverged; }
    std::string brief_report() const;
  };

  /// `delassus` (M = G A⁺ Gᵀ) must outlive the solver; `equality` is E (r × M.size()).
  FloatingCoulombSolver(const linalg::LinearOperator& delassus, Eigen::MatrixXd equality,
                        FrictionLaw law, Options options);

  /// Solves for linear term c and right-hand side e (size r). `state` is the warm start as for
  /// CoulombSolver; on return it holds z, ∇ = Mz + c + Eᵀβ (the floating body's kinematics) and
  /// the classification; `beta` holds β (size r).
  [[nodiscard]] Summary solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                              const Eigen::Ref<const Eigen::VectorXd>& e, ContactState& state,
                              Eigen::VectorXd& beta) const;

 private:
  bool uses_newton() const;
  /// ρ₀: balances the two terms of M + ρEᵀE on the diagonal.
  double initial_penalty() const;
  Summary solve_newton(const Eigen::Ref<const Eigen::VectorXd>& c, const Eigen::Ref<const Eigen::VectorXd>& e,
                       ContactState& state, Eigen::VectorXd& beta) const;
  Summary solve_augmented_lagrangian(const Eigen::Ref<const Eigen::VectorXd>& c,
                                     const Eigen::Ref<const Eigen::VectorXd>& e, ContactState& state,
                                     Eigen::VectorXd& beta) const;

  const linalg::LinearOperator& delassus_;
  Eigen::MatrixXd equality_;
  FrictionLaw law_;
  Options options_;
};

}  // namespace frictopt::contact
