// SPDX-License-Identifier: MIT
// Primal active-set method for convex QPs with a positive SEMIdefinite Hessian (Nocedal &
// Wright, "Numerical Optimization", 2nd ed., Alg. 16.3, extended to singular reduced Hessians
// by stepping along zero-curvature descent directions until a constraint blocks).
#include "frictopt/optim/dense_qp.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "frictopt/core/error.hpp"

namespace frictopt::optim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string shape(const Eigen::MatrixXd& m) {
  std::ostringstream s;
  s << m.rows() << "x" << m.cols();
  return s.str();
}

// Constraint rows scaled to unit norm, so that tolerances and ratio tests compare like with
// like whatever the user's units. Zero rows are dropped after checking them.
struct ScaledRows {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  Eigen::VectorXd norm;         // original row norms of the kept rows
  std::vector<int> original;    // kept row -> original row index
  bool consistent = true;       // false if a zero row is violated
  int bad_row = -1;
};

ScaledRows scale_rows(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, bool equality,
                      double tol) {
  ScaledRows out;
  std::vector<int> kept;
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const double nrm = A.row(i).norm();
    if (nrm == 0.0) {
      const bool ok = equality ? std::abs(b(i)) <= tol : b(i) >= -tol;
      if (!ok && out.consistent) {
        out.consistent = false;
        out.bad_row = static_cast<int>(i);
      }
      continue;
    }
    kept.push_back(static_cast<int>(i));
  }
  out.A.resize(static_cast<Eigen::Index>(kept.size()), A.cols());
  out.b.resize(static_cast<Eigen::Index>(kept.size()));
  out.norm.resize(static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    const double nrm = A.row(kept[k]).norm();
    out.A.row(r) = A.row(kept[k]) / nrm;
    out.b(r) = b(kept[k]) / nrm;
    out.norm(r) = nrm;
  }
  out.original = std::move(kept);
  return out;
}

struct ActiveSetResult {
  QpOutcome outcome = QpOutcome::kNotRun;
  std::string message;
  Eigen::VectorXd x;
  Eigen::VectorXd y_eq;      // per scaled equality row
  Eigen::VectorXd lambda_in; // per scaled inequality row
  std::vector<int> working_in;
  int iterations = 0;
};

// Residual of `a` after projection onto the span of the orthonormal columns of `basis`.
double independent_part(const Eigen::MatrixXd& basis, const Eigen::VectorXd& a) {
  if (basis.cols() == 0) return a.norm();
  Eigen::VectorXd r = a - basis * (basis.transpose() * a);
  r -= basis * (basis.transpose() * r);  // second Gram–Schmidt pass for orthogonality
  return r.norm();
}

void append_orthonormal(Eigen::MatrixXd& basis, const Eigen::VectorXd& a) {
  Eigen::VectorXd r = a;
  if (basis.cols() > 0) {
    r -= basis * (basis.transpose() * r);
    r -= basis * (basis.transpose() * r);
  }
  basis.conservativeResize(a.size(), basis.cols() + 1);
  basis.col(basis.cols() - 1) = r / r.norm();
}

// Rows whose independent part falls below this (rows have unit norm) count as dependent:
// above it, R of the working-set QR stays well conditioned (condition ≲ 1e8).
constexpr double kDependentRow = 1e-8;
// A direction p "moves towards" a row only if aᵀp exceeds this fraction of ‖p‖; smaller
// components cannot violate the row by more than round-off along the step.
constexpr double kParallel = 1e-11;
// Consecutive zero-length steps before switching to Bland's smallest-index rule (anti-cycling).
constexpr int kDegenerateStepsBeforeBland = 30;

