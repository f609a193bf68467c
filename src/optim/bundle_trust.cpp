// SPDX-License-Identifier: MIT
// Bundle trust method, spec 04 §6 (consolidated algorithm) with the linear constraints of
// spec 04 §3.2 inside the direction-finding QP. Readings of the spec's open points are marked
// "spec 04 §5 item N" where they are implemented.
#include "frictopt/optim/bundle_trust.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>

#include "frictopt/core/error.hpp"
#include "frictopt/optim/dense_qp.hpp"

namespace frictopt::optim {

std::string_view to_string(StepKind kind) {
  switch (kind) {
    case StepKind::kStart: return "start";
    case StepKind::kSerious: return "serious";
    case StepKind::kNull: return "null";
    case StepKind::kLineSearchSerious: return "line_search_serious";
    case StepKind::kLineSearchNull: return "line_search_null";
  }
  return "unknown";
}

namespace {

template <class T>
void require(bool ok, const char* field, T value, const char* expected) {
  if (!ok) {
    std::ostringstream s;
    s << "BundleTrust::Options::" << field << " = " << value << "; expected " << expected;
    throw InvalidInput(s.str());
  }
}

// Solution of the direction-finding QP (spec 04 §3.2) at center xc with parameter t.
struct DirectionQp {
  bool ok = false;
  std::string message;
  Eigen::VectorXd d;
  double v = kNaN;
  Eigen::VectorXd theta;   // multipliers of the cuts (convex weights of the bundle)
  Eigen::VectorXd z;       // Σ θ_i g_i (aggregate, without the normal-cone part ω)
  double sigma = kNaN;     // Σ θ_i β_i
  double stationarity = kNaN;     // ‖d‖/t = ‖z + ω‖
  double aggregate_error = kNaN;  // −‖d‖²/t − v = σ + μᵀ(c − C xc)
};

// Primal (spec 04 §3.2): min_{d,v} v + ‖d‖²/(2t) s.t. g_iᵀd − v ≤ β_i, C(xc + d) ≤ c, E d = 0.
// Solved in the primal as the spec asks; θ are the cut multipliers. d = 0, v = max(−β_i) is
// feasible because xc ∈ Υ, which lets the solver skip phase one.
DirectionQp solve_direction_qp(const std::vector<BundleElement>& bundle, const Eigen::VectorXd& xc,
                               double t, const GeneralForm& gf, const DenseQpSolver& solver) {
  const Eigen::Index n = xc.size();
  const auto m = static_cast<Eigen::Index>(bundle.size());
  const Eigen::Index pc = gf.C.rows();
  QpProblem qp;
  qp.H = Eigen::MatrixXd::Zero(n + 1, n + 1);
  qp.H.topLeftCorner(n, n).diagonal().setConstant(1.0 / t);
  qp.g = Eigen::VectorXd::Zero(n + 1);
  qp.g(n) = 1.0;
  qp.A_in = Eigen::MatrixXd::Zero(m + pc, n + 1);
  qp.b_in = Eigen::VectorXd::Zero(m + pc);
  double v0 = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < m; ++i) {
    const BundleElement& b = bundle[static_cast<std::size_t>(i)];
    qp.A_in.row(i).head(n) = b.g.transpose();
    qp.A_in(i, n) = -1.0;
    qp.b_in(i) = b.locality;
    v0 = std::max(v0, -b.locality);
  }
  if (pc > 0) {
    qp.A_in.bottomLeftCorner(pc, n) = gf.C;
    // xc is feasible up to round-off; clamping the slack at 0 keeps d = 0 feasible.
    qp.b_in.tail(pc) = (gf.c - gf.C * xc).cwiseMax(0.0);
  }
  qp.A_eq = Eigen::MatrixXd::Zero(gf.E.rows(), n + 1);
  if (gf.E.rows() > 0) qp.A_eq.leftCols(n) = gf.E;
  qp.b_eq = Eigen::VectorXd::Zero(gf.E.rows());
  Eigen::VectorXd start = Eigen::VectorXd::Zero(n + 1);
  start(n) = v0;
  const DenseQpSolver::Summary s = solver.solve(qp, start);
  DirectionQp out;
  if (!s.converged()) {
    out.message = s.brief_report();
    return out;
  }
  out.ok = true;
  out.d = s.x.head(n);
  out.v = s.x(n);
  out.theta = s.multipliers_in.head(m);
  out.z = Eigen::VectorXd::Zero(n);
  out.sigma = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    out.z += out.theta(i) * bundle[static_cast<std::size_t>(i)].g;
    out.sigma += out.theta(i) * bundle[static_cast<std::size_t>(i)].locality;
  }
  out.stationarity = out.d.norm() / t;
  out.aggregate_error = std::max(0.0, -out.d.squaredNorm() / t - out.v);
  return out;
}

