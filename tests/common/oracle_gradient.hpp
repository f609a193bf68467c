// SPDX-License-Identifier: MIT
// Central differences of a shape oracle's Θ over all design variables, the reference of the
// study tests' subgradient checks (load cases, histories, programs).
#pragma once

#include <Eigen/Core>

#include "common/finite_difference.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::testing {

/// ∇Θ(α) by central differences with the step 1e-4 of the design scale max|α_i| (as the
/// adjoint tests): Θ only (no subgradients), each design solved afresh.
inline Eigen::VectorXd oracle_central_gradient(study::ShapeOracle& oracle, const Eigen::VectorXd& alpha) {
  const auto theta = [&](const Eigen::VectorXd& a) { return oracle.evaluate_design(a, false).value; };
  return central_gradient(theta, alpha, 1e-4 * alpha.cwiseAbs().maxCoeff());
}

}  // namespace frictopt::testing
