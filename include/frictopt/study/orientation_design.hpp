// SPDX-License-Identifier: MIT
// The orientation φ of an anisotropic 3D friction law as a design variable alongside the shape
// (docs/theory/friction-design.md): the optimizer's variable x = (α, s) with
// s = k·φ, the law turned to φ, the bound on φ in Υ, and ∂Θ/∂s from the adjoint ψ_z.
#pragma once

#include <Eigen/Core>
#include <string>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/linear_constraints.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/piece.hpp"

namespace frictopt::study {

/// [design] friction_orientation = true: bounds on φ [rad]; the initial φ⁰ is the case's law's
/// orientation ([contact.friction] orientation_deg).
struct OrientationDesignDefinition {
  double lower = 0.0;  ///< φ_min [rad]
  double upper = 0.0;  ///< φ_max [rad], > φ_min
};

/// The map x = (α, s) ↔ (α, φ) and what the law's orientation adds to the shape problem.
///
/// Units: α is in metres (0 ≤ α ≤ C0, C0 ~ 1e-3 m), φ in radians. The bundle trust method has
/// one Euclidean trust region and one step bound (max_step_length = C0 by default), so the
/// optimizer sees s = k·φ with k = C0 / (φ_max − φ_min) [m/rad]: the whole admissible range of
/// s has the length C0 of the range of each α_k, and a step of length C0 may cross either
/// range completely — neither variable is frozen by the other's units. Θ is unchanged; only
/// ∂Θ/∂s = (∂Θ/∂φ)/k is scaled.
class OrientationDesign {
 public:
  /// `law` is the case's law (its orientation is φ⁰); `design_range` is C0 [m]. Throws
  /// InvalidInput naming design.friction_orientation / orientation_lower_deg /
  /// orientation_upper_deg / contact.friction.orientation_deg: a 2D law (no orientation), an
  /// isotropic disc (Θ does not depend on φ), reversed or non-finite bounds, φ⁰ outside them.
  OrientationDesign(const OrientationDesignDefinition& definition, const contact::FrictionLaw& law,
                    double design_range);

  /// k [m/rad]: s = k φ.
  double scale() const { return scale_; }
  double angle(double s) const { return s / scale_; }
  double variable(double phi) const { return scale_ * phi; }
  double initial_angle() const { return law_.orientation(); }
  const OrientationDesignDefinition& definition() const { return definition_; }

  /// The case's law turned to the absolute orientation φ; the case's law itself (bit for bit)
  /// when φ is its own orientation.
  contact::FrictionLaw law_at(double phi) const;
  /// The law at the optimizer's variable s; the case's law itself when s is x⁰'s (s/k need not
  /// round back to φ⁰ exactly).
  contact::FrictionLaw law_for_variable(double s) const;
  /// Υ × [k φ_min, k φ_max]: the shape's constraints unchanged, one more column with bounds.
  LinearConstraints extend(const LinearConstraints& upsilon) const;
  /// x⁰ = (α⁰, k φ⁰).
  Eigen::VectorXd initial_design(const Eigen::VectorXd& alpha0) const;

  /// ∂Θ/∂s of `piece` at `state` under `law` (the law the state was solved with), from the
  /// adjoint on the contact rows: (∂r/∂φ)ᵀ ψ_z / k (sensitivity::friction_parameter_rows with
  /// the orientation parameter; the costs and the equilibrium rows do not depend on φ).
  double derivative(const sensitivity::Piece& piece, const contact::FrictionLaw& law,
                    const contact::ContactState& state, const Eigen::VectorXd& psi_z) const;

 private:
  OrientationDesignDefinition definition_;
  contact::FrictionLaw law_;
  double scale_ = 1.0;
};

/// With an orientation design (non-null) and a converged `result`: appends ∂Θ/∂s to ξ, so that
/// ξ = (ξ_α, ∂Θ/∂s) for x = (α, s); a no-op otherwise. `law` is the law of `state`.
void append_orientation_derivative(const OrientationDesign* design, const contact::FrictionLaw& law,
                                   const sensitivity::Piece& piece, const contact::ContactState& state,
                                   sensitivity::AdjointSensitivity::Result& result);

}  // namespace frictopt::study
