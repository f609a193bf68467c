// SPDX-License-Identifier: MIT
// The CHOLMOD backend of SpdSolver (private: no cholmod type leaves src/linalg).
#pragma once

#include <memory>

#include "frictopt/linalg/spd_solver.hpp"

namespace frictopt::linalg {

/// Sparse Cholesky P A Pᵀ = L Lᵀ by CHOLMOD (supernodal), with the trailing-block capability.
/// CHOLMOD is called directly (not through Eigen's CholmodSupernodalLLT) because the trailing
/// block needs a user ordering (cholmod_analyze_p) and access to the supernodal factor.
class CholmodSolver final : public SpdSolver {
 public:
  CholmodSolver();
  ~CholmodSolver() override;

  std::string_view name() const override { return "cholmod"; }
  [[nodiscard]] Status analyze(const Eigen::SparseMatrix<double>& A) override;
  bool supports_trailing_factor() const override { return true; }
  [[nodiscard]] Status analyze(const Eigen::SparseMatrix<double>& A, const std::vector<int>& trailing) override;
  bool analyzed() const override;
  [[nodiscard]] Status factorize(const Eigen::SparseMatrix<double>& A) override;
  Eigen::MatrixXd solve_many(const Eigen::Ref<const Eigen::MatrixXd>& B) const override;
  double factor_nonzeros() const override;
  double factor_flops() const override;
  Eigen::MatrixXd trailing_factor() const override;
  Eigen::Index trailing_size() const override;

 private:
  Status analysis_failed(const char* what);
  Status no_unknowns();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace frictopt::linalg
