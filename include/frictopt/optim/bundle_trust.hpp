// SPDX-License-Identifier: MIT
// The bundle trust (BT) method of Schramm & Zowe for locally Lipschitz, nonconvex, nonsmooth f
// over a polyhedron Υ (thesis §2.5), as described in docs/theory/bundle-trust.md (with its
// readings of the printed algorithm, §4–§5).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/optim/diagonal_metric.hpp"
#include "frictopt/optim/linear_constraints.hpp"
#include "frictopt/optim/oracle.hpp"

namespace frictopt::optim {

/// One bundle element (docs/theory/bundle-trust.md §2, §5): a subgradient with its linearization
/// error α, distance measure s and locality measure β = max(|α|, γ s²/t_1) relative to the current
/// center.
struct BundleElement {
  Eigen::VectorXd g;        ///< subgradient at y (or the aggregate z for an aggregate element)
  double lin_err = 0.0;     ///< α = f(x_c) − f(y) − gᵀ(x_c − y)  (docs/theory/bundle-trust.md §2)
  double distance = 0.0;    ///< s: ‖x_c − y‖ (real) or its triangle-inequality bound (aggregate)
  double locality = 0.0;    ///< β = max(|α|, γ s²/t_1) (docs/optim.md)
  Eigen::VectorXd y;        ///< trial point; empty for an aggregate element
  bool is_center = false;   ///< y is the current stability center (β = 0)
  /// f(y) − φ(y) >= 0 for the cut of a piece φ of a max taken at y (OracleResult::pieces); 0 for
  /// a subgradient of f itself; the θ-weighted mean for an aggregate. Only a cut with a gap
  /// within the test's tolerance is a subgradient of f at y and may enter the certificate.
  double piece_gap = 0.0;
  [[nodiscard]] bool is_aggregate() const { return y.size() == 0; }
};

/// How an outer iteration of BT ended.
enum class StepKind { kStart, kSerious, kNull, kLineSearchSerious, kLineSearchNull };
std::string_view to_string(StepKind kind);

/// Why a BundleTrust run ended (finer than Status, which it maps to: see docs/optim.md).
enum class StopReason {
  kNotRun,
  kCertifiedStationary,    ///< stopping test met and the stationarity certificate confirms it
  kStationarityNotCertified,  ///< stopping test met, but the certificate at x does not confirm it
  kIterationLimit,         ///< max_iterations
  kEvaluationLimit,        ///< max_evaluations
  kInnerIterationFailed,   ///< docs/theory/bundle-trust.md §4: too many trials, or t < t_min
  kDirectionQpFailed,      ///< the direction-finding QP returned no solution
  kStartNotEvaluated,      ///< the oracle failed at x_1
  kStoppedByCallback
};
std::string_view to_string(StopReason reason);

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
    double t = kNaN;            ///< trust parameter for the next inner iteration
    double t_max = kNaN;        ///< upper end of t in the last inner iteration (docs/optim.md)
    double stationarity = kNaN; ///< ‖z + ω‖ = ‖d‖/t of the last QP (docs/theory/bundle-trust.md §3)
    double aggregate_error = kNaN;  ///< −‖d‖²/t − v of the last QP
    double predicted_change = kNaN; ///< v of the last QP (< 0)
    Eigen::VectorXd z_prev;     ///< aggregate subgradient z of the last QP at x_k
    double sigma_prev = kNaN;   ///< aggregate locality σ of the last QP at x_k
    std::vector<BundleElement> bundle;  ///< bundle after the update (size ≤ j_max)
    double objective_scale = 1.0;       ///< f seen by the method = f / objective_scale
    /// Scales of the relative stopping test (docs/optim.md), in the method's (scaled) units:
    /// G = max(‖g(x_k)‖, √ε·‖g(x_1)‖), F = √ε·max(f(x_1) − f(x_k), ε·t_1‖g(x_1)‖²).
    double subgradient_scale = kNaN;
    double value_scale = kNaN;
    double f_start = kNaN;      ///< f(x_1) in the method's units (for F)
    double g_start_norm = kNaN; ///< ‖g(x_1)‖ in the method's units (for G)
    double t_start = kNaN;      ///< t_1 (t_min = t_min_relative·t_1)
    /// Unit of the locality γ s²/t_ref: t_1, grown to 10·‖x_k − x_1‖∞/‖g(x_1)‖ once the
    /// centers have moved that far (docs/optim.md).
    double t_reference = kNaN;
    Eigen::VectorXd x_start;    ///< x_1 (for t_reference); empty in old checkpoints: x_k is used
    Eigen::VectorXd g_start;    ///< g(x_1) in the method's units (G in the variable metric); may be empty
    /// Variable metric of the proximal term (Options::variable_metric; identity otherwise).
    DiagonalMetric metric;
    int null_streak = 0;        ///< null steps since the last serious step (metric reset)
    /// The run's own safeguards, so that `resume` continues exactly where the run stopped:
    /// bundle restarts and tightenings of the stopping test so far (at most kMaxRestarts and
    /// kMaxTightenings per run), the factor of ε they left, whether the oracle's resolution was
    /// reached, and j_max as grown by piece cuts (0: not recorded; resume takes the automatic size).
    int restarts = 0;
    int tightenings = 0;
    double test_factor = 1.0;
    bool resolution_reached = false;
    int bundle_size_used = 0;
    /// Restart checks started (Options::confirm_by_restart) and the one in progress: f at the
    /// stop under check (method's units; NaN when none) and its tolerance ε·F.
    int restart_checks = 0;
    double check_value = kNaN;
    double check_tolerance = kNaN;
    int check_iteration = 0;  ///< outer iteration at which the check in progress started
  };
  using IterationCallback = std::function<CallbackResult(const IterationSummary&)>;

  struct Options {
    // Hard upper bound T on the trust parameter t. NaN (default): none — t adapts freely within
    // the per-iteration limit t_growth_limit. Otherwise > 0.
    double t_max = kNaN;
    // Length of the FIRST trial step (units of x): t_1 = max_step_length / ‖g_1‖ (C₀ of
    // docs/optim.md). Only a starting value: from then on t adapts (docs/optim.md, "step bound").
    // NaN (default): 10·‖x_1‖∞, or 10 when x_1 = 0. The application passes its design range.
    // NaN or > 0.
    double max_step_length = kNaN;
    // t_1 given directly. NaN: max_step_length / ‖g_1‖. Otherwise > 0 (and <= t_max).
    double t_initial = kNaN;
    // Descent fraction m_1, model-change fraction m_2 and locality fraction m_3
    // (docs/theory/bundle-trust.md §4; defaults 0.1, 0.5, 0.5). Need 0 < m1 < m2 < 1 and
    // 0 < m3 < 1.
    double m1 = 0.1;
    double m2 = 0.5;
    double m3 = 0.5;
    // m_R of Kiwiel's weight update (Kiwiel 1990, "Proximity control in bundle methods"): after
    // a serious step whose actual change Δ reaches m_R times the predicted change v, t grows to
    // the interpolated t/(2(1 − Δ/v)), by at most t_growth_limit. Need m1 <= m_R < 1.
    double model_agreement = 0.5;
    // Largest factor by which t may grow from one outer iteration to the next (Kiwiel's
    // safeguard u_{k+1} >= u_k/10). > 1.
    double t_growth_limit = 10.0;
    // ε of the RELATIVE "almost stationary" test (docs/optim.md): ‖z + ω‖ <= ε·G and
    // σ + μᵀ(c − Cx) <= ε·F, G = max(‖g(x_k)‖, √ε‖g(x_1)‖), F = √ε·max(f(x_1) − f(x_k),
    // ε·t_1‖g(x_1)‖²) (the decrease made). The test reads the same for a·f + b and for x scaled
    // by any factor (docs/optim.md, "Invariance"). >= 0.
    // Default 1e-5: a factor 10 below the accuracy 1e-4 the test set asks for, because the test
    // bounds the stationarity measures, not |f − f*| (docs/optim-testset.md).
    double epsilon = 1e-5;
    // Bundle capacity j_max. 0: automatic max(2n, 10) — 2n is the usual choice; the floor of 10
    // is our reading for small n, where 2n = 4 cannot hold the center, the aggregate and one cut
    // per active piece (DEM, CB3: thousands of null steps with 4, a few dozen with 10).
    // With piece cuts (OracleResult::pieces) the automatic size adds two evaluations' worth of
    // cuts, 2·(1 + pieces) (docs/optim.md, "Cuts of the pieces of a max"). Otherwise >= 3.
    int max_bundle_size = 0;
    // γ of β = max(|α|, γ s²/t_1) (docs/theory/bundle-trust.md §2, made unit-free by the
    // first t). > 0.
    double locality_weight = 1;
    // Reading (a′) of docs/theory/bundle-trust.md §4: within an inner iteration, also try a
    // larger t (up to t_growth_limit·t) when a descent step is "too short". Costs evaluations;
    // the between-iteration update (model_agreement) usually makes it unnecessary. false =
    // thesis as printed.
    bool enlarge_t = false;
    // δ_T of (a′): stop enlarging when the bracket [l, u] is narrower than δ_T·u. In (0, 1).
    double enlarge_margin = 0.1;
    // Limits: outer iterations k_max, oracle calls, QPs per inner iteration
    // (docs/theory/bundle-trust.md §4), t_min = t_min_relative·t_1, line-search step s_min.
    // All >= 1 / > 0.
    int max_iterations = 3000;
    int max_evaluations = 10000;
    int max_inner_iterations = 50;
    double t_min_relative = 1e-12;
    double line_search_min_step = 1e-6;
    // Minimize f/|f(x_1)| instead of f (docs/optim.md). The stopping test and the step rule are
    // invariant under this scaling, so it changes results by round-off only; kept for
    // compatibility. Default off.
    bool scale_objective = false;
    // Final check (docs/optim.md): when the stopping test passes, the stationarity certificate
    // (stationarity.hpp) of the local bundle subgradients at x must be <= ε·min(G, F/ρ) and the
    // aggregate error from the direction QP's multipliers <= ε·F, or the run ends with
    // StopReason::kStationarityNotCertified (Status kStalled) instead of kConverged.
    bool certify_stationarity = true;
    // Restart check of a certified stop (docs/optim.md, "Restart check"): the bundle is reduced
    // to the center's own cut, as bundle codes reset it when the aggregate goes stale, t is reset
    // to ρ/‖g(x_k)‖ (ρ the certificate's radius), and the run goes on until its stopping test
    // passes again or for j_max iterations. "Converged" only if that gained at most ε·F over the
    // first stop (F of the first); otherwise the first stop was premature and the next stop is
    // checked in turn. A verdict that needs two stops from two different bundles does not flip
    // with the last bits of f (the test set's f·(1 + k·2⁻⁴⁰) variants, docs/optim-testset.md).
    // Costs a median of 8 evaluations per run on the test set. false: the first certified stop
    // is returned.
    bool confirm_by_restart = true;
    // The value from which F measures the run's decrease, f(x_1) − f(x_k) (docs/optim.md, "The
    // stopping test"), in the units of f. NaN (default): f(x_1). A run that continues another
    // one from its point (confirm_in_point_units) passes the first run's f(x_1), so that its
    // tests keep the first run's scale. Finite or NaN.
    double value_reference = kNaN;
    // Variable metric (docs/optim.md, "Variable metric"; opt-in): the
    // proximal term of the direction QP is dᵀHd/(2t) with H = diag(h) a relative diagonal metric
    // (geometric mean 1) estimated by least squares from the last `metric_memory` pairs
    // (x_{k+1} − x_k, g(x_{k+1}) − z_k) of serious steps (z_k the aggregate subgradient of the
    // step's QP), moved towards each new estimate by
    // the geometric fraction metric_damping, its condition number bounded by metric_ratio_bound,
    // and reset to the identity after j_max consecutive null steps. The stopping test and the
    // certificate are then read in the variables H^{1/2}x. false (default): H = I, the
    // Euclidean method (with the metric the test-set table needs more evaluations in total:
    // docs/optim-testset.md).
    bool variable_metric = false;
    int metric_memory = 10;           // >= 1
    double metric_damping = 0.2;      // in (0, 1]; 1 = no damping
    double metric_ratio_bound = 1e8;  // >= 1
    // Add the cuts of the other pieces of a max-type f that the oracle returns with each
    // evaluation (OracleResult::pieces; docs/optim.md, "Cuts of the pieces of a max"). No
    // effect for oracles that return none.
    bool use_piece_cuts = true;
    // Confirmation of a "converged" in the point's units (docs/optim.md, "Confirmation in the
    // point's units"; docs/theory/bundle-trust.md §6): when the stop's per-coordinate units
    // u_i = max(|x_i|, |x_1,i|) spread by more than point_units_spread (max u / min u over the
    // coordinates that have a unit), the stop is checked by confirm_in_point_units
    // (point_units_check.hpp) before minimize/resume return it: a restart in x ⊘ u that gains more
    // than ε·F continues the run in those units. Nearly uniform units are skipped: the method is
    // invariant under x → c·x, and with a spread κ the stop is already κε-stationary in x ⊘ u.
    // The check's evaluations count towards max_evaluations/max_iterations; it does not call
    // on_iteration. false: the Euclidean stop is returned as it is.
    bool confirm_in_point_units = true;
    double point_units_spread = 10.0;  // >= 1
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
    StopReason stop_reason = StopReason::kNotRun;
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
    double stationarity = kNaN;     ///< final ‖z + ω‖ (docs/theory/bundle-trust.md §3), unscaled
    double aggregate_error = kNaN;  ///< final σ + μᵀ(c − Cx), unscaled
    double subgradient_scale = kNaN;  ///< G of the relative test, unscaled
    double value_scale = kNaN;        ///< F of the relative test, unscaled
    /// Stationarity certificate of the final check: dist(0, conv{local g_i} + N_Υ(x)), unscaled;
    /// NaN when the stopping test was not met (or certify_stationarity is off). With
    /// Options::variable_metric: in the variables H^{1/2}x of the metric at the stop.
    double certificate_distance = kNaN;
    /// Restart checks of certified stops (Options::confirm_by_restart); each stop but the last
    /// one gained more than ε·F after its restart (a premature stop).
    int restart_checks = 0;
    double t = kNaN;                ///< last trust parameter
    double t_max_given = kNaN;      ///< Options::t_max (NaN = no cap)
    double t_max_used = kNaN;       ///< largest t tried in the run
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
