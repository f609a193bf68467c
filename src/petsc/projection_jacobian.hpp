// SPDX-License-Identifier: MIT
// The derivative of the projection onto a scaled friction set, P(x, s) = proj_{s·W}(x), that
// the semismooth Newton method of the Alart–Curnier function needs (docs/petsc-engine.md).
// The projection itself is contact::FrictionLaw::project; this adds one element of its
// generalized (Clarke) Jacobian for every law: disc, ellipse, regular and per-vertex polygons,
// and the 2D interval.
#pragma once

#include <Eigen/Core>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::petsc {

/// P = proj_{sW}(x), ∂P/∂x (2×2; 2D laws use entry (0,0)) and ∂P/∂s (2), for s >= 0.
struct ProjectionLinearization {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  Eigen::Matrix2d d_x = Eigen::Matrix2d::Zero();
  Eigen::Vector2d d_s = Eigen::Vector2d::Zero();
  /// The face of s·W the projection lands on: kInterior (x inside: stick), kVertex j / kEdge j
  /// (polygons, interval), kSmooth (disc, ellipse), kDegenerate (s = 0 or a zero law).
  contact::FaceLocation face{contact::FrictionFace::kDegenerate, -1};
};

/// One element of the generalized Jacobian of P at (x, s). P is positively homogeneous,
/// P(x, s) = s·P_W(x/s), so with y = x/s: ∂P/∂x = J_W(y) and ∂P/∂s = P_W(y) − J_W(y)·y, where
/// J_W is the Jacobian of the projection onto W:
///  - y inside W: the identity;
///  - polygon (and interval): zero at a vertex, t tᵀ on an edge with unit tangent t;
///  - ellipse {xᵀDx <= 1}, D = diag(1/μ_x², 1/μ_y²) (disc: μ_x = μ_y): P_W(y) = (I + γD)⁻¹y with
///    the multiplier γ > 0; implicit differentiation of PᵀDP = 1 gives
///    J = M − (MDP)(MDP)ᵀ / (PᵀDMDP), M = (I + γD)⁻¹ (symmetric, as M and D are diagonal).
/// s = 0 (or a zero law): P = 0 and both derivatives are zero (the caller's ∂s/∂· is zero there).
ProjectionLinearization linearize_projection(const contact::FrictionLaw& law, const Eigen::Vector2d& x, double s);

}  // namespace frictopt::petsc
