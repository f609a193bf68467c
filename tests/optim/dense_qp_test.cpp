// SPDX-License-Identifier: MIT
#include "frictopt/optim/dense_qp.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "common/finite_difference.hpp"
#include "frictopt/core/error.hpp"

namespace fo = frictopt::optim;
using frictopt::testing::kSeed;

namespace {

// The problems below have data of size O(1) and n ≤ 8; an active-set solve is a handful of
// backward-stable QR factorizations, so 1e-9 leaves ~1e6 ulps for the accumulated round-off.
constexpr double kTol = 1e-9;

Eigen::MatrixXd random_matrix(std::mt19937_64& rng, Eigen::Index r, Eigen::Index c) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd m(r, c);
  for (Eigen::Index i = 0; i < r; ++i)
    for (Eigen::Index j = 0; j < c; ++j) m(i, j) = normal(rng);
  return m;
}

Eigen::VectorXd random_vector(std::mt19937_64& rng, Eigen::Index n) { return random_matrix(rng, n, 1); }

// Random instance whose feasible set contains a random point x_feas.
fo::QpProblem random_problem(std::mt19937_64& rng, Eigen::Index n, Eigen::Index m, Eigen::Index p,
                             Eigen::Index rank_H) {
  fo::QpProblem qp;
  const Eigen::MatrixXd L = random_matrix(rng, n, rank_H);
  qp.H = L * L.transpose();
  qp.g = random_vector(rng, n);
  const Eigen::VectorXd x_feas = random_vector(rng, n);
  qp.A_in = random_matrix(rng, m, n);
  std::uniform_real_distribution<double> slack(0.0, 1.0);
  qp.b_in = qp.A_in * x_feas;
  for (Eigen::Index i = 0; i < m; ++i) qp.b_in(i) += slack(rng);
  qp.A_eq = random_matrix(rng, p, n);
  qp.b_eq = qp.A_eq * x_feas;
  return qp;
}

// Brute force for strictly convex QPs: the minimizer is the solution of the KKT system of
// some active set S ⊆ inequalities that is feasible with λ_S ≥ 0; try them all.
double brute_force_objective(const fo::QpProblem& qp) {
  const Eigen::Index n = qp.g.size();
  const Eigen::Index m = qp.A_in.rows();
  const Eigen::Index p = qp.A_eq.rows();
  double best = std::numeric_limits<double>::infinity();
  for (unsigned mask = 0; mask < (1u << m); ++mask) {
    std::vector<Eigen::Index> S;
    for (Eigen::Index i = 0; i < m; ++i)
      if (mask & (1u << i)) S.push_back(i);
    const auto k = static_cast<Eigen::Index>(S.size()) + p;
    if (k > n) continue;
    Eigen::MatrixXd A(k, n);
    Eigen::VectorXd b(k);
    for (Eigen::Index r = 0; r < p; ++r) {
      A.row(r) = qp.A_eq.row(r);
      b(r) = qp.b_eq(r);
    }
    for (std::size_t r = 0; r < S.size(); ++r) {
      A.row(p + static_cast<Eigen::Index>(r)) = qp.A_in.row(S[r]);
      b(p + static_cast<Eigen::Index>(r)) = qp.b_in(S[r]);
    }
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + k, n + k);
    K.topLeftCorner(n, n) = qp.H;
    K.topRightCorner(n, k) = A.transpose();
    K.bottomLeftCorner(k, n) = A;
    Eigen::VectorXd rhs(n + k);
    rhs << -qp.g, b;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (!lu.isInvertible()) continue;
    const Eigen::VectorXd sol = lu.solve(rhs);
    const Eigen::VectorXd x = sol.head(n);
    const Eigen::VectorXd lam = sol.tail(k);
    bool ok = true;
    for (Eigen::Index r = p; r < k; ++r) ok = ok && lam(r) >= -kTol;
    if (m > 0) ok = ok && (qp.A_in * x - qp.b_in).maxCoeff() <= kTol;
    if (!ok) continue;
    best = std::min(best, 0.5 * x.dot(qp.H * x) + qp.g.dot(x));
  }
  return best;
}

