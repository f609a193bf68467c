// SPDX-License-Identifier: MIT
// The few dense kernels of contact-sized problems that go to the system BLAS/LAPACK (OpenBLAS
// via Debian's alternatives). Why not Eigen: built for -march=x86-64-v2 it has no AVX kernels,
// while OpenBLAS picks AVX2/AVX-512 at run time and threads; on the m ≈ 5,000 contact blocks of
// 100k-unknown 3D problems that is a 4–8× difference (docs/benchmarks.md).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace frictopt::linalg::blas {

/// B ← L⁻¹ B for a lower-triangular L (dtrsm).
void lower_solve_in_place(const Eigen::MatrixXd& L, Eigen::MatrixXd& B);
/// x ← L⁻ᵀ L⁻¹ x for a lower-triangular L (two dtrsv).
void cholesky_solve_in_place(const Eigen::MatrixXd& L, Eigen::Ref<Eigen::VectorXd> x);
/// (L Lᵀ)⁻¹ from the lower Cholesky factor L, as a full symmetric matrix (dpotri: 2m³/3 flops,
/// a third of what m triangular solves with unit vectors and a product would cost).
Eigen::MatrixXd inverse_from_cholesky(const Eigen::MatrixXd& L);
/// y = S x for a symmetric S of which the lower triangle is read (dsymv).
void symmetric_times(const Eigen::MatrixXd& S, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y);
/// Aᵀ B (dgemm).
Eigen::MatrixXd transpose_times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);
/// The singular values of A, descending (dgesdd without vectors: threaded BLAS-3 bidiagonalization;
/// at 5,000² about 10× faster than Eigen's BDCSVD built for x86-64-v2). Used by the certificate's
/// (MF1′) rank test.
Eigen::VectorXd singular_values(const Eigen::MatrixXd& A);
/// x = K⁻¹ r by LU with partial pivoting (dgetrf/dgetrs); returns false if K is exactly
/// singular. `reciprocal_condition` gets LAPACK's 1-norm estimate (dgecon).
bool lu_solve(Eigen::MatrixXd K, const Eigen::VectorXd& r, Eigen::VectorXd& x, double& reciprocal_condition);

/// LU factors with partial pivoting in single precision (sgetrf/sgetrs): half the memory and
/// about half the time of dgetrf, accurate enough for a preconditioner (the semismooth Newton
/// method's GMRES, docs/contact.md "Semismooth Newton"), where the Krylov iteration in double
/// precision recovers the digits.
class SinglePrecisionLu {
 public:
  /// Factorizes A (square, taken over); returns false if a pivot is exactly zero.
  bool factorize(Eigen::MatrixXf A);
  /// x ← (LU)⁻¹ x, the solve in float.
  void solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const;
  Eigen::Index size() const { return lu_.rows(); }

 private:
  Eigen::MatrixXf lu_;
  std::vector<int> pivots_;
  mutable Eigen::VectorXf work_;
};

}  // namespace frictopt::linalg::blas
