// SPDX-License-Identifier: MIT
#include "frictopt/contact/delassus.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "frictopt/linalg/dense_blas.hpp"
#include "frictopt/core/error.hpp"

// Sub-block (leading-dimension) forms of the BLAS-3 kernels that linalg::blas does not offer:
// the principal blocks of M solve with trailing triangles of L in place.
extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
}

namespace frictopt::contact {
namespace {
// Columns per triangular solve of principal_block: large enough for BLAS-3 efficiency, small
// enough that a group's first index is close to all of its columns' (rows above it are zero).
constexpr Eigen::Index kColumnsPerSolve = 192;
}  // namespace

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
  if (cached(rows) && cached(cols)) {
    Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t j = 0; j < cols.size(); ++j)
      for (std::size_t i = 0; i < rows.size(); ++i)
        out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            cache_.block(cache_.position[static_cast<std::size_t>(rows[i])],
                         cache_.position[static_cast<std::size_t>(cols[j])]);
    return out;
  }
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

bool SchurDelassus::cached(const std::vector<Eigen::Index>& idx) const {
  if (cache_.position.empty()) return idx.empty();
  return std::all_of(idx.begin(), idx.end(), [&](Eigen::Index k) { return cache_.position[static_cast<std::size_t>(k)] >= 0; });
}

void SchurDelassus::release_block_cache() const { cache_ = BlockCache{}; }

void SchurDelassus::release_block_columns() const { cache_.columns = Eigen::MatrixXd(); }

Eigen::MatrixXd SchurDelassus::principal_block(const std::vector<Eigen::Index>& idx) const {
  const Eigen::Index m = L_.rows();
  // Without its columns the cache cannot grow: start over unless it already holds idx.
  if (!cache_.indices.empty() && cache_.columns.size() == 0 && !cached(idx)) release_block_cache();
  if (cache_.position.empty()) cache_.position.assign(static_cast<std::size_t>(m), -1);
  std::vector<Eigen::Index> fresh;
  for (const Eigen::Index k : idx) {
    FRICTOPT_ASSERT(k >= 0 && k < m, "SchurDelassus::principal_block: index in range");
    if (cache_.position[static_cast<std::size_t>(k)] < 0) fresh.push_back(k);
  }
  std::sort(fresh.begin(), fresh.end());
  FRICTOPT_ASSERT(std::adjacent_find(fresh.begin(), fresh.end()) == fresh.end(),
                  "SchurDelassus::principal_block: distinct indices");
  if (!fresh.empty()) extend_cache(fresh);
  return block(idx, idx);
}

