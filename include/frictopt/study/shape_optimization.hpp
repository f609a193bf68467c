// SPDX-License-Identifier: MIT
// A shape optimization run: the bundle trust method (optim) on the oracle Θ(α) (ShapeOracle)
// over the admissible set Υ of the body (shape), with progress reported through a callback.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string_view>

#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {

/// Υ in the optimizer's form (same rows; the slope/volume names stay with shape).
optim::LinearConstraints to_optim_constraints(const shape::LinearConstraints& upsilon);

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
/// relative stationarity tolerance whatever the cost's units (spec 04 §7 "robustness"), and the
/// first step is at most the design range C0 (the optimizer's max_step_length).
optim::BundleTrust::Options default_study_options(const BodyDefinition& body);

/// Runs (or, from a checkpoint, resumes) the optimization. The oracle must belong to `body`.
/// `on_progress` is called after every outer iteration (history, checkpoints, VTK series); it
/// may stop the run. Bad input (e.g. an initial design outside Υ that cannot be projected)
/// throws InvalidInput.
[[nodiscard]] optim::BundleTrust::Summary optimize(ShapeOracle& oracle, optim::BundleTrust::Options options,
                                                   const ProgressCallback& on_progress,
                                                   const optim::BundleTrust::IterationSummary* checkpoint = nullptr);

}  // namespace frictopt::study
