// SPDX-License-Identifier: MIT
#include "frictopt/study/shape_optimization.hpp"

#include <chrono>

namespace frictopt::study {

optim::BundleTrust::Options default_study_options(const ElasticBody& body) {
  optim::BundleTrust::Options o;
  o.scale_objective = true;
  o.max_step_length = body.definition().admissible.upper_bound;
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
  const optim::BundleTrust method(options, oracle.body().admissible_set());
  return checkpoint ? method.resume(oracle, *checkpoint)
                    : method.minimize(oracle, oracle.body().definition().initial_design);
}

}  // namespace frictopt::study