struct Evaluation {
  bool ok = false;
  double f = kNaN;
  Eigen::VectorXd g;
};

}  // namespace

void BundleTrust::Options::validate() const {
  require(std::isnan(t_max) || t_max > 0.0, "t_max", t_max, "> 0 or NaN (automatic)");
  require(max_step_length > 0.0 && std::isfinite(max_step_length), "max_step_length",
          max_step_length, "finite and > 0");
  require(std::isnan(t_initial) || t_initial > 0.0, "t_initial", t_initial,
          "> 0 (and <= T) or NaN (= T)");
  if (!std::isnan(t_initial) && !std::isnan(t_max))
    require(t_initial <= t_max, "t_initial", t_initial, "<= t_max");
  require(m1 > 0.0 && m1 < 1.0, "m1", m1, "in (0, 1)");
  require(m2 > m1 && m2 < 1.0, "m2", m2, "in (m1, 1)");
  require(m3 > 0.0 && m3 < 1.0, "m3", m3, "in (0, 1)");
  require(epsilon >= 0.0 && std::isfinite(epsilon), "epsilon", epsilon, ">= 0");
  require(max_bundle_size == 0 || max_bundle_size >= 3, "max_bundle_size", max_bundle_size,
          ">= 3 or 0 (automatic 2n)");
  require(locality_weight > 0.0 && std::isfinite(locality_weight), "locality_weight",
          locality_weight, "finite and > 0");
  require(enlarge_margin > 0.0 && enlarge_margin < 1.0, "enlarge_margin", enlarge_margin, "in (0, 1)");
  require(max_iterations >= 1, "max_iterations", max_iterations, ">= 1");
  require(max_evaluations >= 1, "max_evaluations", max_evaluations, ">= 1");
  require(max_inner_iterations >= 1, "max_inner_iterations", max_inner_iterations, ">= 1");
  require(t_min_relative > 0.0 && t_min_relative < 1.0, "t_min_relative", t_min_relative, "in (0, 1)");
  require(line_search_min_step > 0.0 && line_search_min_step < 1.0, "line_search_min_step",
          line_search_min_step, "in (0, 1)");
  require(feasibility_tolerance > 0.0, "feasibility_tolerance", feasibility_tolerance, "> 0");
}

std::string BundleTrust::Summary::brief_report() const {
  std::ostringstream s;
  s << "BundleTrust: " << frictopt::to_string(status) << ", f = " << f << ", |z+w| = " << stationarity
    << ", agg. error = " << aggregate_error << ", iterations " << iterations << " (serious "
    << serious_steps << ", null " << null_steps << "), evaluations " << evaluations;
  if (failed_evaluations > 0) s << " (" << failed_evaluations << " failed)";
  s << ", t = " << t << ", T = " << t_max_used << ", " << time_seconds << " s";
  if (start_projected) s << ", start projected by " << projection_distance;
  if (!message.empty()) s << " — " << message;
  return s.str();
}

BundleTrust::BundleTrust(Options options, LinearConstraints constraints)
    : options_(std::move(options)), constraints_(std::move(constraints)) {
  options_.validate();
}

