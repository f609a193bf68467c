// SPDX-License-Identifier: MIT
// The interface every direct solver of a sparse symmetric positive definite system implements
// (the stiffness matrix of fem), and the factory that picks a backend from Options. The shape
// follows Ceres' SparseCholesky (internal/ceres/sparse_cholesky.h): analyze once per pattern,
// factorize per matrix, then any number of solves.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/status.hpp"

namespace frictopt::linalg {

/// Backends of SpdSolver. CHOLMOD (supernodal, SuiteSparse) is the first and the default.
enum class SpdBackend { kCholmod };
std::string_view to_string(SpdBackend backend);
/// Inverse of to_string; throws InvalidInput listing the accepted names.
SpdBackend parse_spd_backend(std::string_view name);

/// Lifetime choices of an SpdSolver (SpdSolver::Options). A namespace-level struct, not a nested
/// one, so that `= {}` default arguments can use it inside the class.
struct SpdSolverOptions {
  SpdBackend backend = SpdBackend::kCholmod;  ///< which implementation factorizes
};

/// Direct solver of A x = b for a sparse SPD A (lower triangle read, full storage accepted).
///
/// Lifetime: analyze(A) once per sparsity pattern (fill-reducing ordering, symbolic
/// factorization), factorize(A) per set of values with that pattern, then any number of solves.
/// Not thread-safe. Failures are statuses with a message (message()), never crashes or aborts:
/// an analysis that the backend cannot do (e.g. out of memory, an empty leading block) and a
/// matrix that is not positive definite both return Status::kNumericalFailure.
///
/// Optional capability "Schur factor of a trailing block" (supports_trailing_factor()):
/// analyze(A, trailing) orders the given rows/columns last. Then the trailing m × m block L_tt of
/// the factor L satisfies L_tt L_ttᵀ = S, the Schur complement of A onto those indices, and
/// (A⁻¹)_tt = S⁻¹: a contact problem's Delassus matrix comes from dense algebra on L_tt
/// instead of m sparse solves (docs/theory/state-problem.md §4; the performance budget of
/// docs/architecture.md).
class SpdSolver {
 public:
  using Options = SpdSolverOptions;
  /// The solver for options.backend (never null).
  static std::unique_ptr<SpdSolver> create(const Options& options = {});

  virtual ~SpdSolver() = default;
  SpdSolver() = default;
  SpdSolver(const SpdSolver&) = delete;
  SpdSolver& operator=(const SpdSolver&) = delete;

  /// The backend's name for reports, e.g. "cholmod".
  virtual std::string_view name() const = 0;

  /// Symbolic analysis of A's pattern with the backend's own fill-reducing ordering. Returns
  /// kConverged, or kNumericalFailure with message() saying why.
  [[nodiscard]] virtual Status analyze(const Eigen::SparseMatrix<double>& A) = 0;
  /// Whether analyze(A, trailing) and trailing_factor() are available.
  virtual bool supports_trailing_factor() const { return false; }
  /// Symbolic analysis with `trailing` (distinct indices in [0, n)) ordered last, in the given
  /// order. Throws InvalidInput when the backend does not support it or an index is invalid.
  [[nodiscard]] virtual Status analyze(const Eigen::SparseMatrix<double>& A, const std::vector<int>& trailing);
  /// True after a successful analyze().
  virtual bool analyzed() const = 0;

  /// Numeric factorization of A (same pattern as analyzed). Returns kNumericalFailure (message
  /// names the pivot) when A is not positive definite.
  [[nodiscard]] virtual Status factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// What the last analyze/factorize did ("factorized", or why it failed).
  const std::string& message() const { return message_; }

  /// x = A⁻¹ b after a successful factorize().
  virtual Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const;
  /// X = A⁻¹ B for several right-hand sides (columns), blocked where the backend can.
  virtual Eigen::MatrixXd solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const = 0;

  /// Nonzeros in the factor (a measure of fill and memory); 0 before factorize.
  virtual double factor_nonzeros() const = 0;
  /// Flop count of the numeric factorization from the last analysis (deterministic, unlike times).
  virtual double factor_flops() const = 0;

  /// The dense lower-triangular L_tt (m × m, in the order of `trailing`) of the last
  /// factorization; requires analyze(A, trailing) on a backend that supports it.
  virtual Eigen::MatrixXd trailing_factor() const;
  /// Number of trailing indices (0 without a trailing block).
  virtual Eigen::Index trailing_size() const { return 0; }

 protected:
  std::string message_ = "not factorized";
};

}  // namespace frictopt::linalg
