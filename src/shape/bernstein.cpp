// SPDX-License-Identifier: MIT
#include "frictopt/shape/bernstein.hpp"

#include "frictopt/core/error.hpp"

namespace frictopt::shape {

Eigen::VectorXd bernstein_basis(int degree, double t) {
  FRICTOPT_ASSERT(degree >= 0, "negative Bernstein degree");
  // Raise the degree one step at a time: b^{k}_i = (1 − t) b^{k−1}_i + t b^{k−1}_{i−1}.
  Eigen::VectorXd b = Eigen::VectorXd::Zero(degree + 1);
  b(0) = 1.0;
  for (int k = 1; k <= degree; ++k) {
    for (int i = k; i >= 1; --i) b(i) = (1.0 - t) * b(i) + t * b(i - 1);
    b(0) *= (1.0 - t);
  }
  return b;
}

Eigen::VectorXd bernstein_basis_derivative(int degree, double t) {
  Eigen::VectorXd db = Eigen::VectorXd::Zero(degree + 1);
  if (degree == 0) return db;
  const Eigen::VectorXd lower = bernstein_basis(degree - 1, t);
  for (int i = 0; i <= degree; ++i) {
    const double left = i >= 1 ? lower(i - 1) : 0.0;
    const double right = i <= degree - 1 ? lower(i) : 0.0;
    db(i) = degree * (left - right);
  }
  return db;
}

}  // namespace frictopt::shape
