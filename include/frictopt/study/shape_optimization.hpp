// SPDX-License-Identifier: MIT
// A shape optimization run: the bundle trust method (optim) on the oracle Θ(α) (ShapeOracle)
// over the admissible set Υ of the body (shape), with progress reported through a callback.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {

/// What a progress line and a history row need after each outer iteration.
struct OptimizationProgress {
  const optim::BundleTrust::IterationSummary& method;  ///< the optimizer's state (checkpointable)
  /// The oracle's evaluation at x_k; empty (ok == false, zero counters) when x_k comes from a
  /// checkpoint and was not evaluated in this process (a resumed run does not re-solve it).
  const Evaluation& center;
  double elapsed_seconds = 0.0;
  int state_solves = 0;                                ///< state problems solved so far
};
using ProgressCallback = std::function<CallbackResult(const OptimizationProgress&)>;

/// The one admissibility check of a given design (certify, check-gradient, optimize's start):
/// throws InvalidInput "<who>: ..." when α does not have one entry per control point or
/// violates Υ by more than `tolerance`·max(1, ‖α‖∞), naming the violated rows.
void require_admissible_design(const ElasticBody& body, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                               double tolerance, std::string_view who);

/// Bundle trust options for shape studies: the objective is scaled by |Θ(α⁰)| so that ε is a
/// relative stationarity tolerance whatever the cost's units (docs/optim.md, "The stopping test"),
/// and the first step is at most the design range C0 (the optimizer's max_step_length).
optim::BundleTrust::Options default_study_options(const BodyDefinition& body);

/// Runs (or, from a checkpoint, resumes) the optimization. The oracle must belong to `body`.
/// `on_progress` is called after every outer iteration (history, checkpoints, VTK series); it
/// may stop the run. Bad input (e.g. an initial design outside Υ that cannot be projected)
/// throws InvalidInput.
[[nodiscard]] optim::BundleTrust::Summary optimize(ShapeOracle& oracle, optim::BundleTrust::Options options,
                                                   const ProgressCallback& on_progress,
                                                   const optim::BundleTrust::IterationSummary* checkpoint = nullptr);

/// How a finished optimization ended, for exit codes and summaries (README, "Exit codes"): a
/// result the user can use as it is, one written but needing attention, or a failure.
struct OptimizationOutcome {
  enum class Kind {
    kCertified,       ///< converged: certified stationary, in contact
    kLimitReached,    ///< the iteration or evaluation limit the case set was reached first
    kNeedsAttention,  ///< a result was written, but it is not certified or not meaningful (`attention`)
    kFailed           ///< the method or the final state solve failed (numerical failure)
  };
  Kind kind = Kind::kFailed;
  /// Why the result needs attention (empty for kCertified and kLimitReached), one sentence each.
  std::vector<std::string> attention;
};

[[nodiscard]] std::string_view to_string(OptimizationOutcome::Kind kind);

/// The outcome of a run from the method's summary and the evaluation at its final design:
/// kStalled (stationarity not certified, an inner iteration that found no step) needs attention,
/// and so does any final design at which no contact node carries force (I+ empty): there the
/// state does not depend on the design near it, every such design is stationary, and a cost such
/// as target_pressure can be lowered by lifting the body off the foundation (docs/optim.md,
/// "Outcomes").
[[nodiscard]] OptimizationOutcome assess_outcome(const optim::BundleTrust::Summary& summary, const Evaluation& final);

}  // namespace frictopt::study
