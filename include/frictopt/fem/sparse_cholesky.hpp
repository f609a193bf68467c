// SPDX-License-Identifier: MIT
// Sparse Cholesky P A Pᵀ = L Lᵀ by CHOLMOD (supernodal), symbolic analysis once per pattern,
// optionally with a prescribed trailing block whose factor is the Schur complement's.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "frictopt/core/status.hpp"

namespace frictopt::fem {

/// RAII wrapper around CHOLMOD that keeps cholmod types out of public headers. Lifetime:
/// analyze(pattern) once per mesh, factorize(values) per design, then any number of solves.
/// Not thread-safe. Reads only the lower triangle of A.
///
/// Trailing block: analyze(A, trailing) orders the given rows/columns last (the rest by
/// CHOLMOD's own fill-reducing choice, AMD or METIS, on the leading block). Then the trailing
/// m × m block L_tt of L satisfies L_tt L_ttᵀ = S, the Schur complement of A onto those
/// indices, and (A⁻¹)_tt = S⁻¹: a contact problem's Delassus matrix comes from dense algebra
/// on L_tt instead of m sparse solves (spec 02 §5; DESIGN.md performance budget).
class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;

  /// Symbolic analysis (fill-reducing ordering, supernodes) with CHOLMOD's default orderings.
  void analyze(const Eigen::SparseMatrix<double>& A);
  /// Symbolic analysis with `trailing` (distinct indices) ordered last, in the given order.
  void analyze(const Eigen::SparseMatrix<double>& A, const std::vector<int>& trailing);
  bool analyzed() const;
  /// Numeric factorization; analyze() must have been called with the same pattern. Returns
  /// kNumericalFailure (message names the column) when A is not positive definite.
  [[nodiscard]] Status factorize(const Eigen::SparseMatrix<double>& A);
  const std::string& message() const { return message_; }
  /// x = A⁻¹ b for one or several right-hand sides (columns).
  Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const;
  Eigen::MatrixXd solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const;
  /// Nonzeros in the factor L (a measure of fill and memory); 0 before factorize.
  double factor_nonzeros() const;
  /// Flop count of the numeric factorization from the last analysis (deterministic, unlike times).
  double factor_flops() const;
  /// The dense lower-triangular L_tt (m × m, in the order of `trailing`) of the last
  /// factorization; requires analyze(A, trailing).
  Eigen::MatrixXd trailing_factor() const;
  /// Number of trailing indices (0 without a trailing block).
  Eigen::Index trailing_size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string message_ = "not factorized";
};

}  // namespace frictopt::fem
