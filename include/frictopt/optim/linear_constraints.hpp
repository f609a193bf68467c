// SPDX-License-Identifier: MIT
// The polyhedral feasible set Υ = {x : lb ≤ x ≤ ub, A_in x ≤ b_in, A_eq x = b_eq} of
// docs/theory/bundle-trust.md §3 (the core type LinearConstraints) in the general form
// C x ≤ c, E x = e the QPs use.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/core/linear_constraints.hpp"

namespace frictopt::optim {

/// Υ in the form the user writes it: the one type shared with shape and study (core).
using LinearConstraints = frictopt::LinearConstraints;

/// Υ as C x ≤ c, E x = e: finite bounds become rows ±e_iᵀ (lower first, then upper, then A_in).
/// `row_origin` names each row of C for messages ("lower[3]", "upper[0]", "A_in[2]").
struct GeneralForm {
  Eigen::MatrixXd C;
  Eigen::VectorXd c;
  Eigen::MatrixXd E;
  Eigen::VectorXd e;
  std::vector<std::string> row_origin;
};

/// Converts validated constraints for n variables to the general form.
[[nodiscard]] GeneralForm to_general_form(const LinearConstraints& constraints, Eigen::Index n);

/// Result of projecting a point onto Υ.
struct Projection {
  bool feasible_set_empty = false;  ///< true: Υ = ∅ and `point` is meaningless
  bool converged = true;            ///< false: the projection QP hit a limit (see message)
  Eigen::VectorXd point;            ///< argmin_{y ∈ Υ} ‖y − x‖
  double distance = 0.0;            ///< ‖point − x‖
  std::string message;              ///< why Υ is empty, if it is
};

/// Euclidean projection onto Υ by the dense QP min ½‖y − x‖² over Υ (phase one detects Υ = ∅).
/// Throws InvalidInput on inconsistent dimensions.
[[nodiscard]] Projection project_onto(const LinearConstraints& constraints,
                                      const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace frictopt::optim
