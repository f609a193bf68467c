// SPDX-License-Identifier: MIT
// The PETSc engine's state solve (docs/petsc-engine.md): Coulomb contact of one body
// against the rigid foundation by a semismooth Newton method on the Alart–Curnier function,
// condensed onto the displacements, with distributed assembly (MATMPIAIJ, block size dim,
// rigid-body near-null space) and Krylov steps (GMRES + GAMG by default; every KSP/PC of
// PETSc through its options). Collective on PETSC_COMM_WORLD: every rank calls every method
// with the same (replicated) mesh and data.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/linalg/spd_solver.hpp"

namespace frictopt::petsc {

/// Semismooth Newton solver of the discrete Coulomb problem in the primal displacements.
///
/// With r(u) = K u − f (K the stiffness over all DOFs, f the traction load), the force the
/// foundation exerts on contact node i is r_i = (−q_i, λ_i) (docs/theory/state-problem.md §3, in
/// the dual variables z_i = (q_i, λ_i) of contact::ContactBoundary: A u = l + Gᵀz). With ρ > 0 and
/// the gap w_i = u_ν^i + g_i, the Alart–Curnier quantities λ̂_i = λ_i − ρ w_i and
/// q̂_i = q_i + ρ u_t^i give the nonsmooth equations
///   F_ν^i = r_ν^i − max(0, λ̂_i) = 0,   F_t^i = r_t^i + proj_{max(0,λ̂_i)·W}(q̂_i) = 0
/// (λ ⟂ w >= 0 and q ∈ λ ∂N_W(u_t): docs/theory/state-problem.md §3), F = r on the other free DOFs
/// and u = u_d on Γ_u. Each Newton step solves one linear system with a generalized Jacobian
/// (non-symmetric where nodes slip) by KSP; a backtracking line search on ‖F‖₂ globalizes.
/// Lifetime: `fem` and `boundary` must outlive the solver; PETSc must be initialized
/// (PetscSession::require()).
class ContactNewtonSolver {
 public:
  struct Options {
    /// Stop when ‖F(u)‖₂ <= relative_tolerance·‖F(u_d)‖₂ (F at the unloaded state: the force
    /// scale of the problem). In (0, 1).
    double relative_tolerance = 1e-11;
    /// Cap on Newton iterations. >= 1.
    int max_iterations = 60;
    /// Step halvings of the line search before a step is taken regardless (a nonmonotone step;
    /// counted in Summary::nonmonotone_steps). >= 0.
    int max_halvings = 12;
    /// Relative tolerance of each Krylov solve (default; -ksp_rtol overrides). In (0, 1).
    double krylov_relative_tolerance = 1e-9;
    /// Cap on Krylov iterations per step (default; -ksp_max_it overrides). >= 1.
    int krylov_max_iterations = 5000;
    /// ρ / mean diag(K) over the contact normal DOFs: the Alart–Curnier parameter in units of
    /// the stiffness (any ρ > 0 gives the same solution; ≈ 1 keeps both parts of F balanced).
    double augmentation = 1.0;
    /// ε_cl of the node classification (docs/theory/sensitivity.md §3), as contact::TrescaSolver's.
    double classification_tolerance = 1e-8;
    /// Relative tolerance of the adjoint's transposed Krylov solve (subgradient(); default,
    /// -ksp_rtol overrides). Tighter than the Newton steps': ψ is read as exact. In (0, 1).
    double adjoint_relative_tolerance = 1e-10;
    /// PETSc options (e.g. "-ksp_type cg -pc_type hypre") inserted into PETSc's database before
    /// the KSP reads them; an option no PETSc object uses is an error (InvalidInput).
    std::string petsc_options;
    /// Throws InvalidInput naming the field, its value and the expectation.
    void validate() const;
  };

  /// The piece of the last Newton linearization at one contact node (docs/petsc-engine.md):
  /// whether the normal row imposes the gap (λ̂ > 0) and the face of λ̂·W the friction
  /// projection selected (interior = stick; vertex, edge or smooth boundary = slip).
  struct NodePiece {
    bool in_contact = false;
    contact::FaceLocation face{contact::FrictionFace::kDegenerate, -1};
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "solve() has not been called";
    int newton_iterations = 0;
    int krylov_iterations = 0;           ///< summed over all Newton steps (and the free response)
    int nonmonotone_steps = 0;
    double relative_residual = kNaN;     ///< ‖F‖₂ / ‖F(u_d)‖₂ at return
    /// ‖t δu‖₂ / ‖u‖₂ of the last accepted Newton step (t its line-search factor; NaN: none).
    double last_relative_increment = kNaN;
    double kkt_residual = kNaN;          ///< contact::ContactResiduals of the returned state
    double complementarity_gap = kNaN;
    int num_ranks = 1;
    std::string krylov_type;             ///< used: KSPType and PCType, e.g. "gmres+gamg"
    std::string last_krylov_reason;      ///< PETSc's KSPConvergedReason of the last solve
    double assembly_seconds = 0.0;
    double solve_seconds = 0.0;
    bool converged() const { return status == Status::kConverged; }
    std::string brief_report() const;
  };