void SchurDelassus::extend_cache(const std::vector<Eigen::Index>& fresh) const {
  const Eigen::Index m = L_.rows();
  const int ldl = static_cast<int>(m);
  const Eigen::Index old_count = static_cast<Eigen::Index>(cache_.indices.size());
  const Eigen::Index first = old_count > 0 ? std::min(cache_.first_row, fresh.front()) : fresh.front();
  const Eigen::Index rows = m - first, count = static_cast<Eigen::Index>(fresh.size());
  // X_new = L⁻¹E_fresh, group by group: column k of E starts at row k, and a group whose first
  // index is r solves L[r:, r:] Y = E[r:, group] (the rows above r stay zero).
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(rows, count);
  for (Eigen::Index j = 0; j < count; ++j) X(fresh[static_cast<std::size_t>(j)] - first, j) = 1.0;
  const double one = 1.0, zero = 0.0;
  const int ldx = static_cast<int>(rows);
  for (Eigen::Index start = 0; start < count; start += kColumnsPerSolve) {
    const Eigen::Index r = fresh[static_cast<std::size_t>(start)];
    const int n = static_cast<int>(m - r), width = static_cast<int>(std::min(kColumnsPerSolve, count - start));
    dtrsm_("L", "L", "N", "N", &n, &width, &one, L_.data() + r + r * m, &ldl, X.data() + (r - first) + start * rows,
           &ldx);
  }
  // Gram blocks: new × new by dsyrk (lower triangle, mirrored), old × new by dgemm.
  Eigen::MatrixXd nn(count, count);
  const int cn = static_cast<int>(count);
  dsyrk_("L", "T", &cn, &ldx, &one, X.data(), &ldx, &zero, nn.data(), &cn);
  nn.triangularView<Eigen::StrictlyUpper>() = nn.transpose();
  Eigen::MatrixXd on(old_count, count);
  if (old_count > 0) {
    // The old columns are zero above cache_.first_row >= first: multiply over their rows only.
    const Eigen::Index offset = cache_.first_row - first;
    const int k = static_cast<int>(m - cache_.first_row), co = static_cast<int>(old_count);
    const int ldo = static_cast<int>(cache_.columns.rows());
    dgemm_("T", "N", &co, &cn, &k, &one, cache_.columns.data(), &ldo, X.data() + offset, &ldx, &zero, on.data(), &co);
  }
  for (Eigen::Index j = 0; j < count; ++j) {
    const double sj = signs_(fresh[static_cast<std::size_t>(j)]);
    for (Eigen::Index i = 0; i < count; ++i) nn(i, j) *= signs_(fresh[static_cast<std::size_t>(i)]) * sj;
    for (Eigen::Index i = 0; i < old_count; ++i) on(i, j) *= signs_(cache_.indices[static_cast<std::size_t>(i)]) * sj;
  }
  BlockCache next;
  next.first_row = first;
  next.indices = cache_.indices;
  next.indices.insert(next.indices.end(), fresh.begin(), fresh.end());
  next.position = std::move(cache_.position);
  for (Eigen::Index j = 0; j < count; ++j) next.position[static_cast<std::size_t>(fresh[static_cast<std::size_t>(j)])] = old_count + j;
  next.columns.resize(rows, old_count + count);
  if (old_count > 0) {
    const Eigen::Index offset = cache_.first_row - first;
    next.columns.topLeftCorner(offset, old_count).setZero();
    next.columns.block(offset, 0, cache_.columns.rows(), old_count) = cache_.columns;
  }
  next.columns.rightCols(count) = X;
  next.block.resize(old_count + count, old_count + count);
  if (old_count > 0) {
    next.block.topLeftCorner(old_count, old_count) = cache_.block;
    next.block.topRightCorner(old_count, count) = on;
    next.block.bottomLeftCorner(count, old_count) = on.transpose();
  }
  next.block.bottomRightCorner(count, count) = nn;
  cache_ = std::move(next);
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

Eigen::MatrixXd turn_delassus(const Eigen::MatrixXd& standard, const Eigen::MatrixXd& frame_rows) {
  const Eigen::Index dim = frame_rows.rows();
  if (frame_rows.cols() != dim || (dim != 2 && dim != 3) || standard.rows() != standard.cols() ||
      standard.rows() % dim != 0)
    throw InvalidInput(fmt::format("turn_delassus: M {}×{} and frame rows {}×{}; expected a square M of a multiple "
                                   "of dim rows and a dim × dim frame (dim 2 or 3)",
                                   standard.rows(), standard.cols(), frame_rows.rows(), frame_rows.cols()));
  // Q = F D: F's rows with the standard signs D = diag(−1, (−1,) 1) undone.
  Eigen::MatrixXd Q = frame_rows;
  Q.leftCols(dim - 1) *= -1.0;
  const Eigen::Index p = standard.rows() / dim;
  Eigen::MatrixXd M(standard.rows(), standard.cols());
  for (Eigen::Index j = 0; j < p; ++j)
    for (Eigen::Index i = 0; i < p; ++i)
      M.block(dim * i, dim * j, dim, dim) = Q * standard.block(dim * i, dim * j, dim, dim) * Q.transpose();
  return 0.5 * (M + M.transpose());
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
