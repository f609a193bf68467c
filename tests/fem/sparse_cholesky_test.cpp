// SPDX-License-Identifier: MIT
#include "frictopt/fem/sparse_cholesky.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <numeric>

#include "frictopt/fem/linear_elasticity.hpp"

namespace frictopt::fem {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

Eigen::SparseMatrix<double> small_stiffness() {
  static const auto shape = shape::BezierShape::surface(1.0, 1.0, 3, 3);
  static const mesh::StructuredMesh mesh(shape, 1.0, {{3, 3, 2}, 1.0});
  LinearElasticity problem(mesh, {2e11, 0.3, PlaneModel::kPlaneStrain},
                           expand_dirichlet(mesh, {{mesh::Face::kLeft, {}, {}}}), {});
  problem.assemble(mesh.positions(Eigen::VectorXd::Constant(9, 0.1)));
  return problem.stiffness();
}

TEST(SparseCholesky, SolvesAgainstADenseOracle) {
  const Eigen::SparseMatrix<double> A = small_stiffness();
  SparseCholesky cholesky;
  cholesky.analyze(A);
  ASSERT_EQ(cholesky.factorize(A), Status::kConverged);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = cholesky.solve(b);
  const Eigen::VectorXd oracle = Eigen::MatrixXd(A).ldlt().solve(b);
  // Backward-stable solves of the same SPD system: agreement to cond·eps.
  EXPECT_LE((x - oracle).norm(), 1e6 * kEps * oracle.norm());
  EXPECT_GT(cholesky.factor_nonzeros(), 0.0);
}

TEST(SparseCholesky, TrailingFactorIsTheCholeskyFactorOfTheSchurComplement) {
  const Eigen::SparseMatrix<double> A = small_stiffness();
  const int n = static_cast<int>(A.rows());
  // A scattered, unsorted trailing set: the order must be the one given.
  const std::vector<int> trailing{n - 1, 5, 17, 2, n / 2, n / 3};
  SparseCholesky cholesky;
  cholesky.analyze(A, trailing);
  ASSERT_EQ(cholesky.factorize(A), Status::kConverged);
  const Eigen::MatrixXd L = cholesky.trailing_factor();
  const Eigen::MatrixXd dense = Eigen::MatrixXd(A);
  const Eigen::MatrixXd Ainv = dense.inverse();
  Eigen::MatrixXd Ainv_tt(trailing.size(), trailing.size());
  for (std::size_t i = 0; i < trailing.size(); ++i)
    for (std::size_t j = 0; j < trailing.size(); ++j) Ainv_tt(i, j) = Ainv(trailing[i], trailing[j]);
  // (A⁻¹)_tt = S⁻¹ = (L Lᵀ)⁻¹.
  const Eigen::MatrixXd S = L * L.transpose();
  EXPECT_LE((S.inverse() - Ainv_tt).norm(), 1e-8 * Ainv_tt.norm());
  EXPECT_LE(L.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().norm(), 0.0);
  // The trailing ordering does not change solves.
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  EXPECT_LE((cholesky.solve(b) - dense.ldlt().solve(b)).norm(), 1e-8 * cholesky.solve(b).norm());
}

TEST(SparseCholesky, ReportsAnIndefiniteMatrix) {
  Eigen::SparseMatrix<double> A(3, 3);
  A.insert(0, 0) = 1.0;
  A.insert(1, 1) = -1.0;
  A.insert(2, 2) = 1.0;
  A.makeCompressed();
  SparseCholesky cholesky;
  cholesky.analyze(A);
  EXPECT_EQ(cholesky.factorize(A), Status::kNumericalFailure);
  EXPECT_NE(cholesky.message().find("not positive definite"), std::string::npos) << cholesky.message();
}

}  // namespace
}  // namespace frictopt::fem
