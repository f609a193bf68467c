// SPDX-License-Identifier: MIT
#include "frictopt/study/shape_optimization.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "frictopt/core/error.hpp"

namespace frictopt::study {

optim::LinearConstraints to_optim_constraints(const shape::LinearConstraints& u) {
  optim::LinearConstraints c;
  c.lower = u.lower;
  c.upper = u.upper;
  c.A_in = u.A_in;
  c.b_in = u.b_in;
  c.A_eq = u.A_eq;
  c.b_eq = u.b_eq;
  return c;
}

void require_admissible_design(const ElasticBody& body, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                               double tolerance, std::string_view who) {
  const Eigen::Index d = body.definition().shape.num_controls();
  if (alpha.size() != d)
    throw InvalidInput(fmt::format("{}: the design has {} entries; expected {} (the shape's control points)", who,
                                   alpha.size(), d));
  // N_Υ(α) and the state exist on Υ only: refuse an outside design before any solve.
  const shape::LinearConstraints& upsilon = body.admissible_set();
  const double violation = to_optim_constraints(upsilon).max_violation(alpha);
  if (!(violation <= tolerance * std::max(1.0, alpha.lpNorm<Eigen::Infinity>())))
    throw InvalidInput(fmt::format("{}: the design violates the admissible set by {:.3e}; expected a design in Υ ({})",
                                   who, violation, upsilon.describe_violation(alpha, 0.0)));
}

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
  const optim::BundleTrust method(options, to_optim_constraints(oracle.body().admissible_set()));
  return checkpoint ? method.resume(oracle, *checkpoint)
                    : method.minimize(oracle, oracle.body().definition().initial_design);
}

}  // namespace frictopt::study