void expect_kkt(const fo::QpProblem& qp, const fo::DenseQpSolver::Summary& s, const std::string& where) {
  ASSERT_TRUE(s.converged()) << where << ": " << s.brief_report();
  const double scale = 1.0 + qp.g.lpNorm<Eigen::Infinity>() + qp.H.lpNorm<Eigen::Infinity>() * s.x.lpNorm<Eigen::Infinity>();
  EXPECT_LE(s.primal_infeasibility, kTol * (1.0 + qp.b_in.lpNorm<Eigen::Infinity>())) << where;
  EXPECT_LE(s.stationarity_residual, kTol * scale) << where;
  for (Eigen::Index i = 0; i < qp.A_in.rows(); ++i) {
    EXPECT_GE(s.multipliers_in(i), 0.0) << where << " row " << i;
    const double slack = qp.b_in(i) - qp.A_in.row(i).dot(s.x);
    EXPECT_LE(std::abs(s.multipliers_in(i) * slack), kTol * scale * (1.0 + std::abs(qp.b_in(i))))
        << where << " complementarity, row " << i;
  }
}

}  // namespace

TEST(DenseQpSolver, SolvesUnconstrainedStrictlyConvexQpByNewtonStep) {
  std::mt19937_64 rng{kSeed};
  const fo::QpProblem qp = random_problem(rng, 5, 0, 0, 5);
  const auto s = fo::DenseQpSolver().solve(qp);
  ASSERT_TRUE(s.converged()) << s.brief_report();
  const Eigen::VectorXd exact = qp.H.ldlt().solve(-qp.g);
  EXPECT_LE((s.x - exact).norm(), kTol * exact.norm());
}

TEST(DenseQpSolver, MatchesBruteForceEnumerationOfActiveSetsOnRandomInstances) {
  std::mt19937_64 rng{kSeed};
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Index n = 2 + trial % 3;
    const Eigen::Index m = 3 + trial % 4;
    const Eigen::Index p = trial % 2;
    const fo::QpProblem qp = random_problem(rng, n, m, p, n);
    const auto s = fo::DenseQpSolver().solve(qp);
    const std::string where = "seed " + std::to_string(kSeed) + ", trial " + std::to_string(trial);
    expect_kkt(qp, s, where);
    const double bf = brute_force_objective(qp);
    EXPECT_NEAR(s.objective, bf, kTol * (1.0 + std::abs(bf))) << where;
  }
}

TEST(DenseQpSolver, SatisfiesKktForRankDeficientHessiansWithEqualities) {
  std::mt19937_64 rng{kSeed + 1};
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Index n = 3 + trial % 4;
    // rank(H) < n: bounded only thanks to a box, as in the bundle QP (H = diag(I/t, 0)).
    fo::QpProblem qp = random_problem(rng, n, 4, trial % 3 == 0 ? 1 : 0, n - 2);
    const Eigen::Index m = qp.A_in.rows();
    qp.A_in.conservativeResize(m + 2 * n, n);
    qp.b_in.conservativeResize(m + 2 * n);
    qp.A_in.bottomRows(2 * n) << Eigen::MatrixXd::Identity(n, n), -Eigen::MatrixXd::Identity(n, n);
    qp.b_in.tail(2 * n).setConstant(10.0);
    // The random feasible point is N(0,1)-distributed, far inside the box |x_i| ≤ 10.
    const auto s = fo::DenseQpSolver().solve(qp);
    expect_kkt(qp, s, "seed " + std::to_string(kSeed + 1) + ", trial " + std::to_string(trial));
  }
}

TEST(DenseQpSolver, HandlesDuplicatedAndParallelCutsOfADegenerateBundle) {
  // Bundle-shaped: min v + ½‖d‖² s.t. g_iᵀd − v ≤ β_i with the same cut repeated and a cut
  // that is a convex combination of two others (degenerate vertex).
  const Eigen::Index n = 2;
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Zero(n + 1, n + 1);
  qp.H.topLeftCorner(n, n).setIdentity();
  qp.g = Eigen::VectorXd::Unit(n + 1, n);
  qp.A_in.resize(6, n + 1);
  qp.A_in << 1, 0, -1,  1, 0, -1,  1, 0, -1,  -1, 0, -1,  0, 0, -1,  0, 1, -1;
  qp.b_in.setZero(6);
  qp.A_eq.resize(0, n + 1);
  qp.b_eq.resize(0);
  const auto s = fo::DenseQpSolver().solve(qp, Eigen::VectorXd::Zero(n + 1));
  expect_kkt(qp, s, "degenerate bundle");
  // Minimum-norm element of conv{(1,0), (−1,0), (0,0), (0,1)} is 0: d = 0, v = 0.
  EXPECT_LE(s.x.norm(), kTol);
  EXPECT_NEAR(s.multipliers_in.sum(), 1.0, kTol);
}

