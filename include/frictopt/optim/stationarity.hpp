// SPDX-License-Identifier: MIT
// The stationarity certificate of docs/theory/stationarity.md §2: the distance from 0 to conv{ξ_i}
// + N_Υ(x), computed by a small convex QP, with the convex weights and the normal-cone part that
// attain it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/optim/linear_constraints.hpp"

namespace frictopt::optim {

struct StationarityOptions {
  // A row of C x ≤ c is active at x when c_i − C_i x ≤ active_tolerance·max(1, |c_i|)
  // (user units; docs/theory/stationarity.md §2). >= 0.
  double active_tolerance = 1e-8;
  // Subgradients closer than this (max norm, relative to max_i ‖ξ_i‖∞) are merged
  // before the QP (docs/theory/stationarity.md §2). >= 0.
  double duplicate_tolerance = 1e-12;
  void validate() const;  // throws InvalidInput naming field, value, expectation
};

struct StationarityCertificate {
  Status status = Status::kNotRun;
  std::string message = "not computed";
  /// δ = dist(0, conv{ξ_i} + N_Υ(x)) (docs/theory/stationarity.md §2).
  double distance = kNaN;
  /// θ: convex weights over the columns given (merged duplicates carry their group's weight on
  /// the first member); θ ≥ 0, Σθ = 1.
  Eigen::VectorXd weights;
  /// Ξθ, the element of conv{ξ_i} closest to −N_Υ(x).
  Eigen::VectorXd subgradient_part;
  /// ω = C_Aᵀη + Eᵀζ ∈ N_Υ(x), η ≥ 0.
  Eigen::VectorXd normal_part;
  /// Indices (rows of the general form, see GeneralForm::row_origin) of the active inequalities.
  std::vector<int> active_inequalities;
  std::vector<std::string> active_names;
  int num_distinct_subgradients = 0;
  /// Scale to judge δ by: max_i ‖ξ_i‖ (docs/theory/stationarity.md §2).
  double subgradient_scale = kNaN;
  [[nodiscard]] std::string brief_report() const;
};

/// Computes δ = min ‖Ξθ + C_Aᵀη + Eᵀζ‖ over θ ≥ 0, 1ᵀθ = 1, η ≥ 0, ζ free
/// (docs/theory/stationarity.md §2). `subgradients` is n × m (one ξ_i per column, m ≥ 1); `x` (size
/// n) is the point whose active constraints define N_Υ(x); `constraints` may be empty
/// (unconstrained: N = {0}). Throws InvalidInput on inconsistent sizes, m = 0 or non-finite input.
/// A point violating Υ by more than the active tolerance is an InvalidInput as well (N_Υ is only
/// defined on Υ). The distinct columns of `Xi`: columns closer than tolerance·‖Xi‖_∞ (max-norm,
/// relative to the largest entry, so the test means the same in any units) form one group. Returns
/// the index of each group's first column; group[j] is column j's group.
[[nodiscard]] std::vector<Eigen::Index> distinct_columns(const Eigen::Ref<const Eigen::MatrixXd>& Xi, double tolerance,
                                                         std::vector<Eigen::Index>& group);

[[nodiscard]] StationarityCertificate stationarity_certificate(
    const Eigen::Ref<const Eigen::MatrixXd>& subgradients, const Eigen::Ref<const Eigen::VectorXd>& x,
    const LinearConstraints& constraints = {}, const StationarityOptions& options = {});

}  // namespace frictopt::optim
