// SPDX-License-Identifier: MIT
#include "frictopt/optim/projected_subgradient.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

void ProjectedSubgradient::Options::validate() const {
  if (!(initial_step > 0.0) || !std::isfinite(initial_step))
    throw InvalidInput("ProjectedSubgradient::Options::initial_step = " + std::to_string(initial_step) +
                       "; expected finite and > 0");
  if (max_evaluations < 1)
    throw InvalidInput("ProjectedSubgradient::Options::max_evaluations = " +
                       std::to_string(max_evaluations) + "; expected >= 1");
  if (!(feasibility_tolerance > 0.0))
    throw InvalidInput("ProjectedSubgradient::Options::feasibility_tolerance = " +
                       std::to_string(feasibility_tolerance) + "; expected > 0");
}

std::string ProjectedSubgradient::Summary::brief_report() const {
  std::ostringstream s;
  s << "ProjectedSubgradient: " << to_string(status) << ", best f = " << f << ", evaluations "
    << evaluations << ", " << time_seconds << " s";
  if (!message.empty()) s << " — " << message;
  return s.str();
}

ProjectedSubgradient::ProjectedSubgradient(Options options, LinearConstraints constraints)
    : options_(options), constraints_(std::move(constraints)) {
  options_.validate();
}

namespace {
// Bounds alone project by clamping; anything else goes through the projection QP.
Eigen::VectorXd project(const LinearConstraints& k, const Eigen::VectorXd& x) {
  if (k.empty()) return x;
  if (k.A_in.rows() == 0 && k.A_eq.rows() == 0) {
    Eigen::VectorXd y = x;
    if (k.lower.size() > 0) y = y.cwiseMax(k.lower);
    if (k.upper.size() > 0) y = y.cwiseMin(k.upper);
    return y;
  }
  const Projection p = project_onto(k, x);
  if (p.feasible_set_empty) throw InvalidInput("ProjectedSubgradient: the feasible set is empty (" + p.message + ")");
  return p.point;
}
}  // namespace

ProjectedSubgradient::Summary ProjectedSubgradient::minimize(
    Oracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& x0) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = x0.size();
  if (n == 0 || !x0.allFinite())
    throw InvalidInput("ProjectedSubgradient::minimize: x0 must be non-empty and finite");
  constraints_.validate(n);
  Summary s;
  Eigen::VectorXd x = x0;
  if (constraints_.max_violation(x) > options_.feasibility_tolerance) x = project(constraints_, x);
  double a = options_.initial_step;
  int k = 0;
  while (s.evaluations < options_.max_evaluations) {
    ++s.evaluations;
    const OracleResult r = oracle.evaluate(x);
    if (r.ok && r.subgradient.size() != n)
      throw InvalidInput("ProjectedSubgradient: the oracle returned a subgradient of size " +
                         std::to_string(r.subgradient.size()) + "; expected " + std::to_string(n));
    if (!r.ok || !std::isfinite(r.value) || !r.subgradient.allFinite()) {
      ++s.failed_evaluations;
      if (s.x.size() == 0) {
        s.status = Status::kNumericalFailure;
        s.message = "the oracle could not evaluate the starting point";
        s.x = x;
        break;
      }
      // Step back towards the best point with half the step.
      a *= 0.5;
      x = s.x;
      continue;
    }
    if (s.x.size() == 0 || r.value < s.f) {
      s.x = x;
      s.f = r.value;
    }
    const double gn = r.subgradient.norm();
    if (gn == 0.0 && constraints_.empty()) {
      s.status = Status::kConverged;
      s.message = "zero subgradient";
      break;
    }
    ++k;
    const double step = a / std::sqrt(static_cast<double>(k));
    x = project(constraints_, x - step * r.subgradient / std::max(gn, 1e-300));
  }
  if (s.status == Status::kNotRun) {
    s.status = Status::kMaxIterations;
    s.message = "evaluation budget spent (the method has no stopping test)";
  }
  s.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace frictopt::optim
