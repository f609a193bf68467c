// SPDX-License-Identifier: MIT
// linalg::SpdSolver (CHOLMOD backend) against Eigen's dense Cholesky on small SPD matrices.
#include "frictopt/linalg/spd_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <limits>
#include <numeric>

#include "frictopt/core/error.hpp"

namespace frictopt::linalg {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The 7-point Laplacian of an n³ grid plus 0.1·I (SPD, condition ≈ 10²): the sparsity of a
// 3D FE stiffness matrix with one unknown per node.
Eigen::SparseMatrix<double> grid_laplacian(int n) {
  const int size = n * n * n;
  const auto index = [n](int i, int j, int k) { return i + n * (j + n * k); };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int row = index(i, j, k);
        t.emplace_back(row, row, 6.1);
        if (i > 0) t.emplace_back(row, index(i - 1, j, k), -1.0);
        if (i + 1 < n) t.emplace_back(row, index(i + 1, j, k), -1.0);
        if (j > 0) t.emplace_back(row, index(i, j - 1, k), -1.0);
        if (j + 1 < n) t.emplace_back(row, index(i, j + 1, k), -1.0);
        if (k > 0) t.emplace_back(row, index(i, j, k - 1), -1.0);
        if (k + 1 < n) t.emplace_back(row, index(i, j, k + 1), -1.0);
      }
  Eigen::SparseMatrix<double> A(size, size);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

TEST(SpdSolver, FactoryMakesTheCholmodBackendByDefault) {
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  ASSERT_NE(solver, nullptr);
  EXPECT_EQ(solver->name(), "cholmod");
  EXPECT_TRUE(solver->supports_trailing_factor());
  EXPECT_EQ(parse_spd_backend("cholmod"), SpdBackend::kCholmod);
  EXPECT_THROW((void)parse_spd_backend("mumps"), InvalidInput);
}

TEST(SpdSolver, SolvesAgainstADenseOracle) {
  const Eigen::SparseMatrix<double> A = grid_laplacian(5);
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  ASSERT_EQ(solver->analyze(A), Status::kConverged) << solver->message();
  ASSERT_EQ(solver->factorize(A), Status::kConverged) << solver->message();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd oracle = Eigen::MatrixXd(A).ldlt().solve(b);
  // Backward-stable solves of the same SPD system (condition ≈ 10²): agreement to 100·cond·eps.
  EXPECT_LE((solver->solve(b) - oracle).norm(), 1e4 * kEps * oracle.norm());
  Eigen::MatrixXd B(A.rows(), 3);
  B << b, 2.0 * b, Eigen::VectorXd::Ones(A.rows());
  const Eigen::MatrixXd X = solver->solve_many(B);
  EXPECT_LE((X.col(1) - 2.0 * oracle).norm(), 2e4 * kEps * oracle.norm());
  EXPECT_LE((Eigen::MatrixXd(A) * X - B).norm(), 1e4 * kEps * B.norm());
  EXPECT_GT(solver->factor_nonzeros(), 0.0);
  EXPECT_GT(solver->factor_flops(), 0.0);
}

TEST(SpdSolver, TrailingFactorIsTheCholeskyFactorOfTheSchurComplement) {
  const Eigen::SparseMatrix<double> A = grid_laplacian(4);
  const int n = static_cast<int>(A.rows());
  // A scattered, unsorted trailing set: the order must be the one given.
  const std::vector<int> trailing{n - 1, 5, 17, 2, n / 2, n / 3};
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  ASSERT_EQ(solver->analyze(A, trailing), Status::kConverged) << solver->message();
  ASSERT_EQ(solver->factorize(A), Status::kConverged);
  EXPECT_EQ(solver->trailing_size(), static_cast<Eigen::Index>(trailing.size()));
  const Eigen::MatrixXd L = solver->trailing_factor();
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  const Eigen::MatrixXd Ainv = dense.inverse();
  Eigen::MatrixXd Ainv_tt(trailing.size(), trailing.size());
  for (std::size_t i = 0; i < trailing.size(); ++i)
    for (std::size_t j = 0; j < trailing.size(); ++j) Ainv_tt(i, j) = Ainv(trailing[i], trailing[j]);
  // (A⁻¹)_tt = S⁻¹ = (L Lᵀ)⁻¹.
  const Eigen::MatrixXd S = L * L.transpose();
  EXPECT_LE((S.inverse() - Ainv_tt).norm(), 1e-12 * Ainv_tt.norm());
  EXPECT_LE(L.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().norm(), 0.0);
  // The trailing ordering does not change solves.
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  EXPECT_LE((solver->solve(b) - dense.ldlt().solve(b)).norm(), 1e-12 * solver->solve(b).norm());
}

// When every unknown is trailing (one cell layer under a fixed top: only the contact DOFs are
// free) the leading block is empty. CHOLMOD's analysis of it returns no factor, which must not
// be dereferenced (it was: SIGSEGV in Release). The whole matrix is then the Schur block.
TEST(SpdSolver, TrailingBlockMayBeTheWholeMatrix) {
  const Eigen::SparseMatrix<double> A = grid_laplacian(3);
  const int n = static_cast<int>(A.rows());
  std::vector<int> trailing(static_cast<std::size_t>(n));
  std::iota(trailing.rbegin(), trailing.rend(), 0);  // reversed: the given order must be kept
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  ASSERT_EQ(solver->analyze(A, trailing), Status::kConverged) << solver->message();
  ASSERT_EQ(solver->factorize(A), Status::kConverged) << solver->message();
  const Eigen::MatrixXd L = solver->trailing_factor();
  // P A Pᵀ = L Lᵀ with P the reversal.
  const Eigen::MatrixXd PAP = Eigen::MatrixXd(A).reverse();
  EXPECT_LE((L * L.transpose() - PAP).norm(), 20 * kEps * PAP.norm());
}

TEST(SpdSolver, ReportsASystemWithoutUnknownsInsteadOfCrashing) {
  const Eigen::SparseMatrix<double> empty(0, 0);
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  EXPECT_EQ(solver->analyze(empty), Status::kNumericalFailure);
  EXPECT_NE(solver->message().find("no unknowns"), std::string::npos) << solver->message();
  EXPECT_EQ(solver->analyze(empty, {}), Status::kNumericalFailure);
  EXPECT_FALSE(solver->analyzed());
  // factorize after a failed analysis reports the analysis' reason, never dereferences it.
  EXPECT_EQ(solver->factorize(empty), Status::kNumericalFailure);
  EXPECT_NE(solver->message().find("no unknowns"), std::string::npos) << solver->message();
}

// The backend's own analysis failing (here CHOLMOD refusing a non-square stype = −1 matrix: it
// returns no factor) is a status with CHOLMOD's reason in every build, never a dereference.
TEST(SpdSolver, ReportsAFailedBackendAnalysis) {
  Eigen::SparseMatrix<double> rectangular(3, 2);
  rectangular.insert(0, 0) = 1.0;
  rectangular.insert(2, 1) = 1.0;
  rectangular.makeCompressed();
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  EXPECT_EQ(solver->analyze(rectangular), Status::kNumericalFailure);
  EXPECT_NE(solver->message().find("cholmod_analyze returned no factor"), std::string::npos) << solver->message();
  EXPECT_FALSE(solver->analyzed());
  EXPECT_EQ(solver->factorize(rectangular), Status::kNumericalFailure);
}

TEST(SpdSolver, RefusesInvalidTrailingIndices) {
  const Eigen::SparseMatrix<double> A = grid_laplacian(2);
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  EXPECT_THROW((void)solver->analyze(A, {0, 8}), InvalidInput);
  EXPECT_THROW((void)solver->analyze(A, {1, 1}), InvalidInput);
}

TEST(SpdSolver, ReportsAnIndefiniteMatrix) {
  Eigen::SparseMatrix<double> A(3, 3);
  A.insert(0, 0) = 1.0;
  A.insert(1, 1) = -1.0;
  A.insert(2, 2) = 1.0;
  A.makeCompressed();
  const std::unique_ptr<SpdSolver> solver = SpdSolver::create();
  ASSERT_EQ(solver->analyze(A), Status::kConverged);
  EXPECT_EQ(solver->factorize(A), Status::kNumericalFailure);
  EXPECT_NE(solver->message().find("not positive definite"), std::string::npos) << solver->message();
}

}  // namespace
}  // namespace frictopt::linalg
