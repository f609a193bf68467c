// SPDX-License-Identifier: MIT
// One Clarke subgradient (or pseudodifferential element) of Θ(α) = J(α, S(α)) for a chosen
// piece, by one adjoint solve on the full FE system (docs/theory/sensitivity.md §5–§6; thesis
// T4.4.1, T6.2.1).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/sensitivity/piece.hpp"

namespace frictopt::sensitivity {

/// Below this reciprocal condition (LAPACK's 1-norm estimate) a piece's contact matrix
/// S M + C_z counts as singular: its adjoint or forward solve is reported as a failure.
inline constexpr double kSingularReciprocalCondition = 1e-14;

/// Partial derivatives of a cost J(α, u, z) at a state (what the cost module returns).
struct CostPartials {
  double value = kNaN;
  Eigen::VectorXd d_alpha;         ///< ∇_α J at fixed state (d)
  Eigen::VectorXd d_displacement;  ///< ∇_u J over all DOFs (num_dofs); prescribed entries are ignored
  Eigen::VectorXd d_contact;       ///< ∇_z J, per node (q, λ) (dim·p); empty = zero
};

/// The contact rows of the piece's linear system in the unknowns (u_free, z): per node dim
/// rows, r = S (G u) + C_z z (+ g_i for gap rows), where G u = (−u_t, u_ν) per node
/// (contact::ContactBoundary). This is (GE2) without the equilibrium rows, written for every
/// law: vertex slip q − λw_j = 0; stick u_t = 0; ray slip on edge j as the unnormalized pair
/// (w_{j+1} − w_j) × (q − λw_j) = 0 and ⟨w_{j+1} − w_j, u_t⟩ = 0 (equivalent to the
/// thesis-style pair of docs/theory/sensitivity.md §4 but polynomial in the vertices, so also
/// differentiable in μ); smooth slip q − λ w(u_t) = 0
/// linearized at the current u_t; zero force λ = 0; zero friction q = 0; gap u_ν + g = 0.
struct PieceLinearization {
  Eigen::SparseMatrix<double> S;   ///< m × m, m = dim·p
  Eigen::SparseMatrix<double> Cz;  ///< m × m
  std::vector<Eigen::Index> gap_rows;  ///< rows "u_ν + g_i = 0" (node = row / dim)
  /// Residual of the piece's equations at the current state, relative to the state's scales
  /// (should be at the level of the solver/classification tolerance: the piece passes here).
  double relative_residual = kNaN;
};

/// Builds the contact rows of `piece` at `state` (z, gradient = (−u_t, u_ν + g)).
PieceLinearization linearize_piece(const Piece& piece, const contact::FrictionLaw& law,
                                   const contact::ContactState& state);

/// Lifetime choices of an AdjointSensitivity (AdjointSensitivity::Options; a namespace-level
/// struct so that `= {}` default arguments can use it).
struct AdjointOptions {
  /// A piece's contact-sized matrix (S M + C_z, reduced) whose reciprocal condition (LAPACK's
  /// 1-norm estimate) is at or below this counts as singular: the adjoint or forward solve is
  /// then reported as kNumericalFailure instead of returning a meaningless ξ. In [0, 1).
  double singular_reciprocal_condition = kSingularReciprocalCondition;
  /// Throws InvalidInput naming the field, value and range.
  void validate() const;
};

/// The adjoint sensitivity on a fixed body and design. With J_piece = [[A, −Gᵀ], [S G, C_z]],
/// the adjoint (Π_iᵀ ψ = −∇_state J of T4.4.1, on the full system) is reduced by the
/// factorization of A to the contact-sized system
///   (M Sᵀ + C_zᵀ) ψ_z = −∇_z J − G A⁻¹ ∇_u J,      ψ_u = −A⁻¹(∇_u J + Gᵀ Sᵀ ψ_z),
/// with M = G A⁻¹ Gᵀ the Delassus matrix; then (docs/theory/sensitivity.md §6, ξ = ∇_α J + Ξᵀψ)
///   ξ = ∇_α J + ∇_α[ψ_uᵀ(A(α)u − l(α))] + Σ_{gap rows} ψ_z,r B̃_{node(r)}.
/// Rows that only fix a force to zero (λ_i = 0, q_i = 0: separated nodes, frictionless
/// components) are eliminated first — their columns of the contact-sized matrix are unit
/// vectors — so the dense LU and the M block are of the size of the nodes in contact, not of
/// all of Γ_c. Two sparse solves with the existing factorization plus that LU: never a dense
/// inverse of the stiffness matrix.
/// A floating body (fem::LinearElasticity::free_modes(): r rigid translations R the conditions
/// leave free, held by r fixing DOFs in the factorization A_F): the state is u = A_F⁺(l + Gᵀz) +
/// Rβ with the equilibrium Rᵀ(l + Gᵀz) = 0, so both systems are bordered by W = G R:
///   [(M Sᵀ + C_zᵀ)  W] [ψ_z]   [−∇_z J − G A_F⁺ ∇_u J]
///   [ Wᵀ Sᵀ         0] [ψ_β] = [−Rᵀ ∇_u J           ],   ψ_u = −A_F⁺(∇_u J + Gᵀ Sᵀ ψ_z) − R ψ_β
/// (and the forward one with the rows Wᵀ δz = Rᵀ r_α h, δu gaining R δβ;
/// docs/theory/loading-plate.md §3). Free rotations depend on the design and are refused
/// (InvalidInput).
/// Lifetime: `fem` (factorized at the design) and `boundary` must outlive this object.
class AdjointSensitivity {
 public:
  using Options = AdjointOptions;
  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "not computed";
    double reciprocal_condition = kNaN;   ///< of the contact-sized matrix (LU estimate)
    double relative_residual = kNaN;      ///< of the contact-sized adjoint system
    double piece_residual = kNaN;         ///< PieceLinearization::relative_residual
    double time_seconds = 0.0;
    std::string brief_report() const;
  };
  struct Result {
    Eigen::VectorXd subgradient;  ///< ξ (d)
    Eigen::VectorXd psi_u;        ///< adjoint on the free DOFs
    /// ψ_u over all DOFs (zero at prescribed ones): P ψ_u, and for a floating body also its
    /// rigid part −Rψ_β, which the fixing DOFs carry (docs/theory/loading-plate.md §3).
    Eigen::VectorXd psi_full;
    Eigen::VectorXd psi_z;        ///< adjoint on the contact rows (dim·p)
    /// ∂Θ/∂p_k for the friction parameters p of friction_parameters(law) (same piece and adjoint;
    /// the costs do not depend on μ explicitly).
    Eigen::VectorXd friction_gradient;
    Summary summary;
  };