ActiveSetResult active_set(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                           const Eigen::MatrixXd& Aeq, const Eigen::VectorXd& /*beq: x is feasible*/,
                           const Eigen::MatrixXd& Ain, const Eigen::VectorXd& bin,
                           Eigen::VectorXd x, double feas_tol, double opt_tol, int max_iter) {
  const Eigen::Index n = x.size();
  ActiveSetResult res;
  std::vector<int> W_eq;
  std::vector<int> W_in;
  std::vector<char> in_working(static_cast<std::size_t>(Ain.rows()), 0);
  {
    Eigen::MatrixXd basis(n, 0);
    for (Eigen::Index i = 0; i < Aeq.rows(); ++i) {
      if (independent_part(basis, Aeq.row(i).transpose()) > kDependentRow) {
        append_orthonormal(basis, Aeq.row(i).transpose());
        W_eq.push_back(static_cast<int>(i));
      }
    }
    // Warm start: rows active at x enter the working set if independent (saves the
    // degenerate zero steps that would add them one at a time).
    for (Eigen::Index i = 0; i < Ain.rows() && basis.cols() < n; ++i) {
      const double slack = bin(i) - Ain.row(i).dot(x);
      if (std::abs(slack) <= feas_tol * (1.0 + std::abs(bin(i))) &&
          independent_part(basis, Ain.row(i).transpose()) > kDependentRow) {
        append_orthonormal(basis, Ain.row(i).transpose());
        W_in.push_back(static_cast<int>(i));
        in_working[static_cast<std::size_t>(i)] = 1;
      }
    }
  }

  bool at_subspace_minimum = false;
  int degenerate_steps = 0;
  for (int iter = 0; iter < max_iter; ++iter) {
    res.iterations = iter + 1;
    const auto k = static_cast<Eigen::Index>(W_eq.size() + W_in.size());
    Eigen::MatrixXd AW(k, n);
    for (std::size_t r = 0; r < W_eq.size(); ++r) AW.row(static_cast<Eigen::Index>(r)) = Aeq.row(W_eq[r]);
    for (std::size_t r = 0; r < W_in.size(); ++r)
      AW.row(static_cast<Eigen::Index>(W_eq.size() + r)) = Ain.row(W_in[r]);

    const Eigen::VectorXd grad = H * x + g;
    const double gscale = 1.0 + g.lpNorm<Eigen::Infinity>() + (H * x).lpNorm<Eigen::Infinity>();

    Eigen::HouseholderQR<Eigen::MatrixXd> qr(AW.transpose());
    const Eigen::MatrixXd Q = qr.householderQ();
    const Eigen::MatrixXd Z = Q.rightCols(n - k);

    Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
    bool zero_curvature = false;
    if (!at_subspace_minimum && n - k > 0) {
      const Eigen::VectorXd r = Z.transpose() * grad;
      if (r.lpNorm<Eigen::Infinity>() > opt_tol * gscale) {
        const Eigen::MatrixXd Hr = Z.transpose() * H * Z;
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Hr);
        const Eigen::VectorXd& lam = eig.eigenvalues();
        const Eigen::MatrixXd& V = eig.eigenvectors();
        const double lam_max = lam.cwiseAbs().maxCoeff();
        // Eigenvalues below this are zero curvature: H is only semidefinite by contract.
        const double lam_tol = 1e-11 * lam_max;
        Eigen::VectorXd r_null = Eigen::VectorXd::Zero(r.size());
        Eigen::VectorXd w = Eigen::VectorXd::Zero(r.size());
        for (Eigen::Index i = 0; i < lam.size(); ++i) {
          const double c = V.col(i).dot(r);
          if (lam(i) <= lam_tol) {
            r_null += c * V.col(i);
          } else {
            w -= (c / lam(i)) * V.col(i);
          }
        }
        if (r_null.lpNorm<Eigen::Infinity>() > opt_tol * gscale) {
          p = -Z * r_null;  // descent along a direction of zero curvature: no natural step
          zero_curvature = true;
        } else {
          p = Z * w;
        }
      }
    }

    if (p.lpNorm<Eigen::Infinity>() == 0.0) {
      // Subspace minimizer: multipliers from A_Wᵀ λ = −grad (A_W has full row rank).
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(k);
      if (k > 0) {
        const Eigen::VectorXd rhs = -(Q.leftCols(k).transpose() * grad);
        lambda = qr.matrixQR().topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(rhs);
      }
      int drop = -1;
      double most_negative = 0.0;
      const double dual_tol = 1e3 * opt_tol * std::max(1.0, lambda.lpNorm<Eigen::Infinity>());
      const bool bland = degenerate_steps >= kDegenerateStepsBeforeBland;
      for (std::size_t r = 0; r < W_in.size(); ++r) {
        const double lr = lambda(static_cast<Eigen::Index>(W_eq.size() + r));
        if (lr < -dual_tol) {
          if (bland) {
            if (drop < 0 || W_in[r] < W_in[static_cast<std::size_t>(drop)]) drop = static_cast<int>(r);
          } else if (lr < most_negative) {
            most_negative = lr;
            drop = static_cast<int>(r);
          }
        }
      }
      if (drop < 0) {
        res.outcome = QpOutcome::kOptimal;
        res.x = x;
        res.y_eq = Eigen::VectorXd::Zero(Aeq.rows());
        res.lambda_in = Eigen::VectorXd::Zero(Ain.rows());
        for (std::size_t r = 0; r < W_eq.size(); ++r)
          res.y_eq(W_eq[r]) = lambda(static_cast<Eigen::Index>(r));
        for (std::size_t r = 0; r < W_in.size(); ++r)
          res.lambda_in(W_in[r]) = std::max(0.0, lambda(static_cast<Eigen::Index>(W_eq.size() + r)));
        res.working_in = W_in;
        return res;
      }
      in_working[static_cast<std::size_t>(W_in[static_cast<std::size_t>(drop)])] = 0;
      W_in.erase(W_in.begin() + drop);
      at_subspace_minimum = false;
      continue;
    }

    // Ratio test along p.
    const double pnorm = p.norm();
    double alpha = zero_curvature ? kInf : 1.0;
    int blocking = -1;
    double blocking_ap = 0.0;
    const bool bland = degenerate_steps >= kDegenerateStepsBeforeBland;
    for (Eigen::Index i = 0; i < Ain.rows(); ++i) {
      if (in_working[static_cast<std::size_t>(i)]) continue;
      const double ap = Ain.row(i).dot(p);
      if (ap <= kParallel * pnorm) continue;
      const double slack = std::max(0.0, bin(i) - Ain.row(i).dot(x));
      const double step = slack / ap;
      const bool tie = blocking >= 0 && std::abs(step - alpha) <= 1e-14 * std::max(1.0, alpha);
      if (step < alpha && !tie) {
        alpha = step;
        blocking = static_cast<int>(i);
        blocking_ap = ap;
      } else if (tie && !bland && ap > blocking_ap) {
        blocking = static_cast<int>(i);  // prefer the steepest row: better conditioned R
        blocking_ap = ap;
      }
    }
    if (!std::isfinite(alpha)) {
      res.outcome = QpOutcome::kUnbounded;
      res.message = "objective unbounded below along a direction of zero curvature";
      res.x = x;
      return res;
    }
    x += alpha * p;
    degenerate_steps = (alpha * pnorm <= 1e-15 * (1.0 + x.norm())) ? degenerate_steps + 1 : 0;
    if (blocking >= 0) {
      W_in.push_back(blocking);
      in_working[static_cast<std::size_t>(blocking)] = 1;
      at_subspace_minimum = false;
    } else {
      at_subspace_minimum = !zero_curvature;  // full Newton step reached the subspace minimizer
    }
  }
  res.outcome = QpOutcome::kMaxIterations;
  res.message = "active-set iteration limit reached";
  res.x = x;
  return res;
}

