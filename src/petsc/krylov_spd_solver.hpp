// SPDX-License-Identifier: MIT
// linalg::SpdSolver served by the PETSc engine's Krylov solves with the stiffness (private to
// the petsc module): installed in fem::LinearElasticity when engine = "petsc", so that the
// sensitivity module's solves A⁻¹b (the adjoint, docs/theory/sensitivity.md §6) run in the same
// engine as the state, without a CHOLMOD factorization.
#pragma once

#include <functional>

#include "frictopt/linalg/spd_solver.hpp"

namespace frictopt::petsc::detail {

/// analyze/factorize are no-ops (the engine assembles its own distributed matrix at each state
/// solve); solves are valid for the design of the last state solve. Collective: every rank calls
/// solve with the same right-hand side.
class KrylovSpdSolver final : public linalg::SpdSolver {
 public:
  using FreeSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
  explicit KrylovSpdSolver(FreeSolve solve) : solve_(std::move(solve)) { message_ = "Krylov solves (PETSc engine)"; }
  std::string_view name() const override { return "petsc-krylov"; }
  [[nodiscard]] Status analyze(const Eigen::SparseMatrix<double>&) override { return Status::kConverged; }
  bool analyzed() const override { return true; }
  [[nodiscard]] Status factorize(const Eigen::SparseMatrix<double>&) override { return Status::kConverged; }
  Eigen::VectorXd solve(const Eigen::Ref<const Eigen::VectorXd>& b) const override { return solve_(b); }
  Eigen::MatrixXd solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const override {
    Eigen::MatrixXd X(B.rows(), B.cols());
    for (Eigen::Index j = 0; j < B.cols(); ++j) X.col(j) = solve_(B.col(j));
    return X;
  }
  double factor_nonzeros() const override { return 0.0; }
  double factor_flops() const override { return 0.0; }

 private:
  FreeSolve solve_;
};

}  // namespace frictopt::petsc::detail
