// SPDX-License-Identifier: MIT
// The derivative of the projection onto a scaled friction set, P(x, s) = proj_{s·W}(x), that
// the semismooth Newton method of the Alart–Curnier function needs (docs/petsc-engine.md).
// The projection onto W and its generalized (Clarke) Jacobian are the law's
// (contact::FrictionLaw::projection_jacobian); this scales them to s·W.
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
/// P_W and J_W are the law's own (contact::FrictionLaw::projection_jacobian, which lists J_W per
/// kind). s = 0 (or a zero law): P = 0 and both derivatives are zero (the caller's ∂s/∂· is zero
/// there).
ProjectionLinearization linearize_projection(const contact::FrictionLaw& law, const Eigen::Vector2d& x, double s);

}  // namespace frictopt::petsc