double max_violation(const QpProblem& p, const Eigen::VectorXd& x) {
  double v = 0.0;
  if (p.A_eq.rows() > 0) v = std::max(v, (p.A_eq * x - p.b_eq).lpNorm<Eigen::Infinity>());
  if (p.A_in.rows() > 0) v = std::max(v, (p.A_in * x - p.b_in).maxCoeff());
  return v;
}

}  // namespace

std::string_view to_string(QpOutcome outcome) {
  switch (outcome) {
    case QpOutcome::kNotRun: return "not_run";
    case QpOutcome::kOptimal: return "optimal";
    case QpOutcome::kInfeasible: return "infeasible";
    case QpOutcome::kUnbounded: return "unbounded";
    case QpOutcome::kMaxIterations: return "max_iterations";
    case QpOutcome::kNumericalFailure: return "numerical_failure";
  }
  return "unknown";
}

void QpProblem::validate() const {
  const Eigen::Index n = g.size();
  auto fail = [&](const std::string& what, const std::string& got, const std::string& expected) {
    throw InvalidInput("QpProblem::" + what + " is " + got + "; expected " + expected);
  };
  if (H.rows() != n || H.cols() != n)
    fail("H", shape(H), std::to_string(n) + "x" + std::to_string(n) + " (n = g.size())");
  if (A_eq.rows() > 0 && A_eq.cols() != n)
    fail("A_eq", shape(A_eq), "p x " + std::to_string(n));
  if (A_eq.rows() != b_eq.size())
    fail("b_eq", "of size " + std::to_string(b_eq.size()), "size A_eq.rows() = " + std::to_string(A_eq.rows()));
  if (A_in.rows() > 0 && A_in.cols() != n)
    fail("A_in", shape(A_in), "m x " + std::to_string(n));
  if (A_in.rows() != b_in.size())
    fail("b_in", "of size " + std::to_string(b_in.size()), "size A_in.rows() = " + std::to_string(A_in.rows()));
  if (!H.allFinite() || !g.allFinite() || !A_eq.allFinite() || !b_eq.allFinite() ||
      !A_in.allFinite() || !b_in.allFinite())
    throw InvalidInput("QpProblem: non-finite entry in H, g, A_eq, b_eq, A_in or b_in; expected finite data");
}