namespace {

// The outer loop of spec 04 §6, run from a state (fresh or checkpointed).
class Run {
 public:
  Run(const BundleTrust::Options& o, const GeneralForm& gf, Oracle& oracle,
      BundleTrust::Summary& summary)
      : o_(o), gf_(gf), oracle_(oracle), s_(summary) {}

  Evaluation evaluate(const Eigen::VectorXd& x, double scale) {
    ++s_.evaluations;
    const OracleResult r = oracle_.evaluate(x);
    if (r.ok && r.subgradient.size() != x.size())
      throw InvalidInput("BundleTrust: the oracle returned a subgradient of size " +
                         std::to_string(r.subgradient.size()) + "; expected n = " +
                         std::to_string(x.size()));
    Evaluation e;
    if (!r.ok || !std::isfinite(r.value) || !r.subgradient.allFinite()) {
      ++s_.failed_evaluations;
      last_failure_ = r.ok ? "non-finite value or subgradient" : r.message;
      return e;
    }
    e.ok = true;
    e.f = r.value / scale;
    e.g = r.subgradient / scale;
    return e;
  }

  void run(BundleTrust::IterationSummary& st);

 private:
  void finish(BundleTrust::IterationSummary& st, Status status, std::string message) {
    s_.status = status;
    s_.message = std::move(message);
    s_.x = st.x;
    s_.f = st.f;
    s_.t = st.t;
    s_.iterations = st.iteration;
    s_.serious_steps = st.serious_steps;
    s_.null_steps = st.null_steps;
    s_.stationarity = st.stationarity * st.objective_scale;
    s_.aggregate_error = st.aggregate_error * st.objective_scale;
    s_.last_state = st;
  }

