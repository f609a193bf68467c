// SPDX-License-Identifier: MIT
#include "frictopt/linalg/linear_operator.hpp"

#include <string>
#include <utility>

#include "frictopt/core/error.hpp"

namespace frictopt::linalg {

DenseOperator::DenseOperator(Eigen::MatrixXd matrix) : matrix_(std::move(matrix)) {
  if (matrix_.rows() != matrix_.cols())
    throw InvalidInput("DenseOperator: matrix is " + std::to_string(matrix_.rows()) + " x " +
                       std::to_string(matrix_.cols()) + "; expected a square matrix");
  if (!matrix_.allFinite())
    throw InvalidInput("DenseOperator: matrix has non-finite entries; expected finite values");
}

void DenseOperator::apply(const Eigen::Ref<const Eigen::VectorXd>& x,
                          Eigen::Ref<Eigen::VectorXd> y) const {
  FRICTOPT_ASSERT(x.size() == matrix_.cols() && y.size() == matrix_.rows(),
                  "DenseOperator::apply: size mismatch");
  y.noalias() = matrix_ * x;
}

}  // namespace frictopt::linalg
