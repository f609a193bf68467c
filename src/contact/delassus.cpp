// SPDX-License-Identifier: MIT
#include "frictopt/contact/delassus.hpp"

#include <algorithm>

namespace frictopt::contact {

FactorizedDelassus::FactorizedDelassus(const fem::SparseCholesky& cholesky, const ContactBoundary& boundary)
    : cholesky_(cholesky), boundary_(boundary) {}

void FactorizedDelassus::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(boundary_.num_free());
  boundary_.add_transpose_times(x, w);
  y = boundary_.times(cholesky_.solve(w));
}

Eigen::VectorXd FactorizedDelassus::diagonal() const {
  if (diagonal_.size() == 0) diagonal_ = dense_delassus(cholesky_, boundary_).diagonal();
  return diagonal_;
}

Eigen::MatrixXd dense_delassus(const fem::SparseCholesky& cholesky, const ContactBoundary& boundary,
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
    const Eigen::MatrixXd V = cholesky.solve_many(W);
    for (Eigen::Index j = 0; j < width; ++j) M.col(start + j) = boundary.times(V.col(j));
  }
  return 0.5 * (M + M.transpose());
}

}  // namespace frictopt::contact