TEST(DenseQpSolver, ReportsInfeasibleConstraints) {
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Identity(2, 2);
  qp.g = Eigen::VectorXd::Zero(2);
  qp.A_in.resize(2, 2);
  qp.A_in << 1, 1, -1, -1;  // x1 + x2 ≤ 0 and x1 + x2 ≥ 1
  qp.b_in = Eigen::Vector2d(0.0, -1.0);
  qp.A_eq.resize(0, 2);
  qp.b_eq.resize(0);
  const auto s = fo::DenseQpSolver().solve(qp);
  EXPECT_EQ(s.outcome, fo::QpOutcome::kInfeasible) << s.brief_report();
  EXPECT_EQ(s.status, frictopt::Status::kNumericalFailure);
}

TEST(DenseQpSolver, ReportsInconsistentEqualities) {
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Identity(2, 2);
  qp.g = Eigen::VectorXd::Zero(2);
  qp.A_in.resize(0, 2);
  qp.b_in.resize(0);
  qp.A_eq.resize(2, 2);
  qp.A_eq << 1, 1, 2, 2;
  qp.b_eq = Eigen::Vector2d(1.0, 3.0);
  EXPECT_EQ(fo::DenseQpSolver().solve(qp).outcome, fo::QpOutcome::kInfeasible);
}

TEST(DenseQpSolver, ReportsAnUnboundedLinearProgram) {
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Zero(2, 2);
  qp.g = Eigen::Vector2d(1.0, 0.0);
  qp.A_in.resize(1, 2);
  qp.A_in << 0, 1;
  qp.b_in = Eigen::VectorXd::Ones(1);
  qp.A_eq.resize(0, 2);
  qp.b_eq.resize(0);
  EXPECT_EQ(fo::DenseQpSolver().solve(qp).outcome, fo::QpOutcome::kUnbounded);
}

TEST(DenseQpSolver, RejectsInconsistentDimensionsNamingTheBlock) {
  fo::QpProblem qp;
  qp.H = Eigen::MatrixXd::Identity(3, 3);
  qp.g = Eigen::VectorXd::Zero(2);
  try {
    (void)fo::DenseQpSolver().solve(qp);
    FAIL() << "expected InvalidInput";
  } catch (const frictopt::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("QpProblem::H"), std::string::npos) << e.what();
  }
  fo::DenseQpSolver::Options o;
  o.feasibility_tolerance = -1.0;
  EXPECT_THROW(fo::DenseQpSolver{o}, frictopt::InvalidInput);
}

TEST(DenseQpSolver, BadlyScaledBundleQpEndsWithAStatusAndNeverANanSolution) {
  // An unscaled direction QP: min v + ‖d‖²/(2t) s.t. gᵀd − v ≤ 0 with ‖g‖ = 1e7,
  // t = 1e-6. Its reduced Hessian spans 1e6 to 1e-8 and the solver may not resolve it — BundleTrust
  // now scales the QP (bundle_trust.cpp) — but whatever it does, it must either solve it (finite
  // x satisfying KKT) or say it did not; a NaN never passes for a solution.
  for (const double gnorm : {1.0, 1e7, 1e12}) {
    const Eigen::Index n = 10;
    fo::QpProblem qp;
    qp.H = Eigen::MatrixXd::Zero(n + 1, n + 1);
    qp.H.topLeftCorner(n, n).diagonal().setConstant(1.0 / 1e-6);
    qp.g = Eigen::VectorXd::Zero(n + 1);
    qp.g(n) = 1.0;
    qp.A_in = Eigen::MatrixXd::Zero(1, n + 1);
    qp.A_in.row(0).head(n) = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0).normalized().transpose() * gnorm;
    qp.A_in(0, n) = -1.0;
    qp.b_in = Eigen::VectorXd::Zero(1);
    qp.A_eq.resize(0, n + 1);
    qp.b_eq.resize(0);
    const auto s = fo::DenseQpSolver().solve(qp, Eigen::VectorXd::Zero(n + 1));
    if (s.converged()) {
      ASSERT_TRUE(s.x.allFinite()) << "|g| = " << gnorm;
      // Exact solution: d = −t g, v = −t‖g‖²: objective −t‖g‖²/2.
      EXPECT_NEAR(s.objective, -0.5e-6 * gnorm * gnorm, 1e-8 * 0.5e-6 * gnorm * gnorm) << "|g| = " << gnorm;
    } else {
      EXPECT_NE(s.status, frictopt::Status::kConverged);
      EXPECT_FALSE(s.message.empty()) << "|g| = " << gnorm;
    }
  }
}