  const BundleTrust::Options& o_;
  const GeneralForm& gf_;
  Oracle& oracle_;
  BundleTrust::Summary& s_;
  std::string last_failure_;
};

void Run::run(BundleTrust::IterationSummary& st) {
  const DenseQpSolver solver;
  const double T = st.t_max;
  const double t_min = o_.t_min_relative * T;
  const double gamma = o_.locality_weight;
  const double scale = st.objective_scale;
  const auto j_max = static_cast<std::size_t>(s_.bundle_size_used);
  auto beta_of = [gamma](double alpha, double dist) {
    return std::max(std::abs(alpha), gamma * dist * dist);  // spec 04 §5 item 8
  };

  while (st.iteration < o_.max_iterations) {
    // ---- inner iteration (spec 04 §4 "Inner iteration", with (a′) of §5 item 5)
    double l = 0.0;
    double u = T;
    double t = st.t;
    int j = 1;
    DirectionQp qp;
    StepKind kind = StepKind::kStart;
    Eigen::VectorXd y_new;
    Evaluation e_new;
    double alpha_new = 0.0;
    // A trial that passed the descent test while we tried to enlarge t: accepted if the inner
    // iteration later runs out of trials [ADDITION: avoids losing a known decrease].
    bool have_candidate = false;
    Eigen::VectorXd cand_y;
    Evaluation cand_e;
    double cand_t = t;
    DirectionQp cand_qp;

    for (;;) {
      if (j > o_.max_inner_iterations || t < t_min) {
        if (have_candidate) {
          kind = StepKind::kSerious;
          y_new = cand_y;
          e_new = cand_e;
          t = cand_t;
          qp = cand_qp;
          break;
        }
        st.t = t;
        std::ostringstream msg;
        msg << "inner iteration failed (spec 04 §5 item 12): "
            << (t < t_min ? "t fell below t_min = " : "more than max_inner_iterations trials; t = ")
            << (t < t_min ? t_min : t);
        if (!last_failure_.empty()) msg << "; last oracle failure: " << last_failure_;
        finish(st, Status::kStalled, msg.str());
        return;
      }
      qp = solve_direction_qp(st.bundle, st.x, t, gf_, solver);
      ++s_.qp_solves;
      ++st.inner_trials;
      if (!qp.ok) {
        st.t = t;
        finish(st, Status::kNumericalFailure, "direction QP failed: " + qp.message);
        return;
      }
      st.stationarity = qp.stationarity;
      st.aggregate_error = qp.aggregate_error;
      st.predicted_change = qp.v;
      // "Almost stationary" (spec 04 §5 item 2: v^j, not v^k).
      if (qp.stationarity <= o_.epsilon && qp.aggregate_error <= o_.epsilon) {
        st.t = t;
        finish(st, Status::kConverged, "almost stationary: |z+w| <= epsilon and aggregate error <= epsilon");
        return;
      }
      if (s_.evaluations >= o_.max_evaluations) {
        st.t = t;
        s_.evaluation_limit = true;
        finish(st, Status::kMaxIterations, "evaluation limit reached (max_evaluations)");
        return;
      }
      const Eigen::VectorXd y = st.x + qp.d;
      const Evaluation e = evaluate(y, scale);
      if (!e.ok) {  // "could not evaluate here": shrink like a failed trial, case (d)
        u = t;
        t = 0.5 * (l + u);
        ++j;
        continue;
      }
      const double delta = e.f - st.f;
      const double gd = e.g.dot(qp.d);
      const double a_y = st.f - e.f + gd;
      const double beta_y = beta_of(a_y, qp.d.norm());
      if (delta < o_.m1 * qp.v) {  // (a′)
        if (!o_.enlarge_t || gd >= o_.m2 * qp.v || u - t <= o_.enlarge_margin * T) {
          kind = StepKind::kSerious;
          y_new = y;
          e_new = e;
          break;
        }
        have_candidate = true;
        cand_y = y;
        cand_e = e;
        cand_t = t;
        cand_qp = qp;
        l = t;
        t = 0.5 * (l + u);
        ++j;
        continue;
      }
      const double zp = st.z_prev.norm();
      const bool near = std::abs(delta) <= zp + st.sigma_prev;
      const bool local = (a_y <= o_.m3 * st.sigma_prev) || near;
      if (local && gd - beta_y >= o_.m2 * qp.v) {  // (b)
        kind = StepKind::kNull;
        y_new = y;
        e_new = e;
        alpha_new = a_y;
        break;
      }
      if (local && near) {  // (c)(i): line search along x + s d (spec 04 §5 item 6)
        ++s_.line_searches;
        Eigen::VectorXd last_y = y;
        Evaluation last_e = e;
        double last_alpha = a_y;
        double step = 0.5;  // s = 1 is the trial just rejected
        kind = StepKind::kLineSearchNull;
        for (;;) {
          if (s_.evaluations >= o_.max_evaluations) break;
          const Eigen::VectorXd ys = st.x + step * qp.d;
          const Evaluation es = evaluate(ys, scale);
          if (es.ok) {
            last_y = ys;
            last_e = es;
            last_alpha = st.f - es.f + es.g.dot(ys - st.x);
            if (es.f - st.f <= o_.m1 * step * qp.v) {
              kind = StepKind::kLineSearchSerious;
              break;
            }
            const double beta_s = beta_of(last_alpha, (ys - st.x).norm());
            if (es.g.dot(qp.d) - beta_s >= o_.m2 * qp.v) break;  // null step with ys
          }
          if (step < o_.line_search_min_step) break;  // null step with the last valid y
          step *= 0.5;
        }
        y_new = last_y;
        e_new = last_e;
        alpha_new = last_alpha;
        break;
      }
      u = t;  // (c)(ii), (d)
      t = 0.5 * (l + u);
      ++j;
    }

    // ---- reset (spec 04 §4 step 5, §5 item 10), before the new element is inserted
    const Eigen::VectorXd& theta = qp.theta;
    if (st.bundle.size() >= j_max) {
      const double wsum = std::max(theta.sum(), 1e-300);
      BundleElement agg;
      agg.g = qp.z / wsum;
      agg.locality = qp.sigma / wsum;
      for (std::size_t i = 0; i < st.bundle.size(); ++i) {
        const double w = theta(static_cast<Eigen::Index>(i)) / wsum;
        agg.lin_err += w * st.bundle[i].lin_err;
        agg.distance += w * st.bundle[i].distance;
      }
      std::vector<std::size_t> order;
      std::size_t center = 0;
      for (std::size_t i = 0; i < st.bundle.size(); ++i) {
        if (st.bundle[i].is_center) center = i;
        else order.push_back(i);
      }
      // Largest θ first; ties: most recent (higher index) first.
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const double ta = theta(static_cast<Eigen::Index>(a));
        const double tb = theta(static_cast<Eigen::Index>(b));
        return ta != tb ? ta > tb : a > b;
      });
      order.resize(std::min(order.size(), j_max - 3));
      std::sort(order.begin(), order.end());
      std::vector<BundleElement> kept;
      kept.push_back(st.bundle[center]);
      for (std::size_t i : order) kept.push_back(st.bundle[i]);
      kept.push_back(std::move(agg));
      st.bundle = std::move(kept);
    }

