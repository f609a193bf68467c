// SPDX-License-Identifier: MIT
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/semismooth_newton_coulomb.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"

namespace frictopt::contact {
namespace {

constexpr frictopt::detail::EnumTable<CoulombMethod, 4> kMethodNames{{{
    {CoulombMethod::kFixedPoint, "fixed_point"},
    {CoulombMethod::kSplit, "split"},
    {CoulombMethod::kSemismoothNewton, "semismooth_newton"},
    {CoulombMethod::kAutomatic, "automatic"},
}}};

// Loosest inner tolerance: early fixed-point iterates are far from the solution, so solving
// their QPs beyond 1e-6 is wasted work.
constexpr double kLoosestInnerTolerance = 1e-6;

CoulombSolver::Options validated(CoulombSolver::Options options) {
  options.validate();
  return options;
}

}  // namespace

std::string_view to_string(CoulombMethod method) { return kMethodNames.name(method); }

CoulombMethod parse_coulomb_method(std::string_view text) { return kMethodNames.parse(text, "Coulomb method"); }

void CoulombSolver::Options::validate() const {
  const auto fail = [](const char* field, const std::string& value, const char* expected) {
    fail_field("CoulombSolver::Options", field, value, expected);
  };
  if (!(relative_tolerance > 0.0 && relative_tolerance < 1.0))
    fail("relative_tolerance", format_number(relative_tolerance), "a value in (0, 1)");
  if (max_iterations < 1) fail("max_iterations", std::to_string(max_iterations), ">= 1");
  if (!(relaxation > 0.0 && relaxation <= 1.0))
    fail("relaxation", format_number(relaxation), "a value in (0, 1]");
  if (divergence_window < 2)
    fail("divergence_window", std::to_string(divergence_window), ">= 2");
  if (newton.max_iterations < 1) fail("newton.max_iterations", std::to_string(newton.max_iterations), ">= 1");
  if (newton.direct_max_unknowns < 0)
    fail("newton.direct_max_unknowns", std::to_string(newton.direct_max_unknowns), ">= 0");
  if (newton.gmres_max_iterations < 1)
    fail("newton.gmres_max_iterations", std::to_string(newton.gmres_max_iterations), ">= 1");
  if (newton.automatic_min_unknowns < 0)
    fail("newton.automatic_min_unknowns", std::to_string(newton.automatic_min_unknowns), ">= 0");
  if (!(newton.automatic_applications_per_unknown > 0.0) || !std::isfinite(newton.automatic_applications_per_unknown))
    fail("newton.automatic_applications_per_unknown", format_number(newton.automatic_applications_per_unknown),
         "a finite value > 0");
  tresca.validate();
}

std::string CoulombSolver::Summary::brief_report() const {
  std::ostringstream out;
  out.precision(3);
  out << "Coulomb " << to_string(method_used) << ": " << to_string(status) << ", " << iterations
      << " fixed-point it, " << qp_iterations << " QP it, " << operator_applications
      << " applies, last increment " << last_relative_increment << ", KKT " << kkt_residual
      << ", gap " << complementarity_gap;
  if (inner_not_converged > 0) out << ", " << inner_not_converged << " inner solves capped";
  if (newton_iterations > 0)
    out << ", " << newton_iterations << " Newton it, " << linear_iterations << " linear it, " << factorizations
        << " LU" << (fallback ? ", Newton failed: fixed point" : "");
  out << ", " << time_seconds << " s";
  return out.str();
}

CoulombSolver::CoulombSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law, Options options)
    : CoulombSolver(delassus, std::vector<FrictionLaw>{law}, std::move(options)) {}

CoulombSolver::CoulombSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law)
    : CoulombSolver(delassus, std::vector<FrictionLaw>{law}, Options{}) {}

CoulombSolver::CoulombSolver(const linalg::LinearOperator& delassus, std::vector<FrictionLaw> laws,
                             Options options)
    : options_(validated(std::move(options))),
      tresca_(delassus, std::move(laws), options_.tresca) {}

double CoulombSolver::inner_tolerance(double last_increment) const {
  const double floor = options_.tresca.relative_tolerance;
  return std::max(floor, std::min(kLoosestInnerTolerance, 1e-2 * last_increment));
}

