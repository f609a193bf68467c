// SPDX-License-Identifier: MIT
// The LAPACK/BLAS wrappers of linalg::blas against Eigen's own (slower) dense algorithms.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "frictopt/linalg/dense_blas.hpp"

namespace frictopt::linalg::blas {
namespace {

Eigen::MatrixXd spd(int n) {
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd S = B * B.transpose() / n;
  S.diagonal().array() += 0.5;
  return S;
}

TEST(DenseBlas, CholeskyKernelsMatchEigen) {
  const int n = 57;
  const Eigen::MatrixXd S = spd(n);
  const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(S).matrixL();
  const Eigen::MatrixXd inverse = S.inverse();
  const Eigen::MatrixXd from_factor = inverse_from_cholesky(L);
  EXPECT_LE((from_factor - inverse).norm(), 1e-12 * inverse.norm());
  EXPECT_LE((from_factor - from_factor.transpose()).norm(), 0.0);  // mirrored exactly

  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  Eigen::VectorXd solved = x;
  cholesky_solve_in_place(L, solved);
  EXPECT_LE((S * solved - x).norm(), 1e-12 * x.norm());
  Eigen::VectorXd y(n);
  symmetric_times(from_factor, x, y);
  EXPECT_LE((y - inverse * x).norm(), 1e-12 * (inverse * x).norm());
}

TEST(DenseBlas, SingularValuesMatchEigenAndRevealRank) {
  // A 40 × 55 matrix of rank 31 (a product of random factors), so 9 singular values vanish.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Random(40, 31) * Eigen::MatrixXd::Random(31, 55);
  const Eigen::VectorXd ours = singular_values(A);
  const Eigen::VectorXd eigen = Eigen::JacobiSVD<Eigen::MatrixXd>(A).singularValues();
  ASSERT_EQ(ours.size(), 40);
  EXPECT_LE((ours - eigen).norm(), 1e-12 * eigen(0));
  EXPECT_EQ((ours.array() > 1e-10 * ours(0)).count(), 31);
  EXPECT_EQ(singular_values(Eigen::MatrixXd(0, 3)).size(), 0);
}

}  // namespace
}  // namespace frictopt::linalg::blas
