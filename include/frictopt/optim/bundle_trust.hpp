// SPDX-License-Identifier: MIT
// The bundle trust (BT) method of Schramm & Zowe for locally Lipschitz, nonconvex, nonsmooth f
// over a polyhedron Υ, as consolidated in spec 04 §6 (with the readings of spec 04 §5).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

namespace frictopt::optim {

/// One bundle element (spec 04 §5 item 9): a subgradient with its linearization error α,
/// distance measure s and locality measure β = max(|α|, γ s²) relative to the current center.
struct BundleElement {
  Eigen::VectorXd g;        ///< subgradient at y (or the aggregate z for an aggregate element)
  double lin_err = 0.0;     ///< α = f(x_c) − f(y) − gᵀ(x_c − y)  (spec 04 §2)
  double distance = 0.0;    ///< s: ‖x_c − y‖ (real) or its triangle-inequality bound (aggregate)
  double locality = 0.0;    ///< β = max(|α|, γ s²)  (spec 04 §5 item 8)
  Eigen::VectorXd y;        ///< trial point; empty for an aggregate element
  bool is_center = false;   ///< y is the current stability center (β = 0)
  [[nodiscard]] bool is_aggregate() const { return y.size() == 0; }
};

/// How an outer iteration of BT ended.
enum class StepKind { kStart, kSerious, kNull, kLineSearchSerious, kLineSearchNull };
std::string_view to_string(StepKind kind);

class BundleTrust {
 public:
  /// Everything the method state holds after an outer iteration: enough to log progress, to
  /// write a checkpoint and to resume the run with `resume` (x, f, t, aggregates, bundle).
  struct IterationSummary {
    int iteration = 0;          ///< outer iterations k done (= serious + null steps)
    int evaluations = 0;        ///< oracle calls so far (including failed ones)
    int serious_steps = 0;
    int null_steps = 0;
    StepKind step = StepKind::kStart;
    int inner_trials = 0;       ///< QPs solved in this inner iteration
    Eigen::VectorXd x;          ///< stability center x_k (feasible)
    double f = kNaN;            ///< f(x_k) (unscaled)
    double t = kNaN;            ///< trust parameter t_k used for the accepted trial
    double t_max = kNaN;        ///< T actually used
    double stationarity = kNaN; ///< ‖z + ω‖ = ‖d‖/t of the last QP (spec 04 §3.2)
    double aggregate_error = kNaN;  ///< −‖d‖²/t − v of the last QP
    double predicted_change = kNaN; ///< v of the last QP (< 0)
    Eigen::VectorXd z_prev;     ///< aggregate subgradient z of the last QP at x_k
    double sigma_prev = kNaN;   ///< aggregate locality σ of the last QP at x_k
    std::vector<BundleElement> bundle;  ///< bundle after the update (size ≤ j_max)
    double objective_scale = 1.0;       ///< f seen by the method = f / objective_scale
  };
  using IterationCallback = std::function<CallbackResult(const IterationSummary&)>;

