// SPDX-License-Identifier: MIT
#include "krylov_delassus.hpp"

namespace frictopt::petsc::detail {

KrylovDelassus::KrylovDelassus(FreeSolve solve, const contact::ContactBoundary& boundary)
    : solve_(std::move(solve)), boundary_(boundary) {}

void KrylovDelassus::apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(boundary_.num_free());
  boundary_.add_transpose_times(x, w);
  y = boundary_.times(solve_(w));
}

Eigen::VectorXd KrylovDelassus::column(Eigen::Index k) const {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(size());
  e(k) = 1.0;
  Eigen::VectorXd y(size());
  apply(e, y);
  return y;
}

Eigen::VectorXd KrylovDelassus::diagonal() const {
  if (diagonal_.size() == 0) {
    diagonal_.resize(size());
    for (Eigen::Index k = 0; k < size(); ++k) diagonal_(k) = column(k)(k);
  }
  return diagonal_;
}

Eigen::MatrixXd KrylovDelassus::block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j) {
    const Eigen::VectorXd y = column(cols[j]);
    for (std::size_t i = 0; i < rows.size(); ++i) out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = y(rows[i]);
  }
  return out;
}

}  // namespace frictopt::petsc::detail
