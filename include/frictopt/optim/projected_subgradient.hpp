// SPDX-License-Identifier: MIT
// A baseline for the test-set table: Shor's projected subgradient method with normalized,
// diminishing steps a_k = a_0/√(k+1) (thesis §2.5). It has no
// implementable stopping test, so it runs to its evaluation budget and returns the best point.
#pragma once

#include <Eigen/Core>
#include <string>

#include "frictopt/core/status.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

namespace frictopt::optim {

class ProjectedSubgradient {
 public:
  struct Options {
    // a_0: length of the first step (units of x). > 0.
    double initial_step = 1.0;
    // The whole budget is used (no stopping test exists for this method). >= 1.
    int max_evaluations = 5000;
    // A start violating Υ by more than this is projected first. > 0.
    double feasibility_tolerance = 1e-9;
    void validate() const;  // throws InvalidInput naming field, value, expectation
  };
  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "minimize() has not been called";
    Eigen::VectorXd x;   ///< best point found
    double f = kNaN;     ///< f at the best point
    int evaluations = 0;
    int failed_evaluations = 0;
    double time_seconds = 0.0;
    [[nodiscard]] std::string brief_report() const;
  };

  /// Throws InvalidInput on invalid options.
  explicit ProjectedSubgradient(Options options, LinearConstraints constraints = {});
  /// x_{k+1} = P_Υ(x_k − a_k g_k/‖g_k‖). Ends with kMaxIterations when the budget is spent,
  /// kConverged if a zero subgradient is met with Υ = ℝⁿ. Throws InvalidInput on bad shapes
  /// or an empty feasible set.
  [[nodiscard]] Summary minimize(Oracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& x0) const;

 private:
  Options options_;
  LinearConstraints constraints_;
};

}  // namespace frictopt::optim
