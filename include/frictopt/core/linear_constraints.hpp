// SPDX-License-Identifier: MIT
// The one type for a polyhedron Υ = {x : lower ≤ x ≤ upper, A_in x ≤ b_in, A_eq x = b_eq}: shape
// builds the admissible designs in it (docs/theory/problem.md §6), optim minimizes over it
// (docs/theory/bundle-trust.md §3), and study passes it from one to the other unchanged. It
// lives in core because shape comes before optim in the module order (docs/architecture.md §1) and
// neither may depend on the other for it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace frictopt {

/// Linear constraints on x ∈ ℝⁿ. Every block is optional: `lower`/`upper` have size 0 (no
/// bounds) or n, entries may be ∓infinity; A_in is m × n with b_in of size m; A_eq is p × n
/// with b_eq of size p. The names only serve messages.
struct LinearConstraints {
  Eigen::VectorXd lower;
  Eigen::VectorXd upper;
  Eigen::MatrixXd A_in;
  Eigen::VectorXd b_in;
  Eigen::MatrixXd A_eq;
  Eigen::VectorXd b_eq;
  std::vector<std::string> inequality_names;  ///< empty, or one per row of A_in ("slope x1 (2,0)-(1,0) <= 0.05")
  std::vector<std::string> equality_names;    ///< empty, or one per row of A_eq ("volume: sum of alpha")
  std::string variable_name = "x";            ///< how messages call x ("alpha" for designs)

  /// n as given by the bounds (0 when there are none).
  [[nodiscard]] Eigen::Index dimension() const { return lower.size() > 0 ? lower.size() : upper.size(); }
  /// True when no block constrains anything.
  [[nodiscard]] bool empty() const;
  /// Throws InvalidInput naming the block, its shape and the expected shape for n variables,
  /// or a NaN entry, or a bound pair with lower(i) > upper(i).
  void validate(Eigen::Index n) const;
  /// Largest violation max(lb − x, x − ub, A_in x − b_in, |A_eq x − b_eq|, 0) in the user's units.
  [[nodiscard]] double max_violation(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// Empty when max_violation(x) <= tol; else a message naming the worst violated constraint.
  [[nodiscard]] std::string describe_violation(const Eigen::Ref<const Eigen::VectorXd>& x, double tol) const;
};

}  // namespace frictopt
