// SPDX-License-Identifier: MIT
// A dense convex QP solver (primal active-set method for positive SEMIdefinite Hessians) for the
// small subproblems of the bundle trust method (docs/theory/bundle-trust.md §3) and the
// stationarity QP (docs/theory/stationarity.md §2). Hand-written because our Debian package set has
// no dense QP library usable from C++ (`apt-cache search quadprog` lists only r-cran-quadprog;
// eiquadprog, qpOASES, OSQP are not packaged), and because both subproblems have singular Hessians,
// which Goldfarb–Idnani does not accept.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/status.hpp"

namespace frictopt::optim {

/// min ½ xᵀHx + gᵀx  s.t.  A_eq x = b_eq,  A_in x ≤ b_in.
/// H (n × n) must be symmetric positive semidefinite; A_eq is p × n, A_in is m × n (either may
/// have zero rows). Rank-deficient or redundant constraint sets are allowed.
struct QpProblem {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Eigen::MatrixXd A_eq;
  Eigen::VectorXd b_eq;
  Eigen::MatrixXd A_in;
  Eigen::VectorXd b_in;

  [[nodiscard]] Eigen::Index num_variables() const { return g.size(); }
  /// Throws InvalidInput naming the mismatching block and its shape.
  void validate() const;
};

/// How a QP solve ended (finer than Status, which it maps to).
enum class QpOutcome { kNotRun, kOptimal, kInfeasible, kUnbounded, kMaxIterations, kNumericalFailure };
std::string_view to_string(QpOutcome outcome);

class DenseQpSolver {
 public:
  struct Options {
    // Constraint rows are scaled to unit Euclidean norm; a scaled row counts as satisfied when
    // its residual is at most feasibility_tolerance·(1 + |b_i|). > 0.
    double feasibility_tolerance = 1e-10;
    // Relative tolerance on reduced gradients and multiplier signs (scaled by the gradient
    // norm); a few hundred ulps above round-off of the null-space products. > 0.
    double optimality_tolerance = 1e-11;
    // Limit on active-set changes; 0 means automatic 20·(n + m + p) + 100. >= 0.
    int max_iterations = 0;
    void validate() const;  // throws InvalidInput naming field, value, expectation
  };

  struct Summary {
    Status status = Status::kNotRun;
    QpOutcome outcome = QpOutcome::kNotRun;
    std::string message = "solve() has not been called";
    Eigen::VectorXd x;                  ///< primal solution (or last iterate)
    Eigen::VectorXd multipliers_eq;     ///< y with Hx + g + A_eqᵀy + A_inᵀλ = 0
    Eigen::VectorXd multipliers_in;     ///< λ ≥ 0, zero for inactive rows
    std::vector<int> active_inequalities;  ///< indices of A_in rows in the final working set
    double objective = kNaN;
    double primal_infeasibility = kNaN;  ///< max over rows of the (unscaled) violation
    double stationarity_residual = kNaN; ///< ‖Hx + g + A_eqᵀy + A_inᵀλ‖∞
    int iterations = 0;
    bool used_phase_one = false;
    [[nodiscard]] bool converged() const { return outcome == QpOutcome::kOptimal; }
    [[nodiscard]] std::string brief_report() const;
  };

  DenseQpSolver();  ///< default Options
  explicit DenseQpSolver(Options options);

  /// Solves the QP from scratch: a phase-one LP (minimize the largest violation) finds a
  /// feasible point, or reports kInfeasible; phase two then runs from there.
  [[nodiscard]] Summary solve(const QpProblem& problem) const;

  /// Solves from a point the caller knows to be feasible (within feasibility_tolerance), which
  /// skips phase one. Throws InvalidInput if `feasible_start` has the wrong size.
  [[nodiscard]] Summary solve(const QpProblem& problem,
                              const Eigen::Ref<const Eigen::VectorXd>& feasible_start) const;

 private:
  Options options_;
};

}  // namespace frictopt::optim
