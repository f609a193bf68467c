// SPDX-License-Identifier: MIT
#include "frictopt/linalg/dense_blas.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "frictopt/core/error.hpp"
#include "frictopt/linalg/blas_threads.hpp"

extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dtrsv_(const char* uplo, const char* trans, const char* diag, const int* n, const double* a, const int* lda,
            double* x, const int* incx);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dsymv_(const char* uplo, const int* n, const double* alpha, const double* a, const int* lda, const double* x,
            const int* incx, const double* beta, double* y, const int* incy);
void dgesdd_(const char* jobz, const int* m, const int* n, double* a, const int* lda, double* s, double* u,
             const int* ldu, double* vt, const int* ldvt, double* work, const int* lwork, int* iwork, int* info);
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
void dgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* lda, const int* ipiv,
             double* b, const int* ldb, int* info);
void sgetrf_(const int* m, const int* n, float* a, const int* lda, int* ipiv, int* info);
void sgetrs_(const char* trans, const int* n, const int* nrhs, const float* a, const int* lda, const int* ipiv,
             float* b, const int* ldb, int* info);
void dgecon_(const char* norm, const int* n, const double* a, const int* lda, const double* anorm, double* rcond,
             double* work, int* iwork, int* info);
}

namespace frictopt::linalg::blas {

void lower_solve_in_place(const Eigen::MatrixXd& L, Eigen::MatrixXd& B) {
  const int m = static_cast<int>(L.rows()), n = static_cast<int>(B.cols());
  if (m == 0 || n == 0) return;
  const double one = 1.0;
  const BlasThreadsForCall threads(static_cast<double>(m) * m * n);
  dtrsm_("L", "L", "N", "N", &m, &n, &one, L.data(), &m, B.data(), &m);
}

void cholesky_solve_in_place(const Eigen::MatrixXd& L, Eigen::Ref<Eigen::VectorXd> x) {
  const int n = static_cast<int>(L.rows()), one = 1;
  if (n == 0) return;
  FRICTOPT_ASSERT(x.size() == n, "cholesky_solve_in_place: x of the factor's size");
  const BlasThreadsForCall threads(2.0 * n * n);
  dtrsv_("L", "N", "N", &n, L.data(), &n, x.data(), &one);
  dtrsv_("L", "T", "N", &n, L.data(), &n, x.data(), &one);
}

Eigen::MatrixXd inverse_from_cholesky(const Eigen::MatrixXd& L) {
  const int n = static_cast<int>(L.rows());
  Eigen::MatrixXd S = L;
  if (n == 0) return S;
  int info = 0;
  const BlasThreadsForCall threads(2.0 / 3.0 * n * n * static_cast<double>(n));
  dpotri_("L", &n, S.data(), &n, &info);
  // info > 0 means a zero diagonal entry: impossible for the factor of a successful Cholesky.
  FRICTOPT_ASSERT(info == 0, "inverse_from_cholesky: dpotri info = " + std::to_string(info));
  S.triangularView<Eigen::StrictlyUpper>() = S.transpose();
  return S;
}

void symmetric_times(const Eigen::MatrixXd& S, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) {
  const int n = static_cast<int>(S.rows()), one = 1;
  if (n == 0) return;
  FRICTOPT_ASSERT(x.size() == n && y.size() == n, "symmetric_times: vectors of the matrix's size");
  const double alpha = 1.0, beta = 0.0;
  const BlasThreadsForCall threads(2.0 * n * n);
  dsymv_("L", &n, &alpha, S.data(), &n, x.data(), &one, &beta, y.data(), &one);
}

namespace {
Eigen::MatrixXd gemm(const char* ta, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, int rows, int inner) {
  const int cols = static_cast<int>(B.cols());
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(rows, cols);
  if (rows == 0 || cols == 0 || inner == 0) return C;
  const double one = 1.0, zero = 0.0;
  const int lda = static_cast<int>(A.rows()), ldb = static_cast<int>(B.rows());
  const BlasThreadsForCall threads(2.0 * rows * cols * static_cast<double>(inner));
  dgemm_(ta, "N", &rows, &cols, &inner, &one, A.data(), &lda, B.data(), &ldb, &zero, C.data(), &rows);
  return C;
}
}  // namespace

Eigen::MatrixXd transpose_times(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return gemm("T", A, B, static_cast<int>(A.cols()), static_cast<int>(A.rows()));
}


Eigen::VectorXd singular_values(const Eigen::MatrixXd& original) {
  Eigen::MatrixXd A = original;  // dgesdd overwrites its input; the original serves the fallback
  const int m = static_cast<int>(A.rows()), n = static_cast<int>(A.cols()), k = std::min(m, n);
  Eigen::VectorXd s(k);
  if (k == 0) return s;
  int info = 0, lwork = -1, one = 1;
  double query = 0.0, unused = 0.0;
  std::vector<int> iwork(static_cast<std::size_t>(8 * k));
  const BlasThreadsForCall threads(4.0 * std::max(m, n) * static_cast<double>(k) * k);
  dgesdd_("N", &m, &n, A.data(), &m, s.data(), &unused, &one, &unused, &one, &query, &lwork, iwork.data(), &info);
  lwork = static_cast<int>(query);
  std::vector<double> work(static_cast<std::size_t>(std::max(lwork, 1)));
  dgesdd_("N", &m, &n, A.data(), &m, s.data(), &unused, &one, &unused, &one, work.data(), &lwork, iwork.data(), &info);
  FRICTOPT_ASSERT(info >= 0, "singular_values: dgesdd argument " + std::to_string(-info) + " invalid");
  // info > 0: dgesdd's bidiagonal iteration did not converge (rare); Eigen's slower but robust
  // divide-and-conquer SVD answers instead of a wrong rank.
  if (info > 0) return Eigen::BDCSVD<Eigen::MatrixXd>(original).singularValues();
  return s;
}

bool lu_solve(Eigen::MatrixXd K, const Eigen::VectorXd& r, Eigen::VectorXd& x, double& reciprocal_condition) {
  const int n = static_cast<int>(K.rows());
  x = r;
  if (n == 0) {
    reciprocal_condition = 1.0;
    return true;
  }
  const double anorm = K.cwiseAbs().colwise().sum().maxCoeff();
  std::vector<int> ipiv(static_cast<std::size_t>(n));
  int info = 0;
  const BlasThreadsForCall threads(2.0 / 3.0 * n * n * static_cast<double>(n));
  dgetrf_(&n, &n, K.data(), &n, ipiv.data(), &info);
  if (info > 0) {
    reciprocal_condition = 0.0;
    return false;
  }
  std::vector<double> work(static_cast<std::size_t>(4 * n));
  std::vector<int> iwork(static_cast<std::size_t>(n));
  dgecon_("1", &n, K.data(), &n, &anorm, &reciprocal_condition, work.data(), iwork.data(), &info);
  const int one = 1;
  dgetrs_("N", &n, &one, K.data(), &n, ipiv.data(), x.data(), &n, &info);
  return true;
}

bool SinglePrecisionLu::factorize(Eigen::MatrixXf A) {
  FRICTOPT_ASSERT(A.rows() == A.cols(), "SinglePrecisionLu: A must be square");
  lu_ = std::move(A);
  const int n = static_cast<int>(lu_.rows());
  pivots_.assign(static_cast<std::size_t>(n), 0);
  if (n == 0) return true;
  int info = 0;
  const BlasThreadsForCall threads(1.0 / 3.0 * n * n * static_cast<double>(n));
  sgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
  return info == 0;
}

void SinglePrecisionLu::solve_in_place(Eigen::Ref<Eigen::VectorXd> x) const {
  const int n = static_cast<int>(lu_.rows());
  FRICTOPT_ASSERT(x.size() == n, "SinglePrecisionLu::solve_in_place: size mismatch");
  if (n == 0) return;
  work_ = x.cast<float>();
  const int one = 1;
  int info = 0;
  sgetrs_("N", &n, &one, lu_.data(), &n, pivots_.data(), work_.data(), &n, &info);
  x = work_.cast<double>();
}

}  // namespace frictopt::linalg::blas