CoulombSolver::Summary CoulombSolver::solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                                            ContactState& state) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index n = tresca_.delassus().size();
  if (c.size() != n)
    throw InvalidInput("CoulombSolver::solve: c has size " + std::to_string(c.size()) +
                       "; expected " + std::to_string(n));
  if (!c.allFinite()) throw InvalidInput("CoulombSolver::solve: c has non-finite entries");
  const Eigen::VectorXd cc = c;
  Summary summary;
  switch (options_.method) {
    case CoulombMethod::kSplit: summary = solve_split(cc, state); break;
    case CoulombMethod::kFixedPoint: summary = solve_fixed_point(cc, state); break;
    case CoulombMethod::kAutomatic: summary = solve_automatic(cc, state); break;
    case CoulombMethod::kSemismoothNewton:
      // Finished by the Newton solver (residuals, classification, message, fallback).
      summary = SemismoothNewtonCoulombSolver(tresca_.delassus(), tresca_.laws(), options_).solve(cc, state);
      summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return summary;
  }
  if (summary.method_used != CoulombMethod::kSemismoothNewton && !summary.fallback) finish(cc, state, summary);
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

void CoulombSolver::finish(const Eigen::VectorXd& c, ContactState& state, Summary& summary) const {
  // Coulomb conditions: the Tresca conditions with s = λ, from the final state's fresh
  // gradient (independent of the fixed-point increment).
  const Eigen::VectorXd lambda = state.normal_forces();
  const double c_scale = c.size() ? c.cwiseAbs().maxCoeff() : 0.0;
  const ContactResiduals res =
      contact_residuals(tresca_.laws(), lambda, state.z, state.gradient, tresca_.dim(), c_scale);
  summary.kkt_residual = res.kkt_residual;
  summary.complementarity_gap = res.complementarity_gap;
  const double c_norm = c.norm();
  summary.relative_projected_gradient =
      coulomb_projected_gradient_norm(tresca_.laws(), state.z, state.gradient, tresca_.dim(), tresca_.step_length()) /
      (c_norm > 0.0 ? c_norm : 1.0);
  state.slip_bound = lambda;
  classify_nodes(state, tresca_.laws(), options_.tresca.classification_tolerance, c_scale);
  if (summary.method_used == CoulombMethod::kSemismoothNewton) {
    summary.message = summary.status == Status::kConverged
                          ? "semismooth Newton: projected gradient " + format_number(summary.relative_projected_gradient) +
                                " <= " + format_number(options_.tresca.relative_tolerance) + " after " +
                                std::to_string(summary.newton_iterations) + " Newton steps"
                          : summary.message;
    return;
  }
  switch (summary.status) {
    case Status::kConverged:
      summary.message = "relative increment " + format_number(summary.last_relative_increment) + " <= " +
                        format_number(options_.relative_tolerance) + " after " +
                        std::to_string(summary.iterations) + " iterations";
      break;
    case Status::kMaxIterations:
      summary.message = "max_iterations = " + std::to_string(options_.max_iterations) +
                        " reached; last relative increment " + format_number(summary.last_relative_increment);
      break;
    case Status::kDiverged:
      summary.message = "the increment grew in " + std::to_string(options_.divergence_window) +
                        " consecutive iterations (or became non-finite); last relative increment " +
                        format_number(summary.last_relative_increment) +
                        " (the fixed-point map is expansive: try relaxation < 1)";
      break;
    case Status::kStoppedByCallback:
      summary.message = "stopped by the iteration callback";
      break;
    default:
      summary.message = "the inner QP failed: the Delassus operator is not SPD or data are not finite";
  }
}

