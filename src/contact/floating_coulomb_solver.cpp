// SPDX-License-Identifier: MIT
#include "frictopt/contact/floating_coulomb_solver.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "frictopt/core/error.hpp"

namespace frictopt::contact {
namespace {

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
    throw InvalidInput(fmt::format("FloatingCoulombSolver::Options::{} = {}; expected {}", field,
                                   value, expected));
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

FloatingCoulombSolver::Summary FloatingCoulombSolver::solve(
    const Eigen::Ref<const Eigen::VectorXd>& c, const Eigen::Ref<const Eigen::VectorXd>& e,
    ContactState& state, Eigen::VectorXd& beta) const {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::MatrixXd& E = equality_;
  if (e.size() != E.rows())
    throw InvalidInput(fmt::format("FloatingCoulombSolver::solve: e has {} entries; expected {}",
                                   e.size(), E.rows()));
  Summary summary;
  // ρ₀ balances the two terms of M + ρEᵀE on the diagonal.
  const double mean_m = delassus_.diagonal().mean();
  const double mean_e = E.colwise().squaredNorm().mean();
  const double rho0 = mean_e > 0.0 ? mean_m / mean_e : 1.0;
  double rho = rho0;
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(E.rows());
  double last = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= options_.max_outer_iterations; ++k) {
    const AugmentedOperator op(delassus_, E, rho);
    const CoulombSolver inner(op, law_, options_.coulomb);
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
    const double scale =
        std::max({e.norm(), E.norm() * state.z.norm(), std::numeric_limits<double>::min()});
    summary.equality_residual = r.norm() / scale;
    // ∇ = (M + ρEᵀE)z + c_k = Mz + c + Eᵀ(μ + ρr): the kinematics with β = μ + ρr.
    mu += rho * r;
    if (summary.equality_residual <= options_.equality_tolerance) {
      summary.status = Status::kConverged;
      summary.message = fmt::format("forces and moments balance to {:.1e} after {} iterations",
                                    summary.equality_residual, k);
      break;
    }
    if (summary.equality_residual > options_.required_decrease * last)
      rho *= options_.penalty_growth;
    last = summary.equality_residual;
    if (rho > options_.max_penalty_ratio * rho0) {
      summary.status = Status::kDiverged;
      summary.message = fmt::format(
          "no equilibrium: the contact forces cannot balance the loads (residual {:.2e} "
          "with the penalty at {:.0e} × its start)",
          summary.equality_residual, rho / rho0);
      break;
    }
    if (k == options_.max_outer_iterations) {
      summary.status = Status::kMaxIterations;
      summary.message = fmt::format("max_outer_iterations = {} reached; equality residual {:.2e}",
                                    options_.max_outer_iterations, summary.equality_residual);
    }
  }
  beta = mu;
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace frictopt::contact
