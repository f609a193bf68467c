// SPDX-License-Identifier: MIT
#include "frictopt/study/gradient_check.hpp"

#include <algorithm>
#include <cmath>

#include "frictopt/core/validation.hpp"

namespace frictopt::study {

GradientCheck check_gradient(ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha_ref,
                             double relative_step) {
  require_field(std::isfinite(relative_step) && relative_step > 0, "check_gradient", "relative_step", relative_step,
                "a finite number > 0");
  const Eigen::VectorXd alpha = alpha_ref;
  GradientCheck check;
  check.evaluation = oracle.evaluate_design(alpha);
  if (!check.evaluation.ok) return check;
  const Evaluation& e = check.evaluation;
  check.cardinality = oracle.pieces(alpha, 1).cardinality;
  check.step = relative_step * std::max(alpha.cwiseAbs().maxCoeff(), 1e-12);
  const double h = check.step;
  // Relative to the largest component, so near-zero components do not inflate the error.
  const double scale = std::max(e.subgradient.cwiseAbs().maxCoeff(), 1e-300);
  check.worst_relative_error = 0.0;
  for (Eigen::Index k = 0; k < alpha.size(); ++k) {
    Eigen::VectorXd a = alpha;
    a(k) += h;
    const double plus = oracle.evaluate_design(a, false).value;
    a(k) -= 2 * h;
    const double minus = oracle.evaluate_design(a, false).value;
    GradientCheck::Component c;
    c.finite_difference = (plus - minus) / (2 * h);
    c.adjoint = e.subgradient(k);
    c.relative_error = std::abs(c.finite_difference - c.adjoint) / scale;
    check.worst_relative_error = std::max(check.worst_relative_error, c.relative_error);
    check.components.push_back(c);
  }
  return check;
}

}  // namespace frictopt::study
