// SPDX-License-Identifier: MIT
// One body on a fixed mesh: solves the elasticity state for any design α, reusing the mesh,
// the sparsity pattern and the symbolic factorization across designs.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>

#include "frictopt/contact/contact_boundary.hpp"
#include "frictopt/contact/contact_resultants.hpp"
#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/floating_coulomb_solver.hpp"
#include "frictopt/core/status.hpp"
#include "frictopt/fem/linear_elasticity.hpp"
#include "frictopt/fem/loading_plate.hpp"
#include "frictopt/fem/stress_recovery.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/shape/admissible_set.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/orientation_design.hpp"
#include "frictopt/study/state_engine.hpp"

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
  /// Total forces, areas, stick zone (docs/experiments.md §1), from `state` and the tributary
  /// areas.
  contact::ContactResultants resultants;
  bool dense_delassus = false;       ///< used: dense M (true) or the Schur-factor operator
  /// M = G A⁻¹ Gᵀ at this design (dense or from the Schur factor), reused by the sensitivity.
  std::shared_ptr<const contact::DelassusMatrix> delassus;
  /// The dense M when dense_delassus (else null).
  std::shared_ptr<const Eigen::MatrixXd> delassus_matrix;
  /// A floating body (ElasticBody::num_floating_modes() > 0): the augmented-Lagrangian report
  /// (docs/experiments.md §5); `summary` is then its last inner Coulomb solve.
  std::optional<contact::FloatingCoulombSolver::Summary> floating;
  /// β: the rigid motion R β added to A⁺(l + Gᵀz) (empty for a held body).
  Eigen::VectorXd rigid_motion;
  /// The friction law this state was solved with: the definition's, turned to the design's
  /// orientation with [design] friction_orientation, W = {0} on a frictionless program step.
  /// The index sets, pieces, subgradients and the certificate read it from here.
  std::shared_ptr<const contact::FrictionLaw> law;
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
  /// One reading per loading plate of the definition (its translation and the total force it
  /// applies; fem::read_plate), in the definition's order; empty without plates.
  std::vector<fem::PlateReading> plates;
  StateSummary summary;
};

/// The loads of one step of a loading program (study/loading_program.hpp) in place of the
/// definition's: the step's free-DOF load, its prescribed values, and the slip reference of
/// incremental Coulomb friction (docs/theory/loading-program.md §2).
struct StepLoads {
  /// The difference l^k − l(α) of the step's free-DOF load (tractions, nodal forces and the
  /// lifting −A_fd u_d^k of its prescribed displacements) from the definition's load.
  Eigen::VectorXd load_change;
  /// The difference u_d^k − u_d of the prescribed values (full DOF vector, zero at free DOFs).
  Eigen::VectorXd prescribed_change;
  /// u_t^{k−1} of the contact nodes ((dim−1)·p, node-interleaved): friction acts on u_t − u_t^{k−1}.
  Eigen::VectorXd previous_tangential;
  bool friction = true;  ///< false: this step is frictionless (W = {0})
  /// The change of the applied forces (tractions + point forces) as a full DOF vector, for the
  /// equilibrium of a floating body (empty: none).
  Eigen::VectorXd applied_change;
};

/// Lifetime: holds the mesh and the FE problem; not thread-safe (the factorization is reused).
class ElasticBody {
 public:
  /// Validates the definition (throws InvalidInput naming the field); builds mesh, pattern and
  /// the state engine of definition.engine (make_state_engine).
  explicit ElasticBody(BodyDefinition definition);
  ~ElasticBody();
  ElasticBody(const ElasticBody&) = delete;
  ElasticBody& operator=(const ElasticBody&) = delete;

