// SPDX-License-Identifier: MIT
// The adjoint subgradient ξ against difference quotients of Θ, per component (docs/sensitivity.md,
// "Verification"): what `frictopt check-gradient` and frictopt.check_gradient print. Θ is
// piecewise smooth (docs/theory/sensitivity.md): a quotient matches ξ only where no contact node
// changes its index set within ±h, so every component also reports the nodes that do and both
// one-sided quotients — a kink (ξ_k between or at the one-sided quotients) is then told apart
// from a wrong derivative (a mismatch with no node changing piece).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {

/// |difference − ξ_k| / max|ξ| up to which a quotient "matches" ξ_k.
inline constexpr double kGradientCheckAgreement = 1e-4;

struct GradientCheck {
  /// One contact node whose index set differs at α ± h e_k from the one at α.
  struct PieceChange {
    int node = -1;       ///< contact node index (ContactBoundary order)
    int side = 0;        ///< +1: at α + h e_k, −1: at α − h e_k
    int step = -1;       ///< loading-program step (0-based) whose sets changed; −1 without a program
    std::string before;  ///< e.g. "I+ K00", "M"
    std::string after;
  };
  /// How a component's central quotient compares with ξ_k.
  enum class Verdict {
    kMatch,     ///< within kGradientCheckAgreement of max|ξ|
    kKink,      ///< a node changes piece within ±h and ξ_k lies at or between the one-sided quotients
    kMismatch   ///< neither: no piece change explains the difference (suspect the derivative)
  };
  struct Component {
    double step = kNaN;               ///< h_k [m, or the variable's unit]
    double finite_difference = kNaN;  ///< (Θ(α + h e_k) − Θ(α − h e_k)) / 2h
    double forward_difference = kNaN;   ///< (Θ(α + h e_k) − Θ(α)) / h
    double backward_difference = kNaN;  ///< (Θ(α) − Θ(α − h e_k)) / h
    double adjoint = kNaN;            ///< ξ_k
    double relative_error = kNaN;     ///< |central difference − ξ_k| / max_j |ξ_j|
    std::vector<PieceChange> piece_changes;
    int selected_case_changes = 0;    ///< load cases: sides (0–2) where another case attains the max
    Verdict verdict = Verdict::kMatch;
  };
  Evaluation evaluation;          ///< at α, with ξ (ok == false: nothing else is computed)
  double cardinality = kNaN;      ///< |𝕃| at α
  /// The length the steps are relative to: per component the width upper_k − lower_k of its
  /// bounds in Υ (C0 for a control height); max|α| only for a component without finite bounds.
  Eigen::VectorXd step_scale;
  double step = kNaN;             ///< the largest h_k (all equal for a shape design)
  std::vector<Component> components;
  double worst_relative_error = kNaN;
  /// Estimated round-off of a central quotient relative to max|ξ|: the state's relative accuracy
  /// kDerivativeStateTolerance times |Θ| / (h max|ξ|) (the smallest h_k).
  double noise_relative = kNaN;
  /// Why the comparison may not mean anything here (empty: nothing found): a step below the
  /// state's accuracy, ξ = 0, no contact node carrying force.
  std::vector<std::string> warnings;
};

[[nodiscard]] std::string_view to_string(GradientCheck::Verdict verdict);

/// Evaluates Θ and ξ at α and, if that succeeded, the central and one-sided differences of every
/// component with h_k = relative_step · step_scale_k, and the nodes that change piece within
/// ±h_k. The oracle's body should have been built with tighten_for_derivatives (the state must be
/// far more accurate than the step). `relative_step` finite and > 0. Throws InvalidInput when a
/// component has neither finite bounds nor a nonzero entry in α (no length to scale h by).
[[nodiscard]] GradientCheck check_gradient(ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                           double relative_step);

}  // namespace frictopt::study