  struct Options {
    // Upper bound T on the trust parameter t (spec 04 §4). NaN: automatic, T = max_step_length
    // / max(‖g_1‖, 1e-12), "a first step of at most C_0" (spec 04 §7). Otherwise > 0.
    double t_max = kNaN;
    // C_0 of the automatic T: length of the first step (units of x); the application should
    // pass its design range. Default 10, chosen on the Lukšan–Vlček set (docs/optim.md): with
    // 1, T is so small that Rosenbrock and Maxquad crawl; with 100, HS78 (unbounded below
    // away from its local minimum) escapes to −∞. > 0.
    double max_step_length = 10.0;
    // t_0 (spec 04 §5 item 3). NaN: t_0 = T. Otherwise in (0, T].
    double t_initial = kNaN;
    // Descent fraction m_1, model-change fraction m_2 and locality fraction m_3 (spec 04 §7:
    // 0.1, 0.5, 0.5). Need 0 < m1 < m2 < 1 and 0 < m3 < 1.
    double m1 = 0.1;
    double m2 = 0.5;
    double m3 = 0.5;
    // ε of the "almost stationary" test ‖z + ω‖ ≤ ε and σ + μᵀ(c − Cx) ≤ ε (spec 04 §5 item 2;
    // the thesis uses 1e-4 in all examples, §5.2). >= 0.
    double epsilon = 1e-4;
    // Bundle capacity j_max. 0: automatic max(2n, 10) — spec 04 §7 proposes 2d; the floor of 10
    // is our reading for small n, where 2n = 4 cannot hold the center, the aggregate and one cut
    // per active piece (DEM, CB3: thousands of null steps with 4, a few dozen with 10).
    // Otherwise >= 3.
    int max_bundle_size = 0;
    // γ of β = max(|α|, γ s²) (spec 04 §5 item 8). > 0.
    double locality_weight = 1.0;
    // Reading (a′) of spec 04 §5 item 5: also enlarge t when a descent step is "too short".
    // false reproduces the thesis's printed algorithm (t can only decrease).
    bool enlarge_t = true;
    // δ_T of (a′): no enlargement when u − t ≤ δ_T·T. In (0, 1).
    double enlarge_margin = 1e-3;
    // Limits (spec 04 §7): outer iterations k_max, oracle calls, QPs per inner iteration,
    // t_min = t_min_relative·T, line-search step s_min. All >= 1 / > 0.
    int max_iterations = 500;
    int max_evaluations = 5000;
    int max_inner_iterations = 50;
    double t_min_relative = 1e-12;
    double line_search_min_step = 1e-6;
    // Minimize f/|f(x_1)| instead of f (spec 04 §7, "robustness"); default off (reproduction).
    bool scale_objective = false;
    // A start point violating Υ by more than this (user units, max norm) is projected.  > 0.
    double feasibility_tolerance = 1e-9;
    // Keep the per-iteration history in the Summary.
    bool keep_history = true;
    // Called after every outer iteration; returning kStop ends the run (kStoppedByCallback).
    IterationCallback on_iteration;
    void validate() const;  // throws InvalidInput naming field, value and expectation
  };

  /// One line of Summary::history.
  struct HistoryEntry {
    int iteration = 0;
    int evaluations = 0;
    StepKind step = StepKind::kStart;
    double f = kNaN;
    double t = kNaN;
    double stationarity = kNaN;
    double aggregate_error = kNaN;
    int bundle_size = 0;
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "minimize() has not been called";
    /// With status kMaxIterations: which limit stopped the run (Status has one value for both).
    bool evaluation_limit = false;  ///< true: max_evaluations, false: max_iterations
    Eigen::VectorXd x;              ///< final stability center (feasible)
    double f = kNaN;                ///< f(x) (unscaled)
    int iterations = 0;             ///< outer iterations (serious + null steps)
    int serious_steps = 0;
    int null_steps = 0;
    int line_searches = 0;
    int evaluations = 0;            ///< oracle calls, including failed ones
    int failed_evaluations = 0;     ///< calls that returned !ok or non-finite numbers
    int qp_solves = 0;
    double stationarity = kNaN;     ///< final ‖z + ω‖ (spec 04 §3.2)
    double aggregate_error = kNaN;  ///< final σ + μᵀ(c − Cx)
    double t = kNaN;                ///< last trust parameter
    double t_max_given = kNaN;      ///< Options::t_max (NaN = automatic)
    double t_max_used = kNaN;       ///< T used
    int bundle_size_given = 0;      ///< Options::max_bundle_size (0 = automatic)
    int bundle_size_used = 0;       ///< j_max used
    bool start_projected = false;   ///< x0 was infeasible and was projected onto Υ
    double projection_distance = 0.0;
    double objective_scale = 1.0;
    double time_seconds = 0.0;
    std::vector<HistoryEntry> history;
    IterationSummary last_state;    ///< the state after the last outer iteration (for resume)
    [[nodiscard]] bool converged() const { return status == Status::kConverged; }
    [[nodiscard]] std::string brief_report() const;
  };

  /// Validates `options` and `constraints` shapes are checked at minimize() (n comes from x0).
  /// Throws InvalidInput on invalid options.
  explicit BundleTrust(Options options, LinearConstraints constraints = {});

  /// Minimizes f over Υ from x0. If x0 violates Υ it is projected (Summary::start_projected);
  /// throws InvalidInput if Υ is empty, if constraint shapes do not match x0, if x0 is not
  /// finite, or if the oracle returns a subgradient of the wrong size.
  [[nodiscard]] Summary minimize(Oracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& x0) const;

  /// Continues a run from a state passed to the callback (or Summary::last_state) without
  /// re-evaluating anything; counters continue from the checkpoint. Limits apply to the totals.
  [[nodiscard]] Summary resume(Oracle& oracle, const IterationSummary& checkpoint) const;

  [[nodiscard]] const Options& options() const { return options_; }

 private:
  Options options_;
  LinearConstraints constraints_;
};

}  // namespace frictopt::optim
