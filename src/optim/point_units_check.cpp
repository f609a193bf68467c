// SPDX-License-Identifier: MIT
// The confirmation of a "converged" in the per-coordinate units of the point found
// (docs/optim.md, "Confirmation in the point's units").
//
// Why: the proximal term ‖d‖²/(2t) of the direction QP and the stopping test are Euclidean, so
// the method is invariant under x → c·x but not under x_i → c_i·x_i. On HS114 (variables from
// 1 to 1.6e4) the run creeps along a flat valley with steps of length ≈ 2 while x* is ≈ 17 away;
// every local test relative to G and F passes there (the value error is slope × distance), and
// at ε = 1e-6 the run said "converged" 4.8e-6 off f*. In the variables x_i/|x_i| the same valley
// is crossed in a few steps. A stop that is stationary to ε is stationary in any units; a
// restart in the point's own units that still gains more than ε·F shows that it was not.
#include "frictopt/optim/point_units_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

namespace {

// The limits of `options` reached before a stop could be confirmed: the run reports them (with
// the best point found), not "converged" — an unconfirmed stop is no certified one.
BundleTrust::Summary limit_reached(BundleTrust::Summary s, bool evaluation_limit) {
  s.status = Status::kMaxIterations;
  s.stop_reason = evaluation_limit ? StopReason::kEvaluationLimit : StopReason::kIterationLimit;
  s.evaluation_limit = evaluation_limit;
  s.message = std::string("the ") + (evaluation_limit ? "evaluation" : "iteration") +
              " limit was reached before the stop could be confirmed in the point's units (" + s.message + ")";
  return s;
}

// Rounds of "restart in the point's units" before a run that keeps moving is reported as not
// certified (each round that moves is a full run: the bound keeps the whole thing finite).
constexpr int kMaxRounds = 5;

void require_size(const Eigen::Ref<const Eigen::VectorXd>& v, Eigen::Index n, const char* what) {
  if (v.size() != n)
    throw InvalidInput(std::string("confirm_in_point_units: ") + what + " has size " + std::to_string(v.size()) +
                       "; expected " + std::to_string(n) + " (the size of x0)");
}

}  // namespace

Eigen::VectorXd point_units(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& x_ref) {
  if (x.size() != x_ref.size())
    throw InvalidInput("point_units: x has size " + std::to_string(x.size()) + " and x_ref " +
                       std::to_string(x_ref.size()) + "; expected equal sizes");
  Eigen::VectorXd u = x.cwiseAbs().cwiseMax(x_ref.cwiseAbs());
  for (Eigen::Index i = 0; i < u.size(); ++i)
    if (!(u(i) > 0.0) || !std::isfinite(u(i))) u(i) = 1.0;  // no unit to read off: keep x_i's
  return u;
}

double point_units_spread(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& x_ref) {
  const Eigen::VectorXd u = point_units(x, x_ref);
  double largest = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    if (x(i) == 0.0 && x_ref(i) == 0.0) continue;  // u_i = 1 by default: no unit of its own
    largest = std::max(largest, u(i));
    smallest = std::min(smallest, u(i));
  }
  return largest > smallest ? largest / smallest : 1.0;
}

LinearConstraints in_units(const LinearConstraints& constraints, const Eigen::VectorXd& u) {
  LinearConstraints k = constraints;
  // x = u ∘ x̃: lb ≤ x ≤ ub reads lb/u ≤ x̃ ≤ ub/u, A x ≤ b reads (A diag u) x̃ ≤ b.
  if (k.lower.size() > 0) k.lower = k.lower.cwiseQuotient(u);
  if (k.upper.size() > 0) k.upper = k.upper.cwiseQuotient(u);
  if (k.A_in.size() > 0) k.A_in = k.A_in * u.asDiagonal();
  if (k.A_eq.size() > 0) k.A_eq = k.A_eq * u.asDiagonal();
  return k;
}

