// SPDX-License-Identifier: MIT
// The Delassus operator M = G A⁻¹ Gᵀ of the dual contact QP (spec 02, §7 and §9.2), applied
// through the sparse factorization of A, or assembled densely for small contact sets.
#pragma once

#include <Eigen/Core>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/linear_operator.hpp"
#include "frictopt/fem/sparse_cholesky.hpp"

namespace frictopt::contact {

/// y = G A⁻¹ Gᵀ x with one sparse forward/back substitution per application.
/// Lifetime: `cholesky` (factorized) and `boundary` must outlive this operator.
class FactorizedDelassus final : public LinearOperator {
 public:
  FactorizedDelassus(const fem::SparseCholesky& cholesky, const ContactBoundary& boundary);
  Eigen::Index size() const override { return boundary_.num_unknowns(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override;
  /// Exact diagonal: costs dim·p solves (blocked); computed on the first call and cached.
  Eigen::VectorXd diagonal() const override;

 private:
  const fem::SparseCholesky& cholesky_;
  const ContactBoundary& boundary_;
  mutable Eigen::VectorXd diagonal_;
};

/// The dense M = G A⁻¹ Gᵀ (dim·p square), by solves with blocks of `block_columns` right-hand
/// sides (BLAS-3 in CHOLMOD's supernodal solve). Symmetrized to remove round-off asymmetry.
Eigen::MatrixXd dense_delassus(const fem::SparseCholesky& cholesky, const ContactBoundary& boundary,
                               int block_columns = 256);

}  // namespace frictopt::contact
