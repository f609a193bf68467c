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


}  // namespace frictopt::study
