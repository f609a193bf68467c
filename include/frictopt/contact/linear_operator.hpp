// SPDX-License-Identifier: MIT
// The abstract SPD operator the contact QP solvers are written against: the Delassus operator
// M = G A⁻¹ Gᵀ of spec 02, §7 / §9.2, applied either as a dense matrix (small problems, tests)
// or through the sparse Cholesky factorization of the stiffness matrix (the FEM glue).
#pragma once

#include <Eigen/Core>

namespace frictopt::contact {

/// SPD operator on Rⁿ (the Delassus operator); `apply` may be expensive (one sparse solve).
/// Implementations must be usable from a const reference and deterministic.
class LinearOperator {
 public:
  virtual ~LinearOperator() = default;
  /// n, the number of rows (= columns).
  virtual Eigen::Index size() const = 0;
  /// y = M x; `x` and `y` have size() entries and must not alias.
  virtual void apply(const Eigen::Ref<const Eigen::VectorXd>& x,
                     Eigen::Ref<Eigen::VectorXd> y) const = 0;
  /// diag(M), used for scaling and step estimates.
  virtual Eigen::VectorXd diagonal() const = 0;
};

/// A LinearOperator that wraps (and owns a copy of) a dense symmetric matrix.
/// Symmetry and definiteness are the caller's responsibility; the constructor checks only that
/// the matrix is square and finite (throws InvalidInput otherwise).
class DenseOperator final : public LinearOperator {
 public:
  explicit DenseOperator(Eigen::MatrixXd matrix);
  Eigen::Index size() const override { return matrix_.rows(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x,
             Eigen::Ref<Eigen::VectorXd> y) const override;
  Eigen::VectorXd diagonal() const override { return matrix_.diagonal(); }
  const Eigen::MatrixXd& matrix() const { return matrix_; }

 private:
  Eigen::MatrixXd matrix_;
};

}  // namespace frictopt::contact
