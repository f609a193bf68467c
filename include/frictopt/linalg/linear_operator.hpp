// SPDX-License-Identifier: MIT
// The abstract SPD operator that iterative solvers are written against (the contact QP solvers
// apply the Delassus operator M = G A⁻¹ Gᵀ of docs/theory/state-problem.md §5 through it), with a
// dense and a scaled implementation. Operators are applied, never formed, as in MFEM's
// linalg/operator.hpp.
#pragma once

#include <Eigen/Core>

namespace frictopt::linalg {

/// SPD operator on Rⁿ (e.g. the Delassus operator); `apply` may be expensive (one sparse solve).
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

/// factor · base, without copying base (e.g. the Delassus matrix at another Young's modulus:
/// M(E) = (E₀/E) M(E₀)). Lifetime: `base` must outlive this operator.
class ScaledOperator final : public LinearOperator {
 public:
  ScaledOperator(const LinearOperator& base, double factor) : base_(base), factor_(factor) {}
  Eigen::Index size() const override { return base_.size(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override {
    base_.apply(x, y);
    y *= factor_;
  }
  Eigen::VectorXd diagonal() const override { return factor_ * base_.diagonal(); }

 private:
  const LinearOperator& base_;
  double factor_;
};

}  // namespace frictopt::linalg