CoulombSolver::Summary CoulombSolver::solve_automatic(const Eigen::VectorXd& c, ContactState& state) const {
  const Eigen::Index m = c.size();
  if (m < options_.newton.automatic_min_unknowns) {
    Summary summary = solve_fixed_point(c, state);
    summary.method_given = CoulombMethod::kAutomatic;
    return summary;
  }
  // The fixed point first: on problems with few slipping nodes it converges within the budget,
  // and its iterate is a good start for Newton otherwise (docs/contact.md, "Semismooth Newton").
  const long budget = static_cast<long>(
      std::ceil(options_.newton.automatic_applications_per_unknown * static_cast<double>(m)));
  Summary first = solve_fixed_point(c, state, budget);
  first.method_given = CoulombMethod::kAutomatic;
  if (first.status != Status::kMaxIterations || first.iterations >= options_.max_iterations ||
      first.operator_applications < budget)
    return first;
  Options newton = options_;
  newton.method = CoulombMethod::kSemismoothNewton;
  Summary summary = SemismoothNewtonCoulombSolver(tresca_.delassus(), tresca_.laws(), newton).solve(c, state);
  summary.method_given = CoulombMethod::kAutomatic;
  summary.iterations += first.iterations;
  summary.qp_iterations += first.qp_iterations;
  summary.operator_applications += first.operator_applications;
  summary.inner_not_converged += first.inner_not_converged;
  summary.message += " (handed over from the fixed point after " + std::to_string(first.iterations) +
                     " iterations, " + std::to_string(first.operator_applications) + " products with M)";
  return summary;
}

namespace {

/// Shared bookkeeping of both methods: increments, divergence detection, callback.
class FixedPointMonitor {
 public:
  FixedPointMonitor(const CoulombSolver::Options& options, CoulombSolver::Summary& summary)
      : options_(options), summary_(summary) {}

  void add_qp(const TrescaSolver::Summary& qp, int& qp_iterations_this_step) {
    summary_.qp_iterations += qp.iterations;
    summary_.operator_applications += qp.operator_applications;
    qp_iterations_this_step += qp.iterations;
    if (qp.status == Status::kMaxIterations) ++summary_.inner_not_converged;
    if (qp.status == Status::kNumericalFailure) failed_ = true;
  }

