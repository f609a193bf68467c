// SPDX-License-Identifier: MIT
// The adjoint subgradient ξ against central differences of Θ, per component (spec 03 §17.1):
// what `frictopt check-gradient` prints. Differences are meaningful only where every index set
// is strict (no weak nodes); the result says how many weak nodes there are.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {

struct GradientCheck {
  struct Component {
    double finite_difference = kNaN;  ///< (Θ(α + h e_k) − Θ(α − h e_k)) / 2h
    double adjoint = kNaN;            ///< ξ_k
    double relative_error = kNaN;     ///< |difference − ξ_k| / max_j |ξ_j|
  };
  Evaluation evaluation;          ///< at α, with ξ (ok == false: nothing else is computed)
  double cardinality = kNaN;      ///< |𝕃| at α
  double step = kNaN;             ///< h = relative_step · max(max|α|, 1e-12)
  std::vector<Component> components;
  double worst_relative_error = kNaN;
};

/// Evaluates Θ and ξ at α and, if that succeeded, the central differences of every component.
/// The oracle's body should have been built with tighten_for_derivatives (the state must be
/// far more accurate than the step). `relative_step` finite and > 0.
[[nodiscard]] GradientCheck check_gradient(ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                           double relative_step);

}  // namespace frictopt::study
