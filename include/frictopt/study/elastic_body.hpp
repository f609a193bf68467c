// SPDX-License-Identifier: MIT
// One body on a fixed mesh: solves the elasticity state for any design α, reusing the mesh,
// the sparsity pattern and the symbolic factorization across designs.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/fem/stress_recovery.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// Outcome of one state solve.
struct StateSummary {
  Status status = Status::kNotRun;
  std::string message = "solve() has not been called";
  double relative_residual = kNaN;    ///< ‖A u_f − l_f‖ / ‖l_f‖ on the free DOFs
  double assembly_seconds = 0.0;
  double factorization_seconds = 0.0;  ///< numeric (and on the first call symbolic) factorization
  double solve_seconds = 0.0;
  std::string brief_report() const;
};

/// The contact part of a state: dual variables per contact node, gaps, the solver's report.
struct ContactResult {
  contact::ContactState state;       ///< z = (q, λ) per node, u_t and u_ν + g, node statuses
  Eigen::VectorXd gaps;              ///< initial gaps g = B̃α at the contact nodes [m]
  contact::CoulombSolver::Summary summary;
  bool dense_delassus = false;       ///< used: dense M (true) or the Schur-factor operator
  /// M = G A⁻¹ Gᵀ at this design (dense or from the Schur factor), reused by the sensitivity.
  std::shared_ptr<const contact::DelassusMatrix> delassus;
  /// The dense M when dense_delassus (else null).
  std::shared_ptr<const Eigen::MatrixXd> delassus_matrix;
};

/// The state of the body at one design.
struct BodyState {
  Eigen::VectorXd alpha;         ///< the design
  Eigen::MatrixXd positions;     ///< X(α), num_nodes × dim [m]
  Eigen::VectorXd displacement;  ///< full u, num_dofs, node-major [m]
  fem::StressField stress;
  double strain_energy = kNaN;   ///< ½ uᵀAu [J] (2D: per metre of thickness)
  double external_work = kNaN;   ///< lᵀu [J]
  double volume = kNaN;          ///< meas Ω(α) of the mesh [m³ or m²]
  /// The smallest scaled Jacobian of the cells at X(α) (mesh::Mesh::min_scaled_jacobian): 1 for
  /// boxes, → 0 as a trial design distorts the cells (an inverted one is refused before).
  double min_scaled_jacobian = kNaN;
  std::optional<ContactResult> contact;  ///< present when the body has a foundation
  StateSummary summary;
};

/// Lifetime: holds the mesh and the FE problem; not thread-safe (the factorization is reused).
class ElasticBody {
 public:
  /// Validates the definition (throws InvalidInput naming the field); builds mesh and pattern.
  explicit ElasticBody(BodyDefinition definition);

  const BodyDefinition& definition() const { return definition_; }
  /// The body's mesh (from the structured grid of the definition's shape, height and resolution).
  const mesh::Mesh& mesh() const { return *mesh_; }
  /// The name of the mesh's boundary set that is the contact surface Γ_c.
  const std::string& contact_surface() const { return definition_.contact_surface; }
  const fem::LinearElasticity& elasticity() const { return *fem_; }
  const shape::LinearConstraints& admissible_set() const { return admissible_; }
  /// The contact nodes (null without a foundation).
  const contact::ContactBoundary* contact_boundary() const { return boundary_.get(); }

  /// Solves the state problem at design α: elasticity, and with a foundation the Coulomb
  /// contact problem (dual QP fixed point, spec 02 §9.3) warm-started from the last solve.
  /// Throws InvalidInput when α has the wrong size or inverts an element (naming
  /// `design_label`); a failed factorization or contact solve is a status.
  [[nodiscard]] BodyState solve(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                const std::string& design_label = "design");

  /// The contact state the next solve starts from (the last converged one; only its z is
  /// read). A run's checkpoint stores it so that a resumed run repeats the uninterrupted one
  /// bit for bit (io::RunCheckpoint).
  const std::optional<contact::ContactState>& warm_start() const { return warm_start_; }
  void set_warm_start(std::optional<contact::ContactState> state) { warm_start_ = std::move(state); }

 private:
  BodyDefinition definition_;
  std::unique_ptr<const mesh::Mesh> mesh_;  // heap: fem_ and boundary_ keep references to it
  std::unique_ptr<fem::LinearElasticity> fem_;
  shape::LinearConstraints admissible_;
  std::unique_ptr<contact::ContactBoundary> boundary_;
  std::optional<contact::ContactState> warm_start_;  // last converged contact state
};

}  // namespace frictopt::study
