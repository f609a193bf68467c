// SPDX-License-Identifier: MIT
#include "frictopt/study/gradient_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"
#include "frictopt/study/derivative_accuracy.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {

namespace {

using sensitivity::IndexSets;
using sensitivity::NodeSets;

// "M", "I0", "I+ K00", "I+ K+j (vertex 1)", ...: a node's piece as the index-set summaries name it.
std::string describe(const NodeSets& s) {
  std::string text(sensitivity::to_string(s.normal));
  if (s.normal != sensitivity::NormalSet::kStrongContact) return text;
  text += " ";
  text += sensitivity::to_string(s.tangential);
  if (s.vertex >= 0) text += fmt::format(" (vertex {})", s.vertex);
  if (s.edge >= 0) text += fmt::format(" (edge {})", s.edge);
  return text;
}

bool same_piece(const NodeSets& a, const NodeSets& b) {
  return a.normal == b.normal && a.tangential == b.tangential && a.vertex == b.vertex && a.edge == b.edge;
}

void compare_sets(const IndexSets& at, const IndexSets& moved, int side, int step,
                  std::vector<GradientCheck::PieceChange>& out) {
  const std::size_t n = std::min(at.nodes.size(), moved.nodes.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!same_piece(at.nodes[i], moved.nodes[i]))
      out.push_back({static_cast<int>(i), side, step, describe(at.nodes[i]), describe(moved.nodes[i])});
}

// The nodes whose pieces differ between the evaluation at α and the one at α ± h e_k; a change of
// the load case attaining the max ("worst") is counted instead (its nodes are another case's).
void compare_pieces(const Evaluation& at, const Evaluation& moved, int side, GradientCheck::Component& c) {
  if (at.selected_case != moved.selected_case) {
    ++c.selected_case_changes;
    return;
  }
  if (!at.step_index_sets.empty() && at.step_index_sets.size() == moved.step_index_sets.size()) {
    for (std::size_t k = 0; k < at.step_index_sets.size(); ++k)
      compare_sets(at.step_index_sets[k], moved.step_index_sets[k], side, static_cast<int>(k), c.piece_changes);
    return;
  }
  compare_sets(at.index_sets, moved.index_sets, side, -1, c.piece_changes);
}

GradientCheck::Verdict verdict_of(const GradientCheck::Component& c, double scale) {
  const double tolerance = kGradientCheckAgreement * scale;
  if (c.relative_error <= kGradientCheckAgreement) return GradientCheck::Verdict::kMatch;
  const bool changes = !c.piece_changes.empty() || c.selected_case_changes > 0;
  const double low = std::min(c.forward_difference, c.backward_difference) - tolerance;
  const double high = std::max(c.forward_difference, c.backward_difference) + tolerance;
  // At a kink Θ has one-sided derivatives; ξ_k of the default piece is the derivative of one of
  // the pieces meeting there, so it lies at (or, for several kinks within ±h, between) them.
  if (changes && c.adjoint >= low && c.adjoint <= high) return GradientCheck::Verdict::kKink;
  return GradientCheck::Verdict::kMismatch;
}

}  // namespace

std::string_view to_string(GradientCheck::Verdict verdict) {
  switch (verdict) {
    case GradientCheck::Verdict::kMatch: return "match";
    case GradientCheck::Verdict::kKink: return "kink";
    case GradientCheck::Verdict::kMismatch: return "MISMATCH";
  }
  return "?";
}

GradientCheck check_gradient(ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha_ref,
                             double relative_step) {
  require_field(std::isfinite(relative_step) && relative_step > 0, "check_gradient", "relative_step", relative_step,
                "a finite number > 0");
  const Eigen::VectorXd alpha = alpha_ref;
  GradientCheck check;
  // The step's length: a design the user starts from is often flat (α⁰ = 0), where a step
  // relative to max|α| is no step at all (1e-16 m once); the width of each variable's bounds
  // in Υ is a length every design has (C0 for the control heights, the φ range times k for
  // the friction orientation).
  const LinearConstraints& upsilon = oracle.body().admissible_set();
  const double largest = alpha.size() ? alpha.cwiseAbs().maxCoeff() : 0.0;
  check.step_scale.resize(alpha.size());
  for (Eigen::Index k = 0; k < alpha.size(); ++k) {
    const double width = k < upsilon.lower.size() && k < upsilon.upper.size() ? upsilon.upper(k) - upsilon.lower(k)
                                                                             : std::numeric_limits<double>::infinity();
    check.step_scale(k) = std::isfinite(width) && width > 0 ? width : largest;
    if (!(check.step_scale(k) > 0))
      throw InvalidInput(fmt::format("check_gradient: design variable {} has no finite bounds in the admissible set "
                                     "and the design is 0: no length to scale the step by; expected bounds or a "
                                     "nonzero design",
                                     k));
  }
  check.evaluation = oracle.evaluate_design(alpha);
  if (!check.evaluation.ok) return check;
  const Evaluation& e = check.evaluation;
  check.cardinality = oracle.pieces(alpha, 1).cardinality;
  // Relative to the largest component, so near-zero components do not inflate the error.
  const double max_xi = e.subgradient.size() ? e.subgradient.cwiseAbs().maxCoeff() : 0.0;
  const double scale = std::max(max_xi, 1e-300);
  check.worst_relative_error = 0.0;
  check.step = 0.0;
  for (Eigen::Index k = 0; k < alpha.size(); ++k) {
    GradientCheck::Component c;
    c.step = relative_step * check.step_scale(k);
    const double h = c.step;
    check.step = std::max(check.step, h);
    Eigen::VectorXd a = alpha;
    a(k) += h;
    const Evaluation plus = oracle.evaluate_design(a, false);
    a(k) -= 2 * h;
    const Evaluation minus = oracle.evaluate_design(a, false);
    c.finite_difference = (plus.value - minus.value) / (2 * h);
    c.forward_difference = (plus.value - e.value) / h;
    c.backward_difference = (e.value - minus.value) / h;
    c.adjoint = e.subgradient(k);
    c.relative_error = std::abs(c.finite_difference - c.adjoint) / scale;
    if (plus.ok) compare_pieces(e, plus, +1, c);
    if (minus.ok) compare_pieces(e, minus, -1, c);
    c.verdict = verdict_of(c, scale);
    check.worst_relative_error = std::max(check.worst_relative_error, c.relative_error);
    check.components.push_back(std::move(c));
  }
  // What would make the comparison void.
  const double smallest_step = relative_step * (alpha.size() ? check.step_scale.minCoeff() : 0.0);
  check.noise_relative = kDerivativeStateTolerance * std::abs(e.value) / (smallest_step * scale);
  if (check.noise_relative > 1e-2)
    check.warnings.push_back(fmt::format(
        "the step h = {:.3e} is too small for the state's accuracy: a difference quotient is only known to about "
        "{:.1e} of max|xi| (|Theta| {:.3e} x relative accuracy {:.0e} / h); give a larger --step",
        smallest_step, check.noise_relative, std::abs(e.value), kDerivativeStateTolerance));
  if (!(max_xi > 0))
    check.warnings.push_back("xi = 0: Theta does not change to first order here, and relative errors are not defined");
  if (e.index_sets.count(sensitivity::NormalSet::kStrongContact) == 0)
    check.warnings.push_back("no contact node carries force at this design (I+ empty): the body does not touch the "
                             "foundation, and Theta does not depend on the design near it");
  return check;
}

}  // namespace frictopt::study
