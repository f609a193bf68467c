// SPDX-License-Identifier: MIT
// Cost functionals J(α, u, z) with value and partial gradients (docs/theory/costs.md).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/sensitivity/adjoint.hpp"

namespace frictopt::cost {

/// What a cost may read at one state. References must outlive the call.
struct CostInput {
  const fem::LinearElasticity& fem;
  const contact::ContactBoundary& boundary;
  const Eigen::VectorXd& alpha;               ///< design (d)
  const Eigen::MatrixXd& positions;           ///< X(α)
  const Eigen::VectorXd& displacement;        ///< full u (num_dofs)
  const contact::ContactState& contact;       ///< z = (q, λ) per node, gradient (−u_t, u_ν + g)
  const Eigen::VectorXd& tributary_areas;     ///< projected Γ_c area per contact node (p)
};

/// J(α, u, z) with ∇_α J, ∇_u J and ∇_z J at fixed state (sensitivity::CostPartials).
class CostFunctional {
 public:
  virtual ~CostFunctional() = default;
  /// The case file's spelling of the cost's kind (cost_kind.hpp), which the console, the
  /// pictures and summary.json print: one name per cost whatever functional implements it.
  virtual std::string name() const = 0;
  virtual sensitivity::CostPartials evaluate(const CostInput& input) const = 0;
};

/// J₁ = Σ_i (λ̄_i − λ_i)² (thesis ex. 5.2.1): the normal nodal forces toward a target [N²].
/// The target λ̄ has one entry per contact node. Named "target_pressure": the case file's kind,
/// whose target is λ̄_i = p̄·a_i.
std::unique_ptr<CostFunctional> make_target_normal_force(Eigen::VectorXd target);

/// J₂ = Σ_i λ_i^p (thesis ex. 5.2.2 with p = 4, read as Σλ⁴: docs/theory/costs.md).
std::unique_ptr<CostFunctional> make_normal_force_power(double exponent = 4.0);

/// J₃ = −uᵀA u + lᵀu over all DOFs (thesis ex. 5.2.3, docs/theory/costs.md): at a solution
/// J₃ = λᵀg + Σ λ_i N_W(u_t^i) >= 0 (minus twice the strain energy plus the work of loads).
std::unique_ptr<CostFunctional> make_compliance();

/// A smooth peak-pressure surrogate: the discrete L^p norm of the contact pressure
/// P_p = (Σ_i a_i (λ_i/a_i)^p)^{1/p} [Pa·m^{2/p}] with a_i the tributary areas; p → ∞ gives
/// the peak pressure up to the factor (Σa)^{1/p}.
std::unique_ptr<CostFunctional> make_pressure_norm(double exponent = 8.0);

/// Total slip Σ_i √(|u_t^i|² + δ²) − δ [m]: the smoothed total tangential displacement of the
/// contact nodes (δ > 0 smooths |·| at 0).
std::unique_ptr<CostFunctional> make_total_slip(double smoothing);

/// Tangential-traction uniformity J = Σ_i a_i ‖t_i − t̄‖² [N²/m²] over all contact nodes, with
/// t_i = τ_i / a_i the tangential traction on the body (τ_i = −q_i the nodal tangential contact
/// force, a_i the tributary area) and t̄ either `target` (dim − 1 components [Pa]) or, when
/// `target` is empty, the area-weighted mean Σ_i τ_i / Σ_i a_i of the current state — then J is
/// the area-weighted variance of the traction (separated nodes count with t_i = 0, so that the
/// cost stays continuous when nodes lift off). In both cases ∂J/∂τ_k = 2(t_k − t̄): the mean's
/// own derivative drops out because Σ_i a_i (t_i − t̄) = 0.
std::unique_ptr<CostFunctional> make_traction_uniformity(Eigen::VectorXd target = {});

}  // namespace frictopt::cost
