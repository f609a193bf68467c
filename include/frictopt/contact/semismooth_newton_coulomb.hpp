// SPDX-License-Identifier: MIT
// The Coulomb problem of CoulombSolver (docs/theory/state-problem.md §5) by a semismooth Newton
// method on the Alart–Curnier complementarity function of the condensed dual problem
// (docs/contact.md, "Semismooth Newton"; Alart & Curnier 1991; Hintermüller, Ito & Kunisch 2002):
//   Φ(z) = z − P_{K(z)}(z − R(Mz + c)),  K(z) = {λ >= 0} × [λ]₊·W per node,
// i.e. per node Φ_ν = λ − max(0, λ − r w) and Φ_t = q − P_{[λ]₊W}(q + r u_t) (∇ = Mz + c =
// (−u_t, w)). Φ(z) = 0 iff z solves the Coulomb problem (the fixed point's s = λ). The projections
// and their Jacobians are the friction law's own (FrictionLaw::projection_jacobian), so every law
// — disc, ellipse, polygons with per-vertex coefficients, the 2D interval — is solved alike.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/linalg/linear_operator.hpp"

namespace frictopt::contact {

/// Semismooth Newton for the dual Coulomb problem on a dense Delassus matrix M (read from a
/// DenseDelassus or linalg::DenseOperator; any other operator is formed by m products).
/// Each step solves J d = −Φ with J = (I − D − E) + R D M (D the projections' Jacobians, E the
/// derivative of the tangential projection with respect to the slip bound [λ]₊, R = diag(r_i)
/// with r_i = dim / trace(M_ii)): by a dense LU up to NewtonOptions::direct_max_unknowns,
/// above by right-preconditioned GMRES (products J v = (I − D − E)v + R D (M v), one product with
/// M each) with a single-precision LU of the Jacobian of a recent step as preconditioner; a
/// backtracking (Armijo) line search on ½‖Φ‖² globalizes. The stopping quantity is the fixed
/// point's inner one: the Tresca QP's relative reduced projected gradient at s = λ,
/// ‖g̃_ᾱ(z)‖ <= tresca.relative_tolerance·‖c‖ (plus the Coulomb KKT residual below
/// tresca.classification_tolerance, which the node classification needs). When Newton does
/// not converge (step cap, a failed line search, a singular Jacobian) the fixed point solves
/// from the same start (NewtonOptions::fallback_to_fixed_point), and the summary says so.
/// `delassus` must outlive the solver.
class SemismoothNewtonCoulombSolver {
 public:
  /// One law for all nodes (W includes μ). Throws InvalidInput on bad options or sizes.
  SemismoothNewtonCoulombSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law,
                                CoulombSolver::Options options);
  /// One law per node.
  SemismoothNewtonCoulombSolver(const linalg::LinearOperator& delassus, std::vector<FrictionLaw> laws,
                                CoulombSolver::Options options);

  /// As CoulombSolver::solve: warm start from state.z when it has size dim·p (projected onto
  /// the feasible set), otherwise from the frictionless problem (one Tresca QP with s = 0 to
  /// 1e-6). On return `state` holds z, ∇ = Mz + c, slip_bound = λ and the classification; the
  /// summary's method_used is kSemismoothNewton, or kFixedPoint after a fallback.
  [[nodiscard]] CoulombSolver::Summary solve(const Eigen::Ref<const Eigen::VectorXd>& c, ContactState& state) const;

  /// The balance rows of a floating body (FloatingCoulombSolver): E z = e, whose multiplier β
  /// enters the kinematics as ∇ = Mz + c + Eᵀβ.
  struct Balance {
    const Eigen::MatrixXd& equality;  ///< E (r × m), r <= 6
    const Eigen::VectorXd& rhs;       ///< e (r)
    /// Met when residual(z) <= tolerance.
    double tolerance = 1e-10;
    /// ‖Ez − e‖ / max(‖e‖, ‖E‖_F·‖z‖): the balance of forces and moments relative to the loads.
    [[nodiscard]] double residual(const Eigen::Ref<const Eigen::VectorXd>& z) const;
  };

  /// The floating body's problem by the same Newton method on (z, β): Φ(z) with ∇ = Mz + c + Eᵀβ
  /// and the rows Ez − e, the Jacobian bordered as [A + RDM, RDEᵀ; E, 0] (docs/experiments.md §5).
  /// Starts from state.z and `beta` as given (the caller's start: a cold
  /// state starts from the frictionless problem without the rows, which rarely has contact
  /// enough to determine β). Converged when the projected gradient meets
  /// tresca.relative_tolerance relative to ‖c + Eᵀβ‖ and the rows meet balance.tolerance. No
  /// fallback: a failure is returned as such (FloatingCoulombSolver then uses its augmented
  /// Lagrangian, which also tells a load without equilibrium).
  [[nodiscard]] CoulombSolver::Summary solve_balanced(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                      const Balance& balance, ContactState& state,
                                                      Eigen::VectorXd& beta) const;

 private:
  CoulombSolver::Summary iterate(const Eigen::VectorXd& c, const Balance* balance, ContactState& state,
                                 Eigen::VectorXd& beta) const;

  const linalg::LinearOperator& delassus_;
  std::vector<FrictionLaw> laws_;
  CoulombSolver::Options options_;
  CoulombSolver fixed_point_;  ///< the start, the fallback and the residuals (method kFixedPoint)
  int dim_ = 3;
  Eigen::Index num_nodes_ = 0;
  const Eigen::MatrixXd* matrix_ = nullptr;  ///< M: the operator's own, or formed_
  std::optional<Eigen::MatrixXd> formed_;
};

/// ‖g̃_ᾱ(z)‖ with g̃_ᾱ(z) = (z − P_{K}(z − ᾱ∇))/ᾱ and K = {λ >= 0} × max(λ, 0)·W per node: the
/// Tresca QP's reduced projected gradient (TrescaSolver::Options::relative_tolerance) at the slip
/// bound s = λ, zero exactly at a Coulomb solution. `laws` has 1 or p entries.
[[nodiscard]] double coulomb_projected_gradient_norm(std::span<const FrictionLaw> laws,
                                                     const Eigen::Ref<const Eigen::VectorXd>& z,
                                                     const Eigen::Ref<const Eigen::VectorXd>& gradient, int dim,
                                                     double alpha);

}  // namespace frictopt::contact
