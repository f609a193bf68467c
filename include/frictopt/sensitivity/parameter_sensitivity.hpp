// SPDX-License-Identifier: MIT
// Forward sensitivities of the contact state with respect to material and friction parameters
// (docs/identification.md): the derivative of a piece's contact rows in the friction coefficients,
// the law rebuilt from its parameter vector, and the contact-space forward solve that turns several
// parameter directions into state derivatives with one LU of the piece's contact-sized matrix.
#pragma once

#include <Eigen/Core>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/sensitivity/piece.hpp"

namespace frictopt::sensitivity {

/// The law of the same kind (and polygon size) as `law` whose friction_parameters(law, options)
/// values are `values` (their inverse); without the orientation among them the law keeps
/// law.orientation(). Throws InvalidInput when `values` has the wrong size or the law rejects
/// them (negative, non-convex polygon, non-finite angle), naming the law.
contact::FrictionLaw with_friction_parameters(const contact::FrictionLaw& law, const Eigen::Ref<const Eigen::VectorXd>& values,
                                              FrictionParameterOptions options = {});

/// ∂r/∂p_k at fixed (u, z) for the contact rows r = S G u + C_z z (+ g) of linearize_piece and
/// the parameters p of friction_parameters(law): column k (dim·p entries) holds, per gap-closed
/// node, vertex slip −λ ∂w_j/∂p_k; ray slip on edge j (d = w_{j+1} − w_j, ∂d = ∂w_{j+1} − ∂w_j)
/// ∂d × q − λ(∂d × w_j + d × ∂w_j) and ⟨∂d, u_t⟩; smooth slip −λ ∂w(u_t)/∂(μ_x, μ_y)·∂(μ_x, μ_y)/∂p_k;
/// stick, zero force and zero friction rows do not depend on p. For the orientation φ (see
/// FrictionParameterOptions) the same formulas hold with ∂w_j/∂φ = J w_j, and a smooth slip
/// row is −λ ∂w(u_t)/∂φ = −λ (J w − (∂w/∂u) J u_t). The adjoint's friction
/// gradient (AdjointSensitivity::Result::friction_gradient) equals this matrix transposed times ψ_z.
Eigen::MatrixXd friction_parameter_rows(const Piece& piece, const contact::FrictionLaw& law,
                                        const contact::ContactState& state);
/// The same for the parameters `params` (e.g. friction_parameters(law, {.orientation = true}) or
/// orientation_parameter(law)): ∂Θ/∂φ = friction_parameter_rows(…, orientation_parameter(law))ᵀ ψ_z.
Eigen::MatrixXd friction_parameter_rows(const Piece& piece, const contact::FrictionLaw& law,
                                        const contact::ContactState& state, const FrictionParameters& params);

/// Derivatives of a piece's contact state along k parameter directions, in contact space.
struct ContactStateDerivative {
  Eigen::MatrixXd forces;    ///< δz per direction (dim·p × k): (δq, δλ) per node
  Eigen::MatrixXd gradient;  ///< δ∇ = δ(G u) per direction (dim·p × k): (−δu_t, δu_ν) per node
  double reciprocal_condition = kNaN;  ///< LU estimate for S M + C_z
  Status status = Status::kNotRun;
  std::string message = "not computed";
};

/// The forward sensitivity of the piece's state (docs/theory/sensitivity.md §6 on the full system,
/// with the equilibrium rows eliminated through A⁻¹ as in AdjointSensitivity::state_derivative):
/// for a parameter p entering the contact rows with ∂r/∂p = R_z and the equilibrium rows
/// A u − l − Gᵀz with ∂(A u − l)/∂p = r_u,
///   (S M + C_z) δz = −R_z + S Q,    G δu = M δz − Q,    Q = G A⁻¹ r_u,
/// one column per direction. `contact_rows` (R_z) and `equilibrium_image` (Q) are dim·p × k;
/// either may be empty (zero). For Young's modulus (A and the Dirichlet lifting scale with E)
/// r_u = (A u − l_lift)/E, so Q = (G u_f − G A⁻¹ l_lift)/E, no extra solve. The dense
/// M = G A⁻¹ Gᵀ is `delassus_scale · delassus` (a changed E scales M without a copy). A singular
/// S M + C_z (rcond <= kSingularReciprocalCondition) gives kNumericalFailure.
[[nodiscard]] ContactStateDerivative contact_state_derivative(const PieceLinearization& piece,
                                                              const Eigen::MatrixXd& delassus,
                                                              const Eigen::Ref<const Eigen::MatrixXd>& contact_rows,
                                                              const Eigen::Ref<const Eigen::MatrixXd>& equilibrium_image,
                                                              double delassus_scale = 1.0);

}  // namespace frictopt::sensitivity
