// SPDX-License-Identifier: MIT
#include "frictopt/fem/sparse_cholesky.hpp"

#include <Eigen/CholmodSupport>
#include <fmt/format.h>

#include "frictopt/core/error.hpp"

namespace frictopt::fem {

struct SparseCholesky::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

SparseCholesky::SparseCholesky() : impl_(std::make_unique<Impl>()) {
  // The library never prints (STYLE.md §5): silence CHOLMOD's own warnings, we report statuses.
  impl_->llt.cholmod().print = 0;
}
SparseCholesky::~SparseCholesky() = default;
SparseCholesky::SparseCholesky(SparseCholesky&&) noexcept = default;
SparseCholesky& SparseCholesky::operator=(SparseCholesky&&) noexcept = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& A) {
  impl_->llt.analyzePattern(A);
  analyzed_ = true;
}

Status SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
  FRICTOPT_ASSERT(analyzed_, "analyze() before factorize()");
  impl_->llt.factorize(A);
  if (impl_->llt.info() != Eigen::Success) {
    const auto& common = impl_->llt.cholmod();
    message_ = fmt::format(
        "factorization failed: the stiffness matrix is not positive definite (CHOLMOD status {}) "
        "— are rigid-body motions left free by the Dirichlet conditions?",
        common.status);
    return Status::kNumericalFailure;
  }
  message_ = "factorized";
  return Status::kConverged;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::Ref<const Eigen::VectorXd>& b) const {
  return impl_->llt.solve(Eigen::VectorXd(b));
}

Eigen::MatrixXd SparseCholesky::solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const {
  return impl_->llt.solve(Eigen::MatrixXd(B));
}

double SparseCholesky::factor_nonzeros() const {
  auto& common = const_cast<Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>&>(impl_->llt).cholmod();
  return common.lnz;
}

}  // namespace frictopt::fem