void DenseQpSolver::Options::validate() const {
  if (!(feasibility_tolerance > 0.0))
    throw InvalidInput("DenseQpSolver::Options::feasibility_tolerance = " +
                       std::to_string(feasibility_tolerance) + "; expected > 0");
  if (!(optimality_tolerance > 0.0))
    throw InvalidInput("DenseQpSolver::Options::optimality_tolerance = " +
                       std::to_string(optimality_tolerance) + "; expected > 0");
  if (max_iterations < 0)
    throw InvalidInput("DenseQpSolver::Options::max_iterations = " + std::to_string(max_iterations) +
                       "; expected >= 0 (0 = automatic)");
}

std::string DenseQpSolver::Summary::brief_report() const {
  std::ostringstream s;
  s << "DenseQp: " << to_string(outcome) << ", iterations " << iterations << ", objective "
    << objective << ", infeasibility " << primal_infeasibility << ", KKT residual "
    << stationarity_residual << (used_phase_one ? ", phase one used" : "");
  if (!message.empty()) s << " (" << message << ")";
  return s.str();
}

DenseQpSolver::DenseQpSolver() : DenseQpSolver(Options{}) {}

DenseQpSolver::DenseQpSolver(Options options) : options_(options) { options_.validate(); }

namespace {

DenseQpSolver::Summary finish(const QpProblem& problem, const ScaledRows& eq,
                              const ScaledRows& in, const ActiveSetResult& r, int iterations,
                              bool phase_one) {
  DenseQpSolver::Summary s;
  s.outcome = r.outcome;
  s.message = r.message;
  s.iterations = iterations;
  s.used_phase_one = phase_one;
  s.x = r.x;
  s.multipliers_eq = Eigen::VectorXd::Zero(problem.A_eq.rows());
  s.multipliers_in = Eigen::VectorXd::Zero(problem.A_in.rows());
  if (r.outcome == QpOutcome::kOptimal) {
    // Scaled row â = a/‖a‖ with multiplier λ̂ contributes âλ̂ = a(λ̂/‖a‖).
    for (Eigen::Index i = 0; i < r.y_eq.size(); ++i)
      s.multipliers_eq(eq.original[static_cast<std::size_t>(i)]) = r.y_eq(i) / eq.norm(i);
    for (Eigen::Index i = 0; i < r.lambda_in.size(); ++i)
      s.multipliers_in(in.original[static_cast<std::size_t>(i)]) = r.lambda_in(i) / in.norm(i);
    for (int w : r.working_in) s.active_inequalities.push_back(in.original[static_cast<std::size_t>(w)]);
    std::sort(s.active_inequalities.begin(), s.active_inequalities.end());
  }
  s.objective = 0.5 * s.x.dot(problem.H * s.x) + problem.g.dot(s.x);
  s.primal_infeasibility = max_violation(problem, s.x);
  Eigen::VectorXd kkt = problem.H * s.x + problem.g;
  if (problem.A_eq.rows() > 0) kkt += problem.A_eq.transpose() * s.multipliers_eq;
  if (problem.A_in.rows() > 0) kkt += problem.A_in.transpose() * s.multipliers_in;
  s.stationarity_residual = kkt.lpNorm<Eigen::Infinity>();
  switch (r.outcome) {
    case QpOutcome::kOptimal: s.status = Status::kConverged; break;
    case QpOutcome::kMaxIterations: s.status = Status::kMaxIterations; break;
    default: s.status = Status::kNumericalFailure; break;
  }
  return s;
}

int iteration_limit(const DenseQpSolver::Options& o, const QpProblem& p) {
  if (o.max_iterations > 0) return o.max_iterations;
  return static_cast<int>(20 * (p.g.size() + p.A_in.rows() + p.A_eq.rows()) + 100);
}

}  // namespace

