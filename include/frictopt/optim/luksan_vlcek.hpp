// SPDX-License-Identifier: MIT
// Nonsmooth test problems of Lukšan & Vlček, "Test problems for nonsmooth unconstrained and
// linearly constrained optimization", Tech. Rep. V-798, ICS AS CR, 2000 — implemented from the
// formulas, with data, dimensions and starting points as in the authors' Fortran files TEST19
// (unconstrained) and TEST22 (linearly constrained minimax). See docs/optim-testset.md.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

namespace frictopt::optim {

/// One test problem: an oracle (value + one subgradient, the gradient of an active piece at
/// ties), the standard starting point, the optimal value f* of the report and its constraints.
struct LuksanVlcekProblem {
  std::string name;
  std::string source;          ///< "TEST19 #3" or "TEST22 #1"
  Eigen::VectorXd x0;          ///< standard starting point (may violate the constraints)
  double f_star = 0.0;         ///< optimal value from the report
  LinearConstraints constraints;
  FunctionOracle::Function evaluate;
  [[nodiscard]] Eigen::Index dimension() const { return x0.size(); }
  /// |f − f*| ≤ tolerance·max(1, |f*|): the report's usual relative accuracy test.
  [[nodiscard]] bool solved(double f, double tolerance = 1e-4) const;
};

/// The unconstrained problems implemented (20 of TEST19's 25; see docs/optim-testset.md for the
/// five left out and why).
[[nodiscard]] std::vector<LuksanVlcekProblem> luksan_vlcek_unconstrained();
/// The linearly constrained problems implemented (7 of TEST22's 15).
[[nodiscard]] std::vector<LuksanVlcekProblem> luksan_vlcek_constrained();
/// Looks a problem up by name in both sets; throws InvalidInput listing the names if absent.
[[nodiscard]] LuksanVlcekProblem luksan_vlcek_problem(std::string_view name);

}  // namespace frictopt::optim
