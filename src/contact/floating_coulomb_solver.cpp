// SPDX-License-Identifier: MIT
#include "frictopt/contact/floating_coulomb_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/QR>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/semismooth_newton_coulomb.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/core/validation.hpp"

namespace frictopt::contact {
namespace {

// Stagnation test of the outer loop (see solve()): "no progress" is less than a 1 % decrease,
// five such iterations in a row are a stall (first answered by tighter inner tolerances), and a
// stall within 10⁴ × equality_tolerance is the solver's accuracy floor, not infeasibility.
constexpr double kNoProgress = 0.99;
constexpr int kStallIterations = 5;
constexpr double kFloorFactor = 1e4;
// Iterates mixed by the Anderson acceleration of the multiplier update (see solve()).
constexpr int kAndersonMemory = 5;
// The finest inner tolerance a stall may ask for (a few ulps of the relative increments).
constexpr double kFinestInnerTolerance = 1e-14;
// Accuracy of the penalized problems that start the Newton method: only a start (measured on a
// 16×16×8 drag: 1e-6 spent 3 s of a 3.2 s solve in these QPs, 1e-3 spends 0.05 s and Newton
// takes 7 steps instead of 4).
constexpr double kNewtonStartTolerance = 1e-3;

// M + ρEᵀE, applied as M x + ρEᵀ(E x): E has r <= 6 rows, so no m × m matrix is formed.
class AugmentedOperator final : public linalg::LinearOperator {
 public:
  AugmentedOperator(const linalg::LinearOperator& M, const Eigen::MatrixXd& E, double rho)
      : M_(M), E_(E), rho_(rho) {}
  Eigen::Index size() const override { return M_.size(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x,
             Eigen::Ref<Eigen::VectorXd> y) const override {
    M_.apply(x, y);
    y.noalias() += rho_ * (E_.transpose() * (E_ * x));
  }
  Eigen::VectorXd diagonal() const override {
    return M_.diagonal() + rho_ * E_.colwise().squaredNorm().transpose();
  }

 private:
  const linalg::LinearOperator& M_;
  const Eigen::MatrixXd& E_;
  double rho_;
};

}  // namespace

void FloatingCoulombSolver::Options::validate() const {
  const auto fail = [](const char* field, double value, const char* expected) {
    fail_field("FloatingCoulombSolver::Options", field, format_number(value), expected);
  };
  if (!(equality_tolerance > 0.0 && equality_tolerance < 1.0))
    fail("equality_tolerance", equality_tolerance, "a value in (0, 1)");
  if (max_outer_iterations < 1) fail("max_outer_iterations", max_outer_iterations, ">= 1");
  if (!(penalty_growth > 1.0)) fail("penalty_growth", penalty_growth, "> 1");
  if (!(required_decrease > 0.0 && required_decrease < 1.0))
    fail("required_decrease", required_decrease, "a value in (0, 1)");
  if (!(max_penalty_ratio > 1.0)) fail("max_penalty_ratio", max_penalty_ratio, "> 1");
  coulomb.validate();
}

std::string FloatingCoulombSolver::Summary::brief_report() const {
  if (solved_by_newton)
    return fmt::format(
        "floating body (semismooth Newton on the Coulomb conditions and Rᵀ(l + Gᵀz) = 0): {} ({}); {} Newton "
        "steps, {} factorizations, {} linear it, equality residual {:.2e}, {:.3f} s",
        to_string(status), message, newton_iterations, inner.factorizations, inner.linear_iterations,
        equality_residual, time_seconds);
  return fmt::format(
      "floating body (augmented Lagrangian on Rᵀ(l + Gᵀz) = 0): {} ({}); {} outer it, {} "
      "fixed-point it, "
      "{} QP it, equality residual {:.2e}, penalty {:.2e}, {:.3f} s",
      to_string(status), message, outer_iterations, fixed_point_iterations, qp_iterations,
      equality_residual, penalty, time_seconds);
}

FloatingCoulombSolver::FloatingCoulombSolver(const linalg::LinearOperator& delassus,
                                             Eigen::MatrixXd equality, FrictionLaw law,
                                             Options options)
    : delassus_(delassus),
      equality_(std::move(equality)),
      law_(std::move(law)),
      options_(std::move(options)) {
  options_.validate();
  if (equality_.cols() != delassus_.size())
    throw InvalidInput(
        fmt::format("FloatingCoulombSolver: E has {} columns; expected {} (the contact unknowns)",
                    equality_.cols(), delassus_.size()));
}

bool FloatingCoulombSolver::uses_newton() const {
  switch (options_.coulomb.method) {
    case CoulombMethod::kSemismoothNewton:
      return true;
    case CoulombMethod::kAutomatic:
      // Newton needs M's entries: held densely, or formed by m products while that stays cheap
      // next to one augmented-Lagrangian solve (tens of fixed points of hundreds of products).
      return dynamic_cast<const DenseDelassus*>(&delassus_) != nullptr ||
             dynamic_cast<const linalg::DenseOperator*>(&delassus_) != nullptr ||
             delassus_.size() <= options_.coulomb.newton.automatic_min_unknowns;
    default:
      return false;
  }
}

double FloatingCoulombSolver::initial_penalty() const {
  const double mean_m = delassus_.diagonal().mean();
  const double mean_e = equality_.colwise().squaredNorm().mean();
  return mean_e > 0.0 ? mean_m / mean_e : 1.0;
}

FloatingCoulombSolver::Summary FloatingCoulombSolver::solve(
    const Eigen::Ref<const Eigen::VectorXd>& c, const Eigen::Ref<const Eigen::VectorXd>& e,
    ContactState& state, Eigen::VectorXd& beta) const {
  if (e.size() != equality_.rows())
    throw InvalidInput(fmt::format("FloatingCoulombSolver::solve: e has {} entries; expected {}",
                                   e.size(), equality_.rows()));
  if (!uses_newton()) return solve_augmented_lagrangian(c, e, state, beta);
  const ContactState initial = state;
  const Eigen::VectorXd initial_beta = beta;
  const Summary newton = solve_newton(c, e, state, beta);
  if (newton.converged()) return newton;
  // The augmented Lagrangian from the same start: it also tells a load without equilibrium.
  state = initial;
  beta = initial_beta;
  Summary summary = solve_augmented_lagrangian(c, e, state, beta);
  summary.newton_iterations = newton.newton_iterations;
  summary.message = fmt::format("semismooth Newton failed ({}); augmented Lagrangian: {}", newton.message, summary.message);
  summary.time_seconds += newton.time_seconds;
  return summary;
}

FloatingCoulombSolver::Summary FloatingCoulombSolver::solve_newton(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                                   const Eigen::Ref<const Eigen::VectorXd>& e,
                                                                   ContactState& state, Eigen::VectorXd& beta) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::MatrixXd& E = equality_;
  const Eigen::Index m = delassus_.size(), r = E.rows();
  const int dim = law_.dim();
  Summary summary;
  const double rho0 = initial_penalty();
  const Eigen::VectorXd ee = e;
  const SemismoothNewtonCoulombSolver::Balance balance{E, ee, options_.equality_tolerance};
  const auto penalized_start = [&] {
    // The balance as a penalty ρ₀‖Ez − e‖² (the augmented Lagrangian's first step): the
    // frictionless problem, then the Tresca problem with its normal forces as slip bounds (one
    // fixed-point step), so that the start has sticking nodes — from slip everywhere the
    // Jacobian is singular in β (a polygon's vertices fix the tangential forces whatever the
    // rigid motion) — and β ≈ ρ₀(Ez − e).
    const AugmentedOperator op(delassus_, E, rho0);
    const TrescaSolver qp(op, law_, options_.coulomb.tresca);
    const Eigen::VectorXd linear = c - rho0 * (E.transpose() * ee);
    ContactState first(dim, m / dim);
    TrescaSolver::Summary s =
        qp.solve_to(linear, Eigen::VectorXd::Zero(m / dim), first, kNewtonStartTolerance);
    summary.qp_iterations += s.iterations;
    const Eigen::VectorXd slip_bound = first.normal_forces().cwiseMax(0.0);
    s = qp.solve_to(linear, slip_bound, first, kNewtonStartTolerance);
    summary.qp_iterations += s.iterations;
    state = first;
    beta = rho0 * (E * state.z - ee);
  };
  if (state.z.size() != m || state.dim != dim) {
    penalized_start();
  } else if (beta.size() != r) {
    // A warm z without its β: the β that closes the gaps of the touching nodes, (Mz + c + Eᵀβ)_ν =
    // 0 where λ > 0, by least squares; too few touching nodes to fix β: the penalized start.
    Eigen::VectorXd g(m);
    delassus_.apply(state.z, g);
    g += c;
    std::vector<Eigen::Index> rows;
    for (Eigen::Index i = 0; i < m / dim; ++i)
      if (state.z(dim * i + dim - 1) > 0.0) rows.push_back(dim * i + dim - 1);
    bool fitted = false;
    if (static_cast<Eigen::Index>(rows.size()) >= r) {
      Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), r);
      Eigen::VectorXd b(A.rows());
      for (Eigen::Index k = 0; k < A.rows(); ++k) {
        A.row(k) = E.col(rows[static_cast<std::size_t>(k)]).transpose();
        b(k) = -g(rows[static_cast<std::size_t>(k)]);
      }
      const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
      if (qr.rank() == r) {
        beta = qr.solve(b);
        fitted = beta.allFinite();
      }
    }
    if (!fitted) penalized_start();
  }
  const SemismoothNewtonCoulombSolver newton(delassus_, law_, options_.coulomb);
  summary.inner = newton.solve_balanced(c, balance, state, beta);
  summary.newton_iterations = summary.inner.newton_iterations;
  summary.qp_iterations += summary.inner.qp_iterations;
  summary.status = summary.inner.status;
  summary.solved_by_newton = summary.converged();
  summary.equality_residual = balance.residual(state.z);
  summary.message = summary.converged() ? fmt::format("forces and moments balance to {:.1e} after {} Newton steps",
                                                      summary.equality_residual, summary.newton_iterations)
                                        : summary.inner.message;
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

