// SPDX-License-Identifier: MIT
// Safeguarded diagonal variable metric (docs/optim.md, "Variable metric").
//
// Why: the proximal term ‖d‖²/(2t) is Euclidean, so BundleTrust is invariant under x → c·x but
// not under x_i → c_i·x_i; where the variables have very different sizes (HS114: 1 to 1.6e4;
// BPfilter: a constraint x₆ = 1e4·x₂) it creeps along flat valleys. Variable-metric bundle
// methods (Lukšan & Vlček's PVAR/PNEW; Lemaréchal & Sagastizábal's variable prox-metric; the
// diagonal bundle method of Karmitsa 2015, JOTA 166) replace I/t by H/t with H estimated from
// subgradient differences at serious steps. A diagonal H is the per-coordinate unit the method
// is missing; it is estimated by least squares over the last pairs and safeguarded by a bound
// on its condition number and by resets (bundle_trust.cpp).
#include "frictopt/optim/diagonal_metric.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

namespace {
// A coordinate "did not move" over the pairs when its Σ s_ij² is below this share of the
// largest one: its quotient would be round-off.
constexpr double kMovedShare = 1e-12;
}  // namespace

Eigen::VectorXd diagonal_secant_estimate(const Eigen::MatrixXd& steps, const Eigen::MatrixXd& differences,
                                         const Eigen::VectorXd& previous, double ratio_bound) {
  const Eigen::Index n = steps.rows();
  if (differences.rows() != n || differences.cols() != steps.cols() ||
      (previous.size() != 0 && previous.size() != n))
    throw InvalidInput("diagonal_secant_estimate: steps " + std::to_string(steps.rows()) + "x" +
                       std::to_string(steps.cols()) + ", differences " + std::to_string(differences.rows()) +
                       "x" + std::to_string(differences.cols()) + ", previous " + std::to_string(previous.size()) +
                       "; expected equal shapes and previous empty or of size n");
  if (!(ratio_bound >= 1.0))
    throw InvalidInput("diagonal_secant_estimate: ratio_bound = " + std::to_string(ratio_bound) + "; expected >= 1");
  const Eigen::VectorXd moved = steps.cwiseAbs2().rowwise().sum();
  const Eigen::VectorXd curvature = steps.cwiseProduct(differences).rowwise().sum();
  const double largest = n > 0 && steps.cols() > 0 ? moved.maxCoeff() : 0.0;
  Eigen::VectorXd h = previous.size() == n ? previous : Eigen::VectorXd::Ones(n);
  // Geometric means of the estimated entries and of the entries they replace, so that the
  // estimates are brought to the level of the kept ones (the estimate has units f/x², h none).
  double log_estimated = 0.0, log_replaced = 0.0;
  int estimated = 0;
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    b(i) = 0.0;
    if (!(largest > 0.0) || moved(i) <= kMovedShare * largest || !(curvature(i) > 0.0)) continue;
    b(i) = curvature(i) / moved(i);
    if (!std::isfinite(b(i)) || !(b(i) > 0.0)) {
      b(i) = 0.0;
      continue;
    }
    log_estimated += std::log(b(i));
    log_replaced += std::log(h(i));
    ++estimated;
  }
  if (estimated == 0) return {};
  const double level = std::exp((log_replaced - log_estimated) / estimated);
  for (Eigen::Index i = 0; i < n; ++i)
    if (b(i) > 0.0) h(i) = b(i) * level;
  // Normalize to geometric mean 1 (t keeps its meaning) and bound the condition number.
  const double mean_log = h.array().log().mean();
  h *= std::exp(-mean_log);
  const double root = std::sqrt(ratio_bound);
  h = h.cwiseMax(1.0 / root).cwiseMin(root);
  return h;
}

bool update_diagonal_metric(DiagonalMetric& metric, const Eigen::VectorXd& s, const Eigen::VectorXd& u, int memory,
                            double ratio_bound, double damping) {
  if (s.size() != u.size() || s.size() == 0 || memory < 1 || !(damping > 0.0 && damping <= 1.0) ||
      (metric.steps.size() > 0 && metric.steps.rows() != s.size()))
    throw InvalidInput("update_diagonal_metric: s has size " + std::to_string(s.size()) + ", u " +
                       std::to_string(u.size()) + ", memory " + std::to_string(memory) +
                       ", damping " + std::to_string(damping) +
                       "; expected equal non-zero sizes matching the stored pairs, memory >= 1, damping in (0, 1]");
  if (!s.allFinite() || !u.allFinite() || !(s.dot(u) > 0.0)) return false;
  const Eigen::Index n = s.size();
  const Eigen::Index kept = std::min<Eigen::Index>(metric.steps.cols(), memory - 1);
  Eigen::MatrixXd steps(n, kept + 1), differences(n, kept + 1);
  if (kept > 0) {
    steps.leftCols(kept) = metric.steps.rightCols(kept);
    differences.leftCols(kept) = metric.differences.rightCols(kept);
  }
  steps.col(kept) = s;
  differences.col(kept) = u;
  // Each estimate starts from the identity, not from the last h: h then depends on the stored
  // pairs only (the pairs, not a chain of past estimates, are the state), and a coordinate that
  // no stored pair moved is neutral.
  const Eigen::VectorXd h = diagonal_secant_estimate(steps, differences, Eigen::VectorXd(), ratio_bound);
  metric.steps = std::move(steps);
  metric.differences = std::move(differences);
  if (h.size() == 0) return false;
  // Damping: h := h_old^{1−w}·h_est^w (h_old = 1 for the identity). A log-convex combination
  // keeps the geometric mean 1 and the bound κ. Why: the estimate from subgradient differences of
  // a nonsmooth f jumps with the pieces met (on polyhedral problems it is noise); undamped, the
  // metric changed the proximal term at every serious step and cost up to 7x the evaluations on
  // L1HILB and MXHILB (docs/optim-testset.md).
  if (damping < 1.0) {
    const Eigen::ArrayXd old =
        metric.h.size() == h.size() ? Eigen::ArrayXd(metric.h.array().log()) : Eigen::ArrayXd(Eigen::ArrayXd::Zero(h.size()));
    metric.h = ((1.0 - damping) * old + damping * h.array().log()).exp().matrix();
  } else {
    metric.h = h;
  }
  ++metric.updates;
  return true;
}

void reset_diagonal_metric(DiagonalMetric& metric) {
  if (metric.is_identity() && metric.steps.size() == 0) return;
  metric.h.resize(0);
  metric.steps.resize(0, 0);
  metric.differences.resize(0, 0);
  metric.updates = 0;
  ++metric.resets;
}

}  // namespace frictopt::optim