DenseQpSolver::Summary DenseQpSolver::solve(const QpProblem& problem,
                                            const Eigen::Ref<const Eigen::VectorXd>& feasible_start) const {
  problem.validate();
  if (feasible_start.size() != problem.g.size())
    throw InvalidInput("DenseQpSolver::solve: feasible_start has size " +
                       std::to_string(feasible_start.size()) + "; expected " +
                       std::to_string(problem.g.size()));
  const double tol = options_.feasibility_tolerance;
  const ScaledRows eq = scale_rows(problem.A_eq, problem.b_eq, true, tol);
  const ScaledRows in = scale_rows(problem.A_in, problem.b_in, false, tol);
  if (!eq.consistent || !in.consistent) {
    Summary s;
    s.status = Status::kNumericalFailure;
    s.outcome = QpOutcome::kInfeasible;
    s.message = !eq.consistent ? "equality row " + std::to_string(eq.bad_row) + " is zero with nonzero right-hand side"
                               : "inequality row " + std::to_string(in.bad_row) + " reads 0 <= negative";
    s.x = feasible_start;
    return s;
  }
  const ActiveSetResult r = active_set(problem.H, problem.g, eq.A, eq.b, in.A, in.b, feasible_start,
                                       tol, options_.optimality_tolerance, iteration_limit(options_, problem));
  return finish(problem, eq, in, r, r.iterations, false);
}

