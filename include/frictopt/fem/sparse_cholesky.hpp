// SPDX-License-Identifier: MIT
// Sparse Cholesky A = L Lᵀ by CHOLMOD (supernodal), symbolic analysis once per pattern.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

#include "frictopt/core/status.hpp"

namespace frictopt::fem {

/// RAII wrapper around CHOLMOD (through Eigen's CholmodSupernodalLLT) that keeps cholmod types
/// out of public headers. Lifetime: analyze(pattern) once per mesh, factorize(values) per
/// design, then any number of solves. Not thread-safe.
class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// Symbolic analysis (fill-reducing ordering, supernodes) of the lower triangle's pattern.
  void analyze(const Eigen::SparseMatrix<double>& A);
  bool analyzed() const { return analyzed_; }
  /// Numeric factorization; analyze() must have been called with the same pattern. Returns
  /// kNumericalFailure (message names the column) when A is not positive definite.
  [[nodiscard]] Status factorize(const Eigen::SparseMatrix<double>& A);
  const std::string& message() const { return message_; }
  /// x = A⁻¹ b for one or several right-hand sides (columns).
  Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const;
  Eigen::MatrixXd solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const;
  /// Nonzeros in the factor L (a measure of fill and memory); 0 before factorize.
  double factor_nonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool analyzed_ = false;
  std::string message_ = "not factorized";
};

}  // namespace frictopt::fem