  /// Records iteration k with increment ‖Δ‖ and reference ‖x_k‖; returns true when the loop
  /// must stop (summary.status set unless converged-pending handling is needed by the caller).
  bool record(int k, double increment, double reference, Status qp_status, int qp_iterations,
              bool inner_at_floor) {
    summary_.iterations = k;
    const double rel = reference > 0.0 ? increment / reference
                                       : (increment == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
    summary_.last_relative_increment = rel;
    if (failed_) {
      summary_.status = Status::kNumericalFailure;
      return true;
    }
    if (!std::isfinite(increment)) {
      summary_.status = Status::kDiverged;
      return true;
    }
    if (options_.on_iteration &&
        options_.on_iteration({k, rel, qp_iterations, qp_status}) == CallbackResult::kStop) {
      summary_.status = Status::kStoppedByCallback;
      return true;
    }
    if (increment <= options_.relative_tolerance * reference && inner_at_floor) {
      summary_.status = Status::kConverged;
      return true;
    }
    growth_ = (k > 1 && increment > previous_) ? growth_ + 1 : 0;
    previous_ = increment;
    if (growth_ >= options_.divergence_window) {
      summary_.status = Status::kDiverged;
      return true;
    }
    if (k >= options_.max_iterations) {
      summary_.status = Status::kMaxIterations;
      return true;
    }
    return false;
  }

 private:
  const CoulombSolver::Options& options_;
  CoulombSolver::Summary& summary_;
  double previous_ = 0.0;
  int growth_ = 0;
  bool failed_ = false;
};

}  // namespace

CoulombSolver::Summary CoulombSolver::solve_fixed_point(const Eigen::VectorXd& c, ContactState& state,
                                                        long application_budget) const {
  Summary summary;
  summary.method_given = summary.method_used = CoulombMethod::kFixedPoint;
  const Eigen::Index p = tresca_.num_nodes();
  const bool warm = state.z.size() == c.size() && state.dim == tresca_.dim();
  if (!warm) state = ContactState(tresca_.dim(), p);
  // s_0 = λ of the warm start, or 0: the first QP is then the frictionless problem.
  Eigen::VectorXd s = warm ? state.normal_forces() : Eigen::VectorXd::Zero(p);
  FixedPointMonitor monitor(options_, summary);
  const double floor = options_.tresca.relative_tolerance;
  double last_rel = std::numeric_limits<double>::infinity();
  for (int k = 1;; ++k) {
    const double tol = inner_tolerance(last_rel);
    const auto qp = tresca_.solve_to(c, s, state, tol);
    int qp_iterations = 0;
    monitor.add_qp(qp, qp_iterations);
    const Eigen::VectorXd s_next =
        (1.0 - options_.relaxation) * s + options_.relaxation * state.normal_forces();
    const double increment = (s_next - s).norm();
    const double reference = s.norm();
    // Convergence is accepted only from a QP solved at the final accuracy; a small increment
    // seen at a looser tolerance triggers one more (warm, cheap) solve at the floor.
    const bool stop = monitor.record(k, increment, reference, qp.status, qp_iterations, tol <= floor);
    last_rel = summary.last_relative_increment;
    if (summary.status == Status::kConverged || stop) break;
    if (application_budget > 0 && summary.operator_applications >= application_budget) {
      summary.status = Status::kMaxIterations;  // the handover of kAutomatic (solve_automatic)
      break;
    }
    s = s_next;
  }
  return summary;
}

CoulombSolver::Summary CoulombSolver::solve_split(const Eigen::VectorXd& c, ContactState& state) const {
  Summary summary;
  summary.method_given = summary.method_used = CoulombMethod::kSplit;
  const Eigen::Index p = tresca_.num_nodes();
  const int dim = tresca_.dim();
  const bool warm = state.z.size() == c.size() && state.dim == dim;
  FixedPointMonitor monitor(options_, summary);
  if (!warm) {
    // Frictionless start (docs/theory/state-problem.md §6): τ⁰ = 0, λ⁰ = argmin_{λ>=0} K(0, λ).
    state = ContactState(dim, p);
    const auto qp = tresca_.solve_block(TrescaSolver::Block::kNormal, c, Eigen::VectorXd::Zero(p),
                                        state, inner_tolerance(std::numeric_limits<double>::infinity()));
    int unused = 0;
    monitor.add_qp(qp, unused);
  }
  Eigen::VectorXd s = state.normal_forces();
  const double floor = options_.tresca.relative_tolerance;
  double last_rel = std::numeric_limits<double>::infinity();
  for (int k = 1;; ++k) {
    const Eigen::VectorXd z_prev = state.z;
    const double tol = inner_tolerance(last_rel);
    int qp_iterations = 0;
    // (I) tangential forces in s·W with λ fixed; (II) normal forces with q fixed.
    const auto qp1 = tresca_.solve_block(TrescaSolver::Block::kTangential, c, s, state, tol);
    monitor.add_qp(qp1, qp_iterations);
    const auto qp2 = tresca_.solve_block(TrescaSolver::Block::kNormal, c, s, state, tol);
    monitor.add_qp(qp2, qp_iterations);
    const Status qp_status = qp1.status != Status::kConverged ? qp1.status : qp2.status;
    const double increment = (state.z - z_prev).norm();
    const bool stop = monitor.record(k, increment, z_prev.norm(), qp_status, qp_iterations, tol <= floor);
    last_rel = summary.last_relative_increment;
    if (stop) break;
    s = (1.0 - options_.relaxation) * s + options_.relaxation * state.normal_forces();
  }
  return summary;
}

Eigen::VectorXd shift_by_previous_slip(const Eigen::Ref<const Eigen::VectorXd>& c,
                                       const Eigen::Ref<const Eigen::VectorXd>& previous_tangential, int dim) {
  if ((dim != 2 && dim != 3) || c.size() % dim != 0 || previous_tangential.size() != (dim - 1) * (c.size() / dim))
    throw InvalidInput("shift_by_previous_slip: c has " + std::to_string(c.size()) + " entries and u_t^{k-1} " +
                       std::to_string(previous_tangential.size()) + " in dim " + std::to_string(dim) +
                       "; expected dim·p and (dim−1)·p");
  Eigen::VectorXd shifted = c;
  const Eigen::Index p = c.size() / dim;
  for (Eigen::Index i = 0; i < p; ++i)
    for (int k = 0; k < dim - 1; ++k) shifted(dim * i + k) += previous_tangential((dim - 1) * i + k);
  return shifted;
}

FrictionLaw frictionless_law(int dim) {
  if (dim == 2) return FrictionLaw::interval(0.0, 0.0);
  if (dim == 3) return FrictionLaw::disc(0.0);
  throw InvalidInput("frictionless_law: dim = " + std::to_string(dim) + "; expected 2 or 3");
}

}  // namespace frictopt::contact