BundleTrust::Summary confirm_in_point_units(const BundleTrust::Options& options, const LinearConstraints& constraints,
                                            Oracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& x0,
                                            BundleTrust::Summary summary) {
  if (!summary.converged()) return summary;
  const Eigen::Index n = x0.size();
  require_size(summary.x, n, "summary.x");
  BundleTrust::Summary s = std::move(summary);
  int extra_evaluations = 0, extra_iterations = 0;
  for (int round = 0; round < kMaxRounds; ++round) {
    const Eigen::VectorXd u = point_units(s.x, x0);
    const LinearConstraints scaled = in_units(constraints, u);
    // ∂f̃(x̃) = u ∘ ∂f(u ∘ x̃), for f and for the pieces of a max (OracleResult::pieces).
    FunctionOracle scaled_oracle([&oracle, &u](const Eigen::Ref<const Eigen::VectorXd>& x) {
      OracleResult r = oracle.evaluate(x.cwiseProduct(u));
      if (r.ok && r.subgradient.size() == u.size()) r.subgradient = r.subgradient.cwiseProduct(u);
      for (PieceCut& p : r.pieces)
        if (p.subgradient.size() == u.size()) p.subgradient = p.subgradient.cwiseProduct(u);
      return r;
    });
    // The check only has to show whether a gain above ε·F exists: it stops as soon as it has
    // gained that much, and after one bundle's worth of iterations (j_max = max(2n, 10)).
    // The limits of `options` bound the totals, check included.
    const double f_stop = s.f - options.epsilon * s.value_scale;
    const int planned = 2 * static_cast<int>(std::max<Eigen::Index>(n, 5));
    const int iterations_left = options.max_iterations - s.iterations - extra_iterations;
    const int evaluations_left = options.max_evaluations - s.evaluations - extra_evaluations;
    if (iterations_left < 1 || evaluations_left < 1) return limit_reached(std::move(s), evaluations_left < 1);
    // The check and the continued run measure F's decrease from the first run's f(x_1), so that
    // their tests keep its scale (BundleTrust::Options::value_reference).
    const double reference = s.last_state.f_start * s.last_state.objective_scale;
    BundleTrust::Options check = options;
    check.value_reference = std::isfinite(reference) ? reference : options.value_reference;
    check.confirm_in_point_units = false;  // this is the check
    check.confirm_by_restart = false;      // and a restart check of its own
    check.max_iterations = std::min(planned, iterations_left);
    check.max_evaluations = evaluations_left;
    check.keep_history = false;
    check.on_iteration = [f_stop](const BundleTrust::IterationSummary& it) {
      return it.f < f_stop ? CallbackResult::kStop : CallbackResult::kContinue;
    };
    const BundleTrust::Summary r = BundleTrust(check, scaled).minimize(scaled_oracle, s.x.cwiseQuotient(u));
    extra_evaluations += r.evaluations;
    extra_iterations += r.iterations;
    // The run ends here: the better of x and the check's point, with the counters as totals.
    const auto end_with_best = [&] {
      if (r.f < s.f) {
        s.x = r.x.cwiseProduct(u);
        s.f = r.f;
      }
      s.evaluations += extra_evaluations;
      s.iterations += extra_iterations;
    };
    if (!(r.f < f_stop) && r.status == Status::kMaxIterations && (r.evaluation_limit || r.iterations < planned)) {
      end_with_best();
      return limit_reached(std::move(s), r.evaluation_limit);
    }
    if (!(r.f < f_stop)) {  // confirmed: no gain above ε·F in the point's units
      end_with_best();
      std::ostringstream m;
      m << s.message << "; confirmed in the point's units (" << round + 1 << " check(s), " << extra_evaluations
        << " more evaluations)";
      s.message = m.str();
      return s;
    }
    // x was not stationary to ε in these units: go on in them with the full options.
    BundleTrust::Options go_on = options;
    go_on.value_reference = check.value_reference;
    go_on.confirm_in_point_units = false;  // its stop is checked by the next round here
    go_on.on_iteration = nullptr;
    go_on.max_iterations = options.max_iterations - s.iterations - extra_iterations;
    go_on.max_evaluations = options.max_evaluations - s.evaluations - extra_evaluations;
    if (go_on.max_iterations < 1 || go_on.max_evaluations < 1) {
      end_with_best();  // r gained more than ε·F: it is the better point
      return limit_reached(std::move(s), go_on.max_evaluations < 1);
    }
    BundleTrust::Summary next = BundleTrust(go_on, scaled).minimize(scaled_oracle, r.x);
    next.x = next.x.cwiseProduct(u);
    extra_evaluations += next.evaluations;
    extra_iterations += next.iterations;
    next.evaluations = s.evaluations + extra_evaluations;
    next.iterations = s.iterations + extra_iterations;
    next.start_projected = s.start_projected;
    next.projection_distance = s.projection_distance;
    extra_evaluations = 0;
    extra_iterations = 0;
    s = std::move(next);
    if (!s.converged()) return s;  // the continued run says why it stopped
  }
  s.status = Status::kStalled;
  s.stop_reason = StopReason::kStationarityNotCertified;
  s.message = "every stop was followed by a gain above epsilon*F in the point's units (" +
              std::to_string(kMaxRounds) + " rounds): x is not certified stationary";
  return s;
}

}  // namespace frictopt::optim
