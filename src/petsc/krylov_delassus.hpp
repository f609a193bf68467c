// SPDX-License-Identifier: MIT
// The Delassus matrix M = G A⁻¹ Gᵀ applied by Krylov solves with the distributed stiffness
// (private to the petsc module): what the sensitivity module reads (blocks of M,
// docs/theory/sensitivity.md §5) when the state came from the PETSc engine. Each column is one
// preconditioned CG solve with A = K restricted to the free DOFs; blocks are formed column by
// column.
#pragma once

#include <functional>

#include "frictopt/contact/delassus.hpp"

namespace frictopt::petsc::detail {

/// `solve` maps a free-DOF right-hand side to A⁻¹ of it (collective: every rank calls the
/// operator with the same arguments, as the replicated sensitivity does). Lifetime: the solver
/// behind `solve` and `boundary` must outlive this operator; valid until the next state solve.
class KrylovDelassus final : public contact::DelassusMatrix {
 public:
  using FreeSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
  KrylovDelassus(FreeSolve solve, const contact::ContactBoundary& boundary);
  Eigen::Index size() const override { return boundary_.num_unknowns(); }
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y) const override;
  /// Exact diagonal: dim·p solves, computed on the first call and cached.
  Eigen::VectorXd diagonal() const override;
  /// One Krylov solve per column.
  Eigen::MatrixXd block(const std::vector<Eigen::Index>& rows, const std::vector<Eigen::Index>& cols) const override;
  const char* kind() const override { return "krylov"; }

 private:
  Eigen::VectorXd column(Eigen::Index k) const;
  FreeSolve solve_;
  const contact::ContactBoundary& boundary_;
  mutable Eigen::VectorXd diagonal_;
};

}  // namespace frictopt::petsc::detail