    // ---- update (spec 04 §6, SERIOUS / NULL; §5 items 7 and 9)
    const bool serious = kind == StepKind::kSerious || kind == StepKind::kLineSearchSerious;
    if (serious) {
      const Eigen::VectorXd dx = y_new - st.x;
      const double dxn = dx.norm();
      for (BundleElement& b : st.bundle) {
        b.lin_err += e_new.f - st.f - b.g.dot(dx);
        b.distance = b.is_aggregate() ? b.distance + dxn : (y_new - b.y).norm();
        b.locality = beta_of(b.lin_err, b.distance);
        b.is_center = false;
      }
      BundleElement c;
      c.g = e_new.g;
      c.y = y_new;
      c.is_center = true;
      st.bundle.push_back(std::move(c));
      st.x = y_new;
      st.f = e_new.f;
      ++st.serious_steps;
    } else {
      BundleElement b;
      b.g = e_new.g;
      b.y = y_new;
      b.lin_err = alpha_new;
      b.distance = (y_new - st.x).norm();
      b.locality = beta_of(b.lin_err, b.distance);
      st.bundle.push_back(std::move(b));
      ++st.null_steps;
    }
    st.t = t;  // spec 04 §5 item 4
    st.z_prev = qp.z;
    st.sigma_prev = qp.sigma;
    st.step = kind;
    ++st.iteration;
    st.evaluations = s_.evaluations;
    if (o_.keep_history) {
      s_.history.push_back({st.iteration, st.evaluations, kind, st.f * scale, st.t,
                            st.stationarity * scale, st.aggregate_error * scale,
                            static_cast<int>(st.bundle.size())});
    }
    if (o_.on_iteration) {
      BundleTrust::IterationSummary view = st;
      view.f = st.f * scale;
      if (o_.on_iteration(view) == CallbackResult::kStop) {
        finish(st, Status::kStoppedByCallback, "stopped by the iteration callback");
        return;
      }
    }
    st.inner_trials = 0;
  }
  finish(st, Status::kMaxIterations, "iteration limit reached (max_iterations)");
}

}  // namespace

