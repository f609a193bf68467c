// SPDX-License-Identifier: MIT
// The few dense kernels of contact-sized problems that go to the system BLAS/LAPACK (OpenBLAS
// via Debian's alternatives). Why not Eigen: built for -march=x86-64-v2 it has no AVX kernels,
// while OpenBLAS picks AVX2/AVX-512 at run time and threads; on the m ≈ 5,000 contact blocks of
// 100k-unknown 3D problems that is a 4–8× difference (docs/benchmarks.md).
#pragma once

#include <Eigen/Core>

namespace frictopt::contact::blas {

/// B ← L⁻¹ B for a lower-triangular L (dtrsm).
void lower_solve_in_place(const Eigen::MatrixXd& L, Eigen::MatrixXd& B);
/// Aᵀ B (dgemm).
Eigen::MatrixXd transpose_times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
/// A B (dgemm).
Eigen::MatrixXd times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
/// x = K⁻¹ r by LU with partial pivoting (dgetrf/dgetrs); returns false if K is exactly
/// singular. `reciprocal_condition` gets LAPACK's 1-norm estimate (dgecon).
bool lu_solve(Eigen::MatrixXd K, const Eigen::VectorXd& r, Eigen::VectorXd& x, double& reciprocal_condition);

}  // namespace frictopt::contact::blas
