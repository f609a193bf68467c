// SPDX-License-Identifier: MIT
// The Delassus operator M = G A⁻¹ Gᵀ of the dual contact QP (docs/theory/state-problem.md §5):
// applied to vectors by the QP solvers, and read block by block by the sensitivity analysis.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/linalg/spd_solver.hpp"

namespace frictopt::contact {

/// M as an operator that can also return dense blocks M[rows, cols] (the adjoint needs the
/// block of the nodes in contact only, docs/theory/sensitivity.md §6).
class DelassusMatrix : public linalg::LinearOperator {
 public:
  virtual Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const = 0;
  /// The principal block M[idx, idx] (distinct indices, in the given order), for the working-set
  /// Coulomb solver. Default: block(idx, idx); SchurDelassus computes and caches it.
  virtual Eigen::MatrixXd principal_block(const std::vector<Eigen::Index>& idx) const { return block(idx, idx); }
  /// Frees what principal_block kept only to grow the block later (SchurDelassus: the columns
  /// L⁻¹E_idx); no-op by default.
  virtual void release_block_columns() const {}
  /// Short name for reports: "dense", "schur", "factorized".
  virtual const char* kind() const = 0;
};

/// M stored densely. The matrix is shared (not copied) with whoever else needs the dense M, e.g.
/// study::ContactResult::delassus_matrix: at m = 5,000 contact unknowns it is 200 MB.
class DenseDelassus final : public DelassusMatrix {
 public:
  explicit DenseDelassus(Eigen::MatrixXd matrix)
      : DenseDelassus(std::make_shared<const Eigen::MatrixXd>(std::move(matrix))) {}
  explicit DenseDelassus(std::shared_ptr<const Eigen::MatrixXd> matrix);
  Eigen::Index size() const override { return matrix_->rows(); }
  /// y = M x: from m = 2,000 by dsymv (lower triangle; OpenBLAS, threaded), 3.4× faster than the
  /// two triangular solves of SchurDelassus at m = 5,043 (docs/benchmarks.md); below, Eigen's
  /// single-threaded product (small products do not pay for threads on a shared machine).
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override;
  Eigen::VectorXd diagonal() const override { return matrix_->diagonal(); }
  Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const override;
  const char* kind() const override { return "dense"; }
  const Eigen::MatrixXd& matrix() const { return *matrix_; }
  const std::shared_ptr<const Eigen::MatrixXd>& shared_matrix() const { return matrix_; }

 private:
  std::shared_ptr<const Eigen::MatrixXd> matrix_;
};

/// M = D S⁻¹ D from the Cholesky factor L of the contact Schur complement S = L Lᵀ (the
/// trailing block of a factorization that ordered the contact DOFs last, in z order;
/// linalg::SpdSolver::trailing_factor) and the signs D = diag(±1) of G (−1 tangential,
/// +1 normal). An apply is two dense triangular solves (2m² flops), a block of k columns one
/// triangular solve with k right-hand sides: no sparse solve and no m³ work.
class SchurDelassus final : public DelassusMatrix {
 public:
  SchurDelassus(Eigen::MatrixXd schur_factor, int dim);
  Eigen::Index size() const override { return L_.rows(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override;
  /// diag(M)_k = ‖L⁻¹ e_k‖²: one triangular solve with m right-hand sides (computed once, cached).
  Eigen::VectorXd diagonal() const override;
  Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const override;
  const char* kind() const override { return "schur"; }
  /// The dense M = D (L Lᵀ)⁻¹ D by LAPACK dpotri (m² memory, 2m³/3 flops: 2.7 s at m = 5,043).
  Eigen::MatrixXd dense() const;

  /// The principal block M[idx, idx] (idx: distinct indices, any order; the block is in that
  /// order). M[r, c] = D_r (L⁻¹e_r)ᵀ(L⁻¹e_c) D_c, so the block is XᵀX with X = L⁻¹E_idx. Column
  /// k of L⁻¹E is zero above row k, so the columns are solved in groups sorted by index, each
  /// group with the trailing triangle of L below its first index only (BLAS-3 dtrsm), then one
  /// dsyrk. The columns X are kept: a later call with more indices solves only the new ones,
  /// and block() answers requests inside the cached indices from the cached block (the
  /// adjoint's block of the nodes in contact is then free). release_block_columns() frees X
  /// ((m − first index)·|idx| doubles: 0.5 GB for 3,000 columns at m = 20,000) and keeps the
  /// block (a later request outside it then starts the cache over); release_block_cache()
  /// frees both.
  Eigen::MatrixXd principal_block(const std::vector<Eigen::Index>& idx) const override;
  void release_block_columns() const override;
  void release_block_cache() const;
  /// Indices whose columns are cached (in cache order).
  const std::vector<Eigen::Index>& cached_indices() const { return cache_.indices; }

 private:
  /// X = L⁻¹E for `indices` (rows from `first_row` on: the rows above are zero) and
  /// block = D XᵀX D, both in the order of `indices`.
  struct BlockCache {
    std::vector<Eigen::Index> indices;
    std::vector<Eigen::Index> position;  ///< position[k] in indices, or −1 (size m once used)
    Eigen::Index first_row = 0;
    Eigen::MatrixXd columns;
    Eigen::MatrixXd block;
  };
  void extend_cache(const std::vector<Eigen::Index>& fresh) const;
  bool cached(const std::vector<Eigen::Index>& idx) const;

  Eigen::MatrixXd L_;
  Eigen::VectorXd signs_;
  mutable Eigen::VectorXd diagonal_;
  mutable BlockCache cache_;
};

/// y = G A⁻¹ Gᵀ x with one sparse forward/back substitution per application (no extra memory).
/// Lifetime: `solver` (factorized) and `boundary` must outlive this operator.
class FactorizedDelassus final : public DelassusMatrix {
 public:
  FactorizedDelassus(const linalg::SpdSolver& solver, const ContactBoundary& boundary);
  Eigen::Index size() const override { return boundary_.num_unknowns(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override;
  /// Exact diagonal: costs dim·p solves (blocked); computed on the first call and cached.
  Eigen::VectorXd diagonal() const override;
  /// One sparse solve per column.
  Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const override;
  const char* kind() const override { return "factorized"; }

 private:
  const linalg::SpdSolver& solver_;
  const ContactBoundary& boundary_;
  mutable Eigen::VectorXd diagonal_;
};

/// The dense M of a tilted foundation from the standard one: with G = 𝓕 E (E the standard
/// foundation's ±unit rows D on the node DOFs, 𝓕 = diag(F D) per node, F the frame rows of
/// ContactBoundary::frame_rows), M = 𝓕 M_std 𝓕ᵀ blockwise (Q M_ij Qᵀ, Q = F D): m²·2·dim flops,
/// so a tilted foundation keeps the Schur factor's dense route. Symmetrized. Throws
/// InvalidInput when the sizes do not match.
Eigen::MatrixXd turn_delassus(const Eigen::MatrixXd& standard, const Eigen::MatrixXd& frame_rows);

/// The dense M = G A⁻¹ Gᵀ (dim·p square), by solves with blocks of `block_columns` right-hand
/// sides (BLAS-3 in a supernodal backend's solve). Symmetrized to remove round-off asymmetry.
Eigen::MatrixXd dense_delassus(const linalg::SpdSolver& solver, const ContactBoundary& boundary,
                               int block_columns = 256);

}  // namespace frictopt::contact