BundleTrust::Summary BundleTrust::minimize(Oracle& oracle,
                                           const Eigen::Ref<const Eigen::VectorXd>& x0_in) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = x0_in.size();
  if (n == 0) throw InvalidInput("BundleTrust::minimize: x0 is empty; expected n >= 1 variables");
  if (!x0_in.allFinite()) throw InvalidInput("BundleTrust::minimize: x0 has a non-finite entry; expected finite numbers");
  const GeneralForm gf = to_general_form(constraints_, n);  // validates shapes
  Summary s;
  s.t_max_given = options_.t_max;
  s.bundle_size_given = options_.max_bundle_size;
  s.bundle_size_used = options_.max_bundle_size > 0 ? options_.max_bundle_size
                                                    : static_cast<int>(std::max<Eigen::Index>(10, 2 * n));
  Eigen::VectorXd x0 = x0_in;
  if (constraints_.max_violation(x0) > options_.feasibility_tolerance) {
    const Projection p = project_onto(constraints_, x0);
    if (p.feasible_set_empty)
      throw InvalidInput("BundleTrust::minimize: the feasible set is empty (" + p.message +
                         "); expected consistent linear constraints");
    if (!p.converged)
      throw InvalidInput("BundleTrust::minimize: could not project x0 onto the feasible set: " + p.message);
    x0 = p.point;
    s.start_projected = true;
    s.projection_distance = p.distance;
  }

  Run run(options_, gf, oracle, s);
  Evaluation e1 = run.evaluate(x0, 1.0);
  if (!e1.ok) {
    s.status = Status::kNumericalFailure;
    s.message = "the oracle could not evaluate the starting point";
    s.x = x0;
    s.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
  }
  IterationSummary st;
  st.objective_scale = options_.scale_objective ? std::max(std::abs(e1.f), 1e-300) : 1.0;
  e1.f /= st.objective_scale;
  e1.g /= st.objective_scale;
  s.objective_scale = st.objective_scale;
  // Automatic T (spec 04 §7): a first step of at most C_0.
  st.t_max = std::isnan(options_.t_max) ? options_.max_step_length / std::max(e1.g.norm(), 1e-12)
                                        : options_.t_max;
  st.t = std::isnan(options_.t_initial) ? st.t_max : std::min(options_.t_initial, st.t_max);
  s.t_max_used = st.t_max;
  st.x = x0;
  st.f = e1.f;
  st.z_prev = e1.g;     // spec 04 §5 item 3: z_0 = g_1, σ_0 = 0
  st.sigma_prev = 0.0;
  BundleElement c;
  c.g = e1.g;
  c.y = x0;
  c.is_center = true;
  st.bundle.push_back(std::move(c));
  st.evaluations = s.evaluations;
  run.run(st);
  s.f = st.f * st.objective_scale;
  s.last_state.f = s.f;
  s.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

BundleTrust::Summary BundleTrust::resume(Oracle& oracle, const IterationSummary& checkpoint) const {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::Index n = checkpoint.x.size();
  if (n == 0 || checkpoint.bundle.empty())
    throw InvalidInput("BundleTrust::resume: checkpoint has x of size " + std::to_string(n) +
                       " and " + std::to_string(checkpoint.bundle.size()) +
                       " bundle elements; expected n >= 1 and a non-empty bundle");
  for (std::size_t i = 0; i < checkpoint.bundle.size(); ++i) {
    if (checkpoint.bundle[i].g.size() != n)
      throw InvalidInput("BundleTrust::resume: bundle[" + std::to_string(i) + "].g has size " +
                         std::to_string(checkpoint.bundle[i].g.size()) + "; expected " + std::to_string(n));
  }
  if (!(checkpoint.t > 0.0) || !(checkpoint.t_max > 0.0) || checkpoint.z_prev.size() != n)
    throw InvalidInput("BundleTrust::resume: checkpoint t, t_max or z_prev invalid; expected t > 0, t_max > 0, z_prev of size n");
  const GeneralForm gf = to_general_form(constraints_, n);
  if (constraints_.max_violation(checkpoint.x) > options_.feasibility_tolerance)
    throw InvalidInput("BundleTrust::resume: checkpoint x violates the constraints by " +
                       std::to_string(constraints_.max_violation(checkpoint.x)) + "; expected a feasible center");
  Summary s;
  s.t_max_given = options_.t_max;
  s.t_max_used = checkpoint.t_max;
  s.bundle_size_given = options_.max_bundle_size;
  s.bundle_size_used = options_.max_bundle_size > 0 ? options_.max_bundle_size
                                                    : static_cast<int>(std::max<Eigen::Index>(10, 2 * n));
  s.bundle_size_used = std::max<int>(s.bundle_size_used, static_cast<int>(checkpoint.bundle.size()));
  s.evaluations = checkpoint.evaluations;
  IterationSummary st = checkpoint;
  st.f = checkpoint.f / checkpoint.objective_scale;  // callbacks see unscaled f
  s.objective_scale = st.objective_scale;
  Run run(options_, gf, oracle, s);
  run.run(st);
  s.f = st.f * st.objective_scale;
  s.last_state.f = s.f;
  s.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

}  // namespace frictopt::optim