  /// The user's input, as given (a solved state records the law it was solved with).
  const BodyDefinition& definition() const { return definition_; }
  /// The body's mesh (from the structured grid of the definition's shape, height and resolution).
  const mesh::Mesh& mesh() const { return *mesh_; }
  /// The name of the mesh's boundary set that is the contact surface Γ_c.
  const std::string& contact_surface() const { return definition_.contact_surface; }
  const fem::LinearElasticity& elasticity() const { return *fem_; }
  /// Υ over the optimizer's variable x: α, and with [design] friction_orientation x = (α, s)
  /// with the bound on s (study/orientation_design.hpp).
  const shape::LinearConstraints& admissible_set() const { return admissible_; }
  /// The size of x: the shape's control points, + 1 with friction_orientation.
  int num_design_variables() const;
  /// x⁰: α⁰, or (α⁰, k φ⁰) with friction_orientation.
  Eigen::VectorXd initial_design() const;
  /// The orientation as a design variable (null without friction_orientation).
  const OrientationDesign* orientation_design() const {
    return orientation_design_ ? &*orientation_design_ : nullptr;
  }
  /// The number r of rigid-body modes the Dirichlet conditions leave free (0: a held body). A
  /// floating body (r > 0, only with contact) is solved with the kernel-aware dual
  /// (docs/experiments.md §5).
  int num_floating_modes() const { return static_cast<int>(fixing_dofs_.size()); }
  /// The DOFs held at 0 to factorize the floating body's stiffness (its generalized inverse).
  const std::vector<int>& fixing_dofs() const { return fixing_dofs_; }
  /// The contact nodes (null without a foundation).
  const contact::ContactBoundary* contact_boundary() const { return boundary_.get(); }

  /// Solves the state problem at design α — or at x = (α, s) with friction_orientation, with the
  /// law turned to φ = s/k (recorded in the state; its `alpha` is then α) — by the body's
  /// engine: elasticity, and with a foundation the Coulomb contact problem, warm-started from
  /// the last solve (the direct engine: dual QP fixed point, docs/theory/state-problem.md §6).
  /// Throws InvalidInput when α has the wrong size or inverts an element (naming
  /// `design_label`); a failed factorization or contact solve is a status.
  [[nodiscard]] BodyState solve(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                const std::string& design_label = "design");
  /// One step of a loading program: as solve(), with the step's loads. When α is the design of
  /// the last step solve, the assembled A(α), its factorization and the Delassus operator are
  /// reused (the stiffness does not change between steps): only the contact right-hand side does.
  [[nodiscard]] BodyState solve_step(const Eigen::Ref<const Eigen::VectorXd>& alpha, const StepLoads& step,
                                     const std::string& design_label = "design");

  /// The contact state the next solve starts from (the last converged one; only its z is
  /// read). A run's checkpoint stores it so that a resumed run repeats the uninterrupted one
  /// bit for bit (io::RunCheckpoint).
  const std::optional<contact::ContactState>& warm_start() const { return warm_start_; }

  /// The engine that solves the states (study/state_engine.hpp): subgradients and the
  /// operators of the last solved design are asked from it.
  StateEngine& engine() { return *engine_; }
  const StateEngine& engine() const { return *engine_; }
  void set_warm_start(std::optional<contact::ContactState> state) { warm_start_ = std::move(state); }

  /// A kernel for the shape derivative of the case file's [[load]] j alone: a LinearElasticity
  /// on the body's mesh whose only traction is load j (no Dirichlet data, never factorized; only
  /// traction_load and shape_derivative are used). Built on first use and kept by the body, so
  /// that every load case and loading-program step that scales load j shares one (a kernel holds
  /// the mesh's element pattern: about 1.75 kB per unknown).
  const fem::LinearElasticity& traction_kernel(std::size_t j) const;
  /// How many traction kernels have been built so far (for tests and memory reports).
  int num_traction_kernels() const;

 private:
  BodyDefinition definition_;
  std::unique_ptr<const mesh::Mesh> mesh_;  // heap: fem_ and boundary_ keep references to it
  std::unique_ptr<fem::LinearElasticity> fem_;
  shape::LinearConstraints admissible_;
  std::optional<OrientationDesign> orientation_design_;
  // The design x split into α and the law to solve with (x's φ turns it with friction_orientation).
  Eigen::VectorXd shape_design(const Eigen::Ref<const Eigen::VectorXd>& x,
                               std::shared_ptr<const contact::FrictionLaw>& law) const;
  std::unique_ptr<contact::ContactBoundary> boundary_;
  std::optional<contact::ContactState> warm_start_;  // last converged contact state
  // The definition's law and W = {0} (a frictionless program step), shared by the states.
  std::shared_ptr<const contact::FrictionLaw> law_, frictionless_;
  std::vector<int> fixing_dofs_;            // floating body: DOFs held at 0 so that A⁺ is a generalized inverse
  std::unique_ptr<StateEngine> engine_;     // after mesh_, fem_, boundary_: it refers to them
  BodyState solve_impl(const Eigen::Ref<const Eigen::VectorXd>& x, const std::string& design_label,
                       const StepLoads* step);
  // traction_kernel(j), null until first needed (a cache: the body stays logically const).
  mutable std::vector<std::unique_ptr<fem::LinearElasticity>> traction_kernels_;
};

}  // namespace frictopt::study
