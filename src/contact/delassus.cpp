// SPDX-License-Identifier: MIT
#include "frictopt/contact/delassus.hpp"

#include <algorithm>

#include "frictopt/linalg/dense_blas.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::contact {

DenseDelassus::DenseDelassus(std::shared_ptr<const Eigen::MatrixXd> matrix) : matrix_(std::move(matrix)) {
  FRICTOPT_ASSERT(matrix_ && matrix_->rows() == matrix_->cols(), "DenseDelassus: a square matrix");
}

void DenseDelassus::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  // Small M: Eigen's single-threaded product. OpenBLAS threads a dsymv of any size, and on a
  // shared machine its threads' synchronization dominates small products: the identification
  // example (m = 147) took 10.6 s instead of 0.68 s while a build ran on the other core.
  constexpr Eigen::Index kThreadedMinSize = 2000;
  if (matrix_->rows() < kThreadedMinSize) {
    y.noalias() = *matrix_ * x;
  } else {
    linalg::blas::symmetric_times(*matrix_, x, y);  // Ref<VectorXd> is contiguous (inner stride 1)
  }
}

Eigen::MatrixXd DenseDelassus::block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (std::size_t i = 0; i < rows.size(); ++i)
      out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (*matrix_)(rows[i], cols[j]);
  return out;
}

SchurDelassus::SchurDelassus(Eigen::MatrixXd schur_factor, int dim) : L_(std::move(schur_factor)) {
  signs_.resize(L_.rows());
  for (Eigen::Index k = 0; k < L_.rows(); ++k) signs_(k) = (k % dim) == dim - 1 ? 1.0 : -1.0;
}

void SchurDelassus::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  Eigen::VectorXd v = signs_.cwiseProduct(x);
  linalg::blas::cholesky_solve_in_place(L_, v);
  y = signs_.cwiseProduct(v);
}

Eigen::VectorXd SchurDelassus::diagonal() const {
  if (diagonal_.size() == 0) {
    Eigen::MatrixXd X = Eigen::MatrixXd::Identity(L_.rows(), L_.cols());
    linalg::blas::lower_solve_in_place(L_, X);
    diagonal_ = X.colwise().squaredNorm().transpose();
  }
  return diagonal_;
}

Eigen::MatrixXd SchurDelassus::block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const {
  // M[r, c] = D_r (L⁻¹e_r)ᵀ(L⁻¹e_c) D_c: one triangular solve for the union of the columns.
  std::vector<Eigen::Index> all(rows);
  all.insert(all.end(), cols.begin(), cols.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(L_.rows(), static_cast<Eigen::Index>(all.size()));
  for (std::size_t j = 0; j < all.size(); ++j) X(all[j], static_cast<Eigen::Index>(j)) = 1.0;
  linalg::blas::lower_solve_in_place(L_, X);
  const auto position = [&](Eigen::Index k) {
    return static_cast<Eigen::Index>(std::lower_bound(all.begin(), all.end(), k) - all.begin());
  };
  Eigen::MatrixXd R(X.rows(), static_cast<Eigen::Index>(rows.size())), C(X.rows(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) R.col(static_cast<Eigen::Index>(i)) = signs_(rows[i]) * X.col(position(rows[i]));
  for (std::size_t j = 0; j < cols.size(); ++j) C.col(static_cast<Eigen::Index>(j)) = signs_(cols[j]) * X.col(position(cols[j]));
  return linalg::blas::transpose_times(R, C);
}

Eigen::MatrixXd SchurDelassus::dense() const {
  Eigen::MatrixXd M = linalg::blas::inverse_from_cholesky(L_);
  M.array().colwise() *= signs_.array();
  M.array().rowwise() *= signs_.transpose().array();
  return M;
}

FactorizedDelassus::FactorizedDelassus(const linalg::SpdSolver& solver, const ContactBoundary& boundary)
    : solver_(solver), boundary_(boundary) {}

void FactorizedDelassus::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(boundary_.num_free());
  boundary_.add_transpose_times(x, w);
  y = boundary_.times(solver_.solve(w));
}

Eigen::VectorXd FactorizedDelassus::diagonal() const {
  if (diagonal_.size() == 0) diagonal_ = dense_delassus(solver_, boundary_).diagonal();
  return diagonal_;
}

Eigen::MatrixXd FactorizedDelassus::block(const std::vector<Eigen::Index>& rows,
                                          const std::vector<Eigen::Index>& cols) const {
  const Eigen::Index m = boundary_.num_unknowns();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(boundary_.num_free(), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
    e(cols[j]) = 1.0;
    boundary_.add_transpose_times(e, W.col(static_cast<Eigen::Index>(j)));
  }
  const Eigen::MatrixXd V = solver_.solve_many(W);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const Eigen::VectorXd column = boundary_.times(V.col(static_cast<Eigen::Index>(j)));
    for (std::size_t i = 0; i < rows.size(); ++i) out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = column(rows[i]);
  }
  return out;
}

Eigen::MatrixXd dense_delassus(const linalg::SpdSolver& solver, const ContactBoundary& boundary,
                               int block_columns) {
  const Eigen::Index m = boundary.num_unknowns();
  Eigen::MatrixXd M(m, m);
  for (Eigen::Index start = 0; start < m; start += block_columns) {
    const Eigen::Index width = std::min<Eigen::Index>(block_columns, m - start);
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(boundary.num_free(), width);
    for (Eigen::Index j = 0; j < width; ++j) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
      e(start + j) = 1.0;
      boundary.add_transpose_times(e, W.col(j));
    }
    const Eigen::MatrixXd V = solver.solve_many(W);
    for (Eigen::Index j = 0; j < width; ++j) M.col(start + j) = boundary.times(V.col(j));
  }
  return 0.5 * (M + M.transpose());
}

}  // namespace frictopt::contact