DenseQpSolver::Summary DenseQpSolver::solve(const QpProblem& problem) const {
  problem.validate();
  const Eigen::Index n = problem.g.size();
  const double tol = options_.feasibility_tolerance;
  const ScaledRows eq = scale_rows(problem.A_eq, problem.b_eq, true, tol);
  const ScaledRows in = scale_rows(problem.A_in, problem.b_in, false, tol);
  Summary infeasible;
  infeasible.status = Status::kNumericalFailure;
  infeasible.outcome = QpOutcome::kInfeasible;
  infeasible.used_phase_one = true;
  infeasible.x = Eigen::VectorXd::Zero(n);
  if (!eq.consistent || !in.consistent) {
    infeasible.message = !eq.consistent ? "equality row " + std::to_string(eq.bad_row) + " is zero with nonzero right-hand side"
                                        : "inequality row " + std::to_string(in.bad_row) + " reads 0 <= negative";
    return infeasible;
  }
  // Phase one. Equalities first: the minimum-norm solution of Â_eq x = b̂_eq.
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
  if (eq.A.rows() > 0) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(eq.A);
    x0 = cod.solve(eq.b);
    const double res = (eq.A * x0 - eq.b).lpNorm<Eigen::Infinity>();
    if (res > tol * (1.0 + eq.b.lpNorm<Eigen::Infinity>()) * 1e3) {
      infeasible.message = "equality constraints are inconsistent (least-squares residual " +
                           std::to_string(res) + ")";
      return infeasible;
    }
  }
  int iterations = 0;
  if (in.A.rows() > 0) {
    const double s0 = std::max(0.0, (in.A * x0 - in.b).maxCoeff());
    if (s0 > 0.0) {
      // LP in (x, s): min s  s.t.  Â_in x − s ≤ b̂_in,  −s ≤ 0,  Â_eq x = b̂_eq.
      const Eigen::Index m = in.A.rows();
      Eigen::MatrixXd H1 = Eigen::MatrixXd::Zero(n + 1, n + 1);
      Eigen::VectorXd g1 = Eigen::VectorXd::Zero(n + 1);
      g1(n) = 1.0;
      Eigen::MatrixXd A1(m + 1, n + 1);
      A1.setZero();
      A1.topLeftCorner(m, n) = in.A;
      A1.col(n).head(m).setConstant(-1.0);
      A1(m, n) = -1.0;
      Eigen::VectorXd b1(m + 1);
      b1.head(m) = in.b;
      b1(m) = 0.0;
      const ScaledRows in1 = scale_rows(A1, b1, false, tol);
      Eigen::MatrixXd E1 = Eigen::MatrixXd::Zero(eq.A.rows(), n + 1);
      E1.leftCols(n) = eq.A;
      Eigen::VectorXd start(n + 1);
      start.head(n) = x0;
      start(n) = s0;
      const ActiveSetResult r1 = active_set(H1, g1, E1, eq.b, in1.A, in1.b, start, tol,
                                            options_.optimality_tolerance,
                                            iteration_limit(options_, problem));
      iterations += r1.iterations;
      if (r1.outcome != QpOutcome::kOptimal) {
        infeasible.outcome = r1.outcome == QpOutcome::kMaxIterations ? QpOutcome::kMaxIterations
                                                                      : QpOutcome::kNumericalFailure;
        infeasible.status = r1.outcome == QpOutcome::kMaxIterations ? Status::kMaxIterations
                                                                     : Status::kNumericalFailure;
        infeasible.message = "phase one failed: " + r1.message;
        infeasible.iterations = iterations;
        return infeasible;
      }
      if (r1.x(n) > tol * (1.0 + in.b.lpNorm<Eigen::Infinity>())) {
        infeasible.message = "constraints are inconsistent: the smallest achievable violation is " +
                             std::to_string(r1.x(n)) + " (rows scaled to unit norm)";
        infeasible.iterations = iterations;
        infeasible.x = r1.x.head(n);
        return infeasible;
      }
      x0 = r1.x.head(n);
    }
  }
  const ActiveSetResult r = active_set(problem.H, problem.g, eq.A, eq.b, in.A, in.b, x0, tol,
                                       options_.optimality_tolerance, iteration_limit(options_, problem));
  return finish(problem, eq, in, r, iterations + r.iterations, true);
}

}  // namespace frictopt::optim
