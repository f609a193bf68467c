// SPDX-License-Identifier: MIT
// Nonsmooth test problems of Lukšan & Vlček, "Test problems for nonsmooth unconstrained and
// linearly constrained optimization", Tech. Rep. V-798, ICS AS CR, 2000 — implemented from the
// formulas, with data, dimensions and starting points as in the authors' Fortran files TEST19
// (unconstrained) and TEST22 (linearly constrained minimax) — plus scaled variants (f·c, x·c)
// that probe scale invariance. See docs/optim-testset.md.
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
  std::string source;          ///< "TEST19 #3", "TEST22 #1", or "TEST19 #16, f·1e3" for a variant
  Eigen::VectorXd x0;          ///< standard starting point (may violate the constraints)
  double f_star = 0.0;         ///< optimal value from the report (times c for a variant f·c)
  /// Unit of the accuracy test: 1, or c for a variant f·c (so that the variant is held to the
  /// same relative accuracy as the original).
  double value_unit = 1.0;
  LinearConstraints constraints;
  FunctionOracle::Function evaluate;
  /// The structured oracle of a minimax problem of TEST22 written as max_k f_k (or max_k |f_k|):
  /// `evaluate`'s answer plus the cut of every other piece (OracleResult::pieces), so that the
  /// bundle method can model the max piece by piece (docs/optim.md, "Cuts of the pieces of a
  /// max"). Empty for the other problems. The table of docs/optim-testset.md uses `evaluate`
  /// (one subgradient per point); this one serves the structured comparison (`--pieces`).
  FunctionOracle::Function evaluate_with_pieces;
  [[nodiscard]] Eigen::Index dimension() const { return x0.size(); }
  /// |f − f*| <= tolerance·max(value_unit, |f*|): the report's relative accuracy test.
  [[nodiscard]] bool solved(double f, double tolerance = 1e-4) const;
  /// The relative error |f − f*| / max(value_unit, |f*|) that `solved` compares.
  [[nodiscard]] double relative_error(double f) const;
};

/// TEST19: all 25 unconstrained problems.
[[nodiscard]] std::vector<LuksanVlcekProblem> luksan_vlcek_unconstrained();
/// TEST22: all 15 linearly constrained minimax problems.
[[nodiscard]] std::vector<LuksanVlcekProblem> luksan_vlcek_constrained();

/// The variant f̃(x) = c·f(x) (f̃* = c·f*, value_unit = c). c > 0.
[[nodiscard]] LuksanVlcekProblem with_scaled_values(const LuksanVlcekProblem& p, double c);
/// The variant in the variables x̃ = c·x: f̃(x̃) = f(x̃/c), x̃0 = c·x0, constraints mapped. c > 0.
[[nodiscard]] LuksanVlcekProblem with_scaled_variables(const LuksanVlcekProblem& p, double c);
/// Scaled variants of several problems of both sets (f·10^k and x·10^k, k = ±3), named
/// "<problem>_f*1e3", "<problem>_x*1e-3".
[[nodiscard]] std::vector<LuksanVlcekProblem> luksan_vlcek_scaled_variants();

/// Looks a problem up by name in both sets and the variants; throws InvalidInput listing the
/// names if absent.
[[nodiscard]] LuksanVlcekProblem luksan_vlcek_problem(std::string_view name);

}  // namespace frictopt::optim