  /// Builds the distributed stiffness layout and the Krylov solver; reads options.
  /// Throws InvalidInput for bad options (an unknown PETSc option is reported at the first solve,
  /// when PETSc has read them all).
  ContactNewtonSolver(const fem::LinearElasticity& fem, const contact::ContactBoundary& boundary,
                      contact::FrictionLaw law, Options options);
  ~ContactNewtonSolver();
  ContactNewtonSolver(const ContactNewtonSolver&) = delete;
  ContactNewtonSolver& operator=(const ContactNewtonSolver&) = delete;

  /// Solves at node positions X (num_nodes × dim) with initial gaps `gaps` (one per contact
  /// node). `displacement` (full, num_dofs): the start when it has num_dofs entries, else the
  /// free elastic response is the start; on return the solution (on every rank). `state`
  /// receives z = (q, λ), ∇ = (−u_t, w), slip_bound = λ and the classification, as the direct
  /// engine's (contact::CoulombSolver) — on every rank.
  [[nodiscard]] Summary solve(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& gaps,
                              Eigen::VectorXd& displacement, contact::ContactState& state);

  /// How the adjoint's one transposed solve went (subgradient()).
  struct AdjointSummary {
    Status status = Status::kNotRun;
    std::string message = "subgradient() has not been called";
    int krylov_iterations = 0;
    double relative_residual = kNaN;  ///< ‖Jᵀψ − b‖₂/‖b‖₂ of the transposed system
    std::string krylov_type;          ///< e.g. "gmres+gamg"
    std::string krylov_reason;        ///< PETSc's KSPConvergedReason
    double seconds = 0.0;
    bool converged() const { return status == Status::kConverged; }
    std::string brief_report() const;
  };
  struct SubgradientResult {
    Eigen::VectorXd subgradient;  ///< ξ (d), on every rank
    AdjointSummary summary;
  };

  /// ξ of the cost Θ(α) = J(α, u, z) for the piece of the Newton linearization at the last
  /// solve() (docs/petsc-engine.md, "Subgradient"; docs/theory/sensitivity.md §6 for the
  /// structure): with J_N the generalized Jacobian at the converged state and z = (q, λ) = (−r_t,
  /// r_ν) the contact residual, one transposed Krylov solve
  ///   J_Nᵀ ψ = −(∇_u J + K Pᵀ ∇_z J)   (P: the contact rows of r with the sign of z)
  /// gives ξ = ∇_α J + ∇_α[vᵀ(K(α)u − f(α))] + B̃ᵀ c, v = L_rᵀψ + Pᵀ∇_z J, where L_r and the
  /// node coefficients c are the r- and gap-derivatives of the contact rows of F. `X`, `u`:
  /// the design's positions and the returned displacement (full, on every rank); the cost's
  /// partials d_alpha (d or empty), d_displacement (num_dofs; prescribed entries ignored),
  /// d_contact (dim·p or empty); `gap_matrix` B̃ (p × d): g = B̃α. Valid until the next solve();
  /// collective like solve(). A Krylov failure is a status (kNumericalFailure, PETSc's reason).
  [[nodiscard]] SubgradientResult subgradient(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                              const Eigen::Ref<const Eigen::VectorXd>& u,
                                              const Eigen::Ref<const Eigen::VectorXd>& d_alpha,
                                              const Eigen::Ref<const Eigen::VectorXd>& d_displacement,
                                              const Eigen::Ref<const Eigen::VectorXd>& d_contact,
                                              const Eigen::Ref<const Eigen::MatrixXd>& gap_matrix);

  /// M = G A⁻¹ Gᵀ at the last solved design (A: the stiffness on the free DOFs), applied and
  /// read in blocks by Krylov solves (CG + GAMG, one per column): what the sensitivity module
  /// reads for pieces other than the Newton one (subgradient() needs no M). Valid until the next
  /// solve() (which reassembles); collective like solve().
  [[nodiscard]] std::shared_ptr<const contact::DelassusMatrix> delassus();

  /// The piece of the generalized Jacobian at the returned state, per contact node (every rank).
  [[nodiscard]] std::vector<NodePiece> newton_piece() const;

  /// A⁻¹ on the free DOFs at the last solved design, as a linalg::SpdSolver (its analyze and
  /// factorize do nothing; each solve is one CG + GAMG solve to 1e-12): for
  /// fem::LinearElasticity::set_factorization, so the adjoint runs in this engine. The solver
  /// must outlive it; collective like solve().
  [[nodiscard]] std::unique_ptr<linalg::SpdSolver> stiffness_solver();

  const Options& options() const { return options_; }

 private:
  struct Impl;
  Options options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace frictopt::petsc
