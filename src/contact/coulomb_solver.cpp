// SPDX-License-Identifier: MIT
#include "frictopt/contact/coulomb_solver.hpp"

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

constexpr frictopt::detail::EnumTable<CoulombMethod, 3> kMethodNames{{{
    {CoulombMethod::kFixedPoint, "fixed_point"},
    {CoulombMethod::kSplit, "split"},
    {CoulombMethod::kSemismoothNewton, "semismooth_newton"},
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
  if (method == CoulombMethod::kSemismoothNewton)
    fail("method", "semismooth_newton",
         "fixed_point or split (the semismooth Newton method is the PETSc engine's: solver.engine = \"petsc\")");
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
  Summary summary = options_.method == CoulombMethod::kSplit ? solve_split(cc, state)
                                                             : solve_fixed_point(cc, state);
  // Coulomb conditions: the Tresca conditions with s = λ, from the final state's fresh
  // gradient (independent of the fixed-point increment).
  const Eigen::VectorXd lambda = state.normal_forces();
  const double c_scale = cc.size() ? cc.cwiseAbs().maxCoeff() : 0.0;
  const ContactResiduals res =
      contact_residuals(tresca_.laws(), lambda, state.z, state.gradient, tresca_.dim(), c_scale);
  summary.kkt_residual = res.kkt_residual;
  summary.complementarity_gap = res.complementarity_gap;
  state.slip_bound = lambda;
  classify_nodes(state, tresca_.laws(), options_.tresca.classification_tolerance, c_scale);
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
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

CoulombSolver::Summary CoulombSolver::solve_fixed_point(const Eigen::VectorXd& c,
                                                        ContactState& state) const {
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