  /// The forward derivative of the piece's state along a design direction h (a column
  /// combination R_i h of docs/theory/sensitivity.md §6, on the full system):
  ///   (S M + C_z) δz = −B̃h|_gap + S G A⁻¹ r_α h,   δu = A⁻¹(Gᵀ δz − r_α h),
  /// with r_α h = ∂(A u − l)/∂α · h (fem::LinearElasticity::residual_derivative).
  struct StateDerivative {
    Eigen::VectorXd displacement;  ///< δu over all DOFs (zero at prescribed ones)
    Eigen::VectorXd contact;       ///< δz = (δq, δλ) per node
    double reciprocal_condition = 1.0;  ///< of the piece's reduced contact matrix (1 when it is empty)
    Status status = Status::kConverged;  ///< kNumericalFailure when that matrix is singular
  };
  [[nodiscard]] StateDerivative state_derivative(const Piece& piece, const contact::DelassusMatrix& delassus,
                                                 const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                 const Eigen::Ref<const Eigen::VectorXd>& u,
                                                 const contact::ContactState& state,
                                                 const Eigen::Ref<const Eigen::VectorXd>& h) const;

  /// `gap_matrix` is B̃ at the contact nodes (p × d): g = B̃α. Validates `options` and the
  /// gap matrix's size (InvalidInput).
  AdjointSensitivity(const fem::LinearElasticity& fem, const contact::ContactBoundary& boundary,
                     Eigen::MatrixXd gap_matrix, contact::FrictionLaw law, Options options = {});
  const Options& options() const { return options_; }

  /// ξ for `piece` at the state (positions X, full displacement u, contact state) with the
  /// cost's partials. `delassus` is M = G A⁻¹ Gᵀ at this design (only a block is read).
  [[nodiscard]] Result subgradient(const Piece& piece, const contact::DelassusMatrix& delassus,
                                   const Eigen::Ref<const Eigen::MatrixXd>& X,
                                   const Eigen::Ref<const Eigen::VectorXd>& u, const contact::ContactState& state,
                                   const CostPartials& partials) const;

 private:
  const fem::LinearElasticity& fem_;
  const contact::ContactBoundary& boundary_;
  Eigen::MatrixXd gap_matrix_;
  contact::FrictionLaw law_;
  Options options_;
};

}  // namespace frictopt::sensitivity