FloatingCoulombSolver::Summary FloatingCoulombSolver::solve_augmented_lagrangian(
    const Eigen::Ref<const Eigen::VectorXd>& c, const Eigen::Ref<const Eigen::VectorXd>& e,
    ContactState& state, Eigen::VectorXd& beta) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::MatrixXd& E = equality_;
  Summary summary;
  const Eigen::VectorXd ee = e;
  const SemismoothNewtonCoulombSolver::Balance balance{E, ee, options_.equality_tolerance};
  const double rho0 = initial_penalty();
  double rho = rho0;
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(E.rows());
  double last = std::numeric_limits<double>::infinity();
  int stalled = 0;  // consecutive outer iterations without progress
  CoulombSolver::Options coulomb = options_.coulomb;  // inner tolerances, tightened on a stall
  // The inner operator M + ρEᵀE is applied, not formed: the semismooth Newton method would form
  // it by m products per outer iteration, so the inner solves are fixed points (the Newton
  // method solves the whole floating problem instead: solve_newton).
  if (coulomb.method == CoulombMethod::kAutomatic || coulomb.method == CoulombMethod::kSemismoothNewton)
    coulomb.method = CoulombMethod::kFixedPoint;
  std::vector<Eigen::VectorXd> g_history, f_history;  // Anderson acceleration of μ
  double history_rho = rho;
  beta = mu;
  for (int k = 1; k <= options_.max_outer_iterations; ++k) {
    const AugmentedOperator op(delassus_, E, rho);
    const CoulombSolver inner(op, law_, coulomb);
    const Eigen::VectorXd ck = c + E.transpose() * (mu - rho * e);
    summary.inner = inner.solve(ck, state);
    summary.outer_iterations = k;
    summary.fixed_point_iterations += summary.inner.iterations;
    summary.qp_iterations += summary.inner.qp_iterations;
    summary.penalty = rho;

    if (!summary.inner.converged()) {
      summary.status = summary.inner.status;
      summary.message = "inner Coulomb solve: " + summary.inner.message;
      break;
    }
    const Eigen::VectorXd r = E * state.z - e;
    summary.equality_residual = balance.residual(state.z);
    // ∇ = (M + ρEᵀE)z + c_k = Mz + c + Eᵀ(μ + ρr): the kinematics with β = μ + ρr.
    beta = mu + rho * r;
    // The next multiplier: the first-order update μ ← μ + ρr is the fixed-point map
    // g(μ) = μ + ρ r(μ); Anderson acceleration (type II, memory kAndersonMemory) mixes its last
    // iterates so that μ' = g_k − ΔG γ with γ = argmin ‖f_k − ΔF γ‖, f = ρr. Why: near the
    // friction capacity the dual function is flat along the sliding directions and the plain
    // update converges linearly at rate ≈ 0.96 (measured: 200 outer iterations from 1e-3 to
    // 1.6e-9 at 1e-5 below μP), while r has only r <= 6 components — a secant model of
    // dr/dμ from a few iterates is cheap and restores fast convergence. The history restarts
    // when ρ changes (another map) or the residual did not fall (a bad or stagnating mixing step:
    // the plain step follows).
    const Eigen::VectorXd f = rho * r;
    if (rho != history_rho || summary.equality_residual > kNoProgress * last) {
      g_history.clear();
      f_history.clear();
      history_rho = rho;
    }
    g_history.push_back(beta);
    f_history.push_back(f);
    if (static_cast<int>(f_history.size()) > kAndersonMemory + 1) {
      g_history.erase(g_history.begin());
      f_history.erase(f_history.begin());
    }
    if (f_history.size() >= 2) {
      const Eigen::Index n = static_cast<Eigen::Index>(f_history.size()) - 1;
      Eigen::MatrixXd dF(f.size(), n), dG(f.size(), n);
      for (Eigen::Index i = 0; i < n; ++i) {
        dF.col(i) = f_history[static_cast<std::size_t>(i + 1)] - f_history[static_cast<std::size_t>(i)];
        dG.col(i) = g_history[static_cast<std::size_t>(i + 1)] - g_history[static_cast<std::size_t>(i)];
      }
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(dF);
      qr.setThreshold(1e-12);  // a rank-deficient history mixes fewer iterates
      const Eigen::VectorXd gamma = qr.solve(f);
      mu = gamma.allFinite() ? Eigen::VectorXd(beta - dG * gamma) : beta;
    } else {
      mu = beta;
    }
    if (summary.equality_residual <= options_.equality_tolerance) {
      summary.status = Status::kConverged;
      summary.message = fmt::format("forces and moments balance to {:.1e} after {} iterations",
                                    summary.equality_residual, k);
      break;
    }
    // Stagnation: the residual no longer responds to the penalty. With inexact inner solves
    // (relative accuracy ε_in) the augmented Lagrangian reaches ‖Ez − e‖ of order ε_in only, so
    // a residual that stalls within kFloorFactor of the tolerance is the inner solver's accuracy
    // floor — measured near the friction capacity, where the equilibrium is ill-conditioned
    // (stalls at 1.5e-10 against 1e-10 at 2 % below μP), while a load without equilibrium
    // stalls at the order of its relative excess (1e-3 for 0.1 % over the capacity).
    stalled = summary.equality_residual > kNoProgress * last ? stalled + 1 : 0;
    // The inner QP stops at ‖g̃‖ <= tol·‖c_k‖, and c_k carries Eᵀμ: where the dual is flat (near
    // the friction capacity) that accuracy bounds ‖Ez − e‖ far above the equality tolerance
    // (measured: stalls at 1e-8 at 1e-5 below μP). A stall therefore first tightens the inner
    // tolerances (×1e-2, down to kFinestInnerTolerance); only a stall at the finest is final.
    if (stalled >= kStallIterations && coulomb.tresca.relative_tolerance > kFinestInnerTolerance) {
      coulomb.tresca.relative_tolerance = std::max(kFinestInnerTolerance, 1e-2 * coulomb.tresca.relative_tolerance);
      coulomb.relative_tolerance = std::max(kFinestInnerTolerance, 1e-2 * coulomb.relative_tolerance);
      stalled = 0;
    }
    if (stalled >= kStallIterations && summary.equality_residual <= kFloorFactor * options_.equality_tolerance) {
      summary.status = Status::kConverged;
      summary.message = fmt::format(
          "forces and moments balance to {:.1e} after {} iterations (the inner solver's accuracy floor: the "
          "penalty no longer reduces the residual)",
          summary.equality_residual, k);
      break;
    }
    if (stalled >= kStallIterations) {
      summary.status = Status::kDiverged;
      summary.message = fmt::format(
          "no equilibrium: the contact forces cannot balance the loads (the residual stalls at {:.2e} with the "
          "penalty at {:.0e} × its start)",
          summary.equality_residual, rho / rho0);
      break;
    }
    // ρ grows while the residual falls too slowly, up to max_penalty_ratio·ρ₀: beyond that the
    // inner QP's condition number (∝ ρ‖E‖²/λ_min(M)) costs more MPGP iterations than the outer
    // multiplier updates it saves (measured near the friction capacity: 240k QP iterations per
    // inner solve at 10⁵ρ₀ against ~2k at 10ρ₀).
    if (summary.equality_residual > options_.required_decrease * last &&
        rho * options_.penalty_growth <= options_.max_penalty_ratio * rho0)
      rho *= options_.penalty_growth;
    last = summary.equality_residual;
    if (k == options_.max_outer_iterations) {
      summary.status = Status::kMaxIterations;
      summary.message = fmt::format("max_outer_iterations = {} reached; equality residual {:.2e}",
                                    options_.max_outer_iterations, summary.equality_residual);
    }
  }
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace frictopt::contact
