// SPDX-License-Identifier: MIT
#include "frictopt/study/shape_optimization.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "frictopt/core/error.hpp"
#include "frictopt/study/certificate.hpp"

namespace frictopt::study {

void require_admissible_design(const ElasticBody& body, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                               double tolerance, std::string_view who) {
  const Eigen::Index d = body.num_design_variables();
  if (alpha.size() != d)
    throw InvalidInput(fmt::format("{}: the design has {} entries; expected {} (the shape's control points{})", who,
                                   alpha.size(), d, body.orientation_design() ? " and the friction orientation" : ""));
  // N_Υ(α) and the state exist on Υ only: refuse an outside design before any solve.
  const LinearConstraints& upsilon = body.admissible_set();
  const double violation = upsilon.max_violation(alpha);
  if (!(violation <= tolerance * std::max(1.0, alpha.lpNorm<Eigen::Infinity>())))
    throw InvalidInput(fmt::format("{}: the design violates the admissible set by {:.3e}; expected a design in Υ ({})",
                                   who, violation, upsilon.describe_violation(alpha, 0.0)));
}

namespace {

void confirm_with_certificate(ShapeOracle& oracle, optim::BundleTrust::Summary& summary) {
  // The optimizer certifies (ρ, δ)-stationarity from the subgradients its bundle met within ρ of
  // x; `frictopt certify` computes the exact Clarke distance at x over every enumerated piece.
  // The two can disagree (ex521: bundle 7.5e-5·G, certify 2.9e-3 of max‖ξ‖, docs/studies.md
  // §5): a run reports "converged" only if certify's test passes too, at certify's tolerance.
  CertifyOptions co;
  co.clarke_only = true;
  const Certificate c = certify(oracle, summary.x, co);
  if (c.status == Status::kConverged && c.clarke_stationary) return;
  summary.status = Status::kStalled;
  summary.stop_reason = optim::StopReason::kStationarityNotCertified;
  summary.message =
      c.status != Status::kConverged
          ? fmt::format("the optimizer's test and certificate passed, but the study certificate failed: {}", c.message)
          : fmt::format("the optimizer's test and certificate passed (bundle certificate {:.3e}), but the Clarke "
                        "distance over all {} enumerated pieces at x is {:.3e} of max|xi| > {:.0e}: x is not "
                        "certified stationary (frictopt certify)",
                        summary.certificate_distance, c.subgradients.cols(), c.relative_distance,
                        co.stationary_tolerance);
}

}  // namespace

optim::BundleTrust::Options default_study_options(const BodyDefinition& body) {
  optim::BundleTrust::Options o;
  o.scale_objective = true;
  o.max_step_length = body.admissible.upper_bound;
  o.max_iterations = 100;
  o.max_evaluations = 400;
  return o;
}

optim::BundleTrust::Summary optimize(ShapeOracle& oracle, optim::BundleTrust::Options options,
                                     const ProgressCallback& on_progress,
                                     const optim::BundleTrust::IterationSummary* checkpoint) {
  const auto start = std::chrono::steady_clock::now();
  if (on_progress) {
    options.on_iteration = [&](const optim::BundleTrust::IterationSummary& s) {
      // x_k was evaluated by the method (cached), except a centre read from a checkpoint that
      // this process has not evaluated: it is reported empty rather than solved again.
      static const Evaluation kNotEvaluated;
      const Evaluation* cached = oracle.find_evaluation(s.x);
      const Evaluation& center = cached ? *cached : kNotEvaluated;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return on_progress({s, center, elapsed, oracle.num_state_solves()});
    };
  }
  // The other load cases' cuts cost an adjoint each: computed only when the method uses them.
  oracle.set_case_cuts(options.use_piece_cuts);
  const optim::BundleTrust method(options, oracle.body().admissible_set());
  optim::BundleTrust::Summary summary = checkpoint ? method.resume(oracle, *checkpoint)
                                                   : method.minimize(oracle, oracle.body().initial_design());
  if (summary.converged() && options.certify_stationarity && oracle.body().definition().contact)
    confirm_with_certificate(oracle, summary);
  return summary;
}

std::string_view to_string(OptimizationOutcome::Kind kind) {
  switch (kind) {
    case OptimizationOutcome::Kind::kCertified: return "certified";
    case OptimizationOutcome::Kind::kLimitReached: return "limit_reached";
    case OptimizationOutcome::Kind::kNeedsAttention: return "needs_attention";
    case OptimizationOutcome::Kind::kFailed: return "failed";
  }
  return "unknown";
}

OptimizationOutcome assess_outcome(const optim::BundleTrust::Summary& summary, const Evaluation& final) {
  using Kind = OptimizationOutcome::Kind;
  OptimizationOutcome o;
  if (!final.ok) {
    o.kind = Kind::kFailed;
    return o;
  }
  switch (summary.status) {
    case Status::kConverged: o.kind = Kind::kCertified; break;
    case Status::kMaxIterations: o.kind = Kind::kLimitReached; break;
    case Status::kStalled:
      o.kind = Kind::kNeedsAttention;
      o.attention.push_back(fmt::format("the method stopped without certifying stationarity ({}): {}",
                                        optim::to_string(summary.stop_reason), summary.message));
      break;
    default: o.kind = Kind::kFailed; return o;
  }
  // With every contact node separated (M) or touching without force (I0), the state and Θ do not
  // change under small design changes: ξ = 0 and the certificate holds trivially.
  const int strong = final.index_sets.count(sensitivity::NormalSet::kStrongContact);
  if (strong == 0) {
    o.kind = Kind::kNeedsAttention;
    o.attention.push_back(fmt::format(
        "no contact at the final design: no contact node carries force (index sets {}), so the body does not "
        "touch the foundation; Θ does not depend on the design near it and stationarity there says nothing "
        "(a cost such as target_pressure is lowered by lifting the body off). Bound the design (upper_bound, "
        "slope_bound, volume) or press by a force",
        final.index_sets.summary()));
  }
  return o;
}

}  // namespace frictopt::study
