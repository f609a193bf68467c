// SPDX-License-Identifier: MIT
// The load cases of a study at one design (docs/theory/load-cases.md): the K
// cases' loads as StepLoads for ElasticBody::solve_step — so that one factorization of A(α) and one
// Delassus operator serve every case (the stiffness does not depend on the load) — the part of a
// case's sensitivity the body's own load does not give, and the combination Θ of the cases' costs.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/load_case_definition.hpp"

namespace frictopt::study {

/// Θ of the cases' costs and the case it selects.
struct CombinedValue {
  double value = kNaN;  ///< max_k w_k J_k or Σ_k w_k J_k
  /// "worst": the first case (lowest index) with w_k J_k = Θ exactly — its subgradient is the
  /// one the oracle returns; "weighted": the first case with the largest w_k J_k (for reports).
  int selected = -1;
};

/// Lifetime: `body` must outlive this object. Not thread-safe (as the body).
class LoadCases {
 public:
  /// Validates `definition` against the body's [[load]], [[dirichlet]] and [[force]] tables
  /// (throws InvalidInput naming "load_case[k].field"); the body must have a contact definition.
  LoadCases(const ElasticBody& body, LoadCasesDefinition definition);

  const LoadCasesDefinition& definition() const { return definition_; }
  int size() const { return static_cast<int>(definition_.cases.size()); }
  const LoadCaseDefinition& operator[](int k) const { return definition_.cases[static_cast<std::size_t>(k)]; }

  /// −∇_α[ψᵀ(l_k(α) − l(α))] for a full adjoint ψ (zero at prescribed DOFs): the shape derivative
  /// of case k's traction change. The adjoint of the body (sensitivity::AdjointSensitivity)
  /// differentiates the residual A(α)u − l(α) with the case file's tractions l; case k's residual
  /// has l_k = Σ_j s_kj l_j instead, and a traction on a face the design moves changes with α.
  /// (Prescribed displacements enter through the full u, point forces do not depend on α.)
  [[nodiscard]] Eigen::VectorXd load_change_shape_derivative(int k, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                             const Eigen::Ref<const Eigen::VectorXd>& psi) const;

  /// Θ from the cases' cost values J_k (unweighted, in the cases' order).
  [[nodiscard]] CombinedValue combine(std::span<const double> values) const;

 private:
  const ElasticBody& body_;
  LoadCasesDefinition definition_;
};

}  // namespace frictopt::study
