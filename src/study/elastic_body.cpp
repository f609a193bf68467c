// SPDX-License-Identifier: MIT
#include "frictopt/study/elastic_body.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "frictopt/core/error.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/study/floating_body.hpp"
#include "frictopt/study/state_engine_factory.hpp"

namespace frictopt::study {

std::string StateSummary::brief_report() const {
  return fmt::format("elasticity: {} ({}); relative residual {:.2e}; assembly {:.3f} s, factorization {:.3f} s, solve {:.3f} s",
                     to_string(status), message, relative_residual, assembly_seconds, factorization_seconds,
                     solve_seconds);
}

ElasticBody::ElasticBody(BodyDefinition definition) : definition_(std::move(definition)) {
  if (definition_.dirichlet.empty() && definition_.constraints.empty() && !definition_.contact)
    throw InvalidInput(
        "dirichlet: no Dirichlet condition; expected at least one face with prescribed displacement "
        "(otherwise rigid-body motions are free and the stiffness matrix is singular)");
  mesh_ = std::make_unique<const mesh::Mesh>(build_mesh(definition_));
  traction_kernels_.resize(definition_.tractions.size());  // each built on first use
  fem::PrescribedDofs prescribed = fem::expand_dirichlet(*mesh_, definition_.dirichlet);
  fem::add_nodal_constraints(*mesh_, definition_.constraints, prescribed);
  // Loading plates (docs/theory/loading-plate.md): held directions are prescribed zeros, each
  // force-driven direction ties the plate's nodes to one unknown.
  fem::validate_plates(*mesh_, definition_.plates, prescribed,
                       definition_.contact ? definition_.contact_surface : std::string());
  fem::add_plate_held_dofs(*mesh_, definition_.plates, prescribed);
  const std::vector<std::vector<int>> ties = fem::plate_ties(*mesh_, definition_.plates);
  const std::vector<int> prescribed_by_user = prescribed.dofs;
  const fem::DofMap user_dofs(mesh_->num_dofs(), prescribed, ties);
  // A floating body (docs/experiments.md §5): rigid modes the Dirichlet conditions leave free are
  // held by contact and friction only. Hold r DOFs off Γ_c at 0 so that the factorized block is SPD
  // (its inverse is a generalized inverse A⁺); the modes come back as Rβ in solve().
  const Eigen::MatrixXd modes = free_rigid_modes(mesh_->reference_positions(), prescribed_by_user, ties);
  if (modes.cols() > 0) {
    if (!definition_.contact)
      throw InvalidInput(fmt::format(
          "dirichlet: the Dirichlet conditions leave {} rigid-body mode{} free and the body has no contact to hold "
          "them; expected conditions that hold the body (the stiffness matrix would be singular)",
          modes.cols(), modes.cols() == 1 ? "" : "s"));
    // A fixing DOF is neither prescribed nor tied (a plate's unknown stays an unknown).
    std::vector<int> not_candidates = prescribed_by_user;
    for (const auto& group : ties) not_candidates.insert(not_candidates.end(), group.begin(), group.end());
    fixing_dofs_ = study::fixing_dofs(modes, not_candidates,
                               mesh_->boundary(definition_.contact_surface).nodes, mesh_->dim());
    for (int d : fixing_dofs_) prescribed.dofs.push_back(d), prescribed.values.push_back(0.0);
  }
  fem_ = std::make_unique<fem::LinearElasticity>(*mesh_, definition_.material, prescribed, definition_.tractions,
                                                 definition_.linear_solver, ties);
  if (modes.cols() > 0) fem_->set_free_modes(modes, modes_are_translations(modes, mesh_->dim()));
  admissible_ = shape::make_admissible_set(definition_.shape, definition_.admissible);
  if (definition_.friction_orientation) {
    // Orientation as a design (docs/theory/friction-design.md): x = (α, s), Υ gets the bound on s
    // (study/orientation_design.hpp).
    if (!definition_.contact)
      throw InvalidInput("design.friction_orientation = true needs a [contact] table with an anisotropic 3D law");
    orientation_design_.emplace(*definition_.friction_orientation, definition_.contact->law,
                                definition_.admissible.upper_bound);
    admissible_ = orientation_design_->extend(admissible_);
  }
  EngineSetup setup{*mesh_, *fem_, definition_.material, nullptr, {}, {}, prescribed_by_user, fixing_dofs_};
  if (!definition_.forces.empty() || !definition_.plates.empty()) {
    // Checked against the user's conditions (a force on a fixing DOF is carried by the floating
    // body's equilibrium, not refused). A plate's total force, split over its nodes, reaches its
    // tied unknown whole through Pᵀ (restrict_forces).
    std::vector<fem::NodalForce> forces = definition_.forces;
    for (fem::NodalForce& f : fem::plate_nodal_forces(definition_.plates)) forces.push_back(std::move(f));
    setup.nodal_forces_full = fem::nodal_force_load(*mesh_, user_dofs, forces);
    setup.nodal_forces = fem_->dofs().restrict_forces(setup.nodal_forces_full);
  }
  if (definition_.contact) {
    if (definition_.contact->law.dim() != mesh_->dim())
      throw InvalidInput(fmt::format("contact.friction: a {}D friction law for a {}D body",
                                     definition_.contact->law.dim(), mesh_->dim()));
    definition_.contact->coulomb.validate();
    boundary_ = std::make_unique<contact::ContactBoundary>(*mesh_, fem_->dofs(), definition_.contact_surface,
                                                           definition_.contact->foundation);
    law_ = std::make_shared<const contact::FrictionLaw>(definition_.contact->law);
    frictionless_ = std::make_shared<const contact::FrictionLaw>(contact::frictionless_law(mesh_->dim()));
    setup.boundary = boundary_.get();
  }
  engine_ = make_state_engine(definition_, setup);
}

ElasticBody::~ElasticBody() = default;

BodyState ElasticBody::solve(const Eigen::Ref<const Eigen::VectorXd>& alpha, const std::string& design_label) {
  return solve_impl(alpha, design_label, nullptr);
}

int ElasticBody::num_design_variables() const {
  return definition_.shape.num_controls() + (orientation_design_ ? 1 : 0);
}

Eigen::VectorXd ElasticBody::initial_design() const {
  return orientation_design_ ? orientation_design_->initial_design(definition_.initial_design)
                             : definition_.initial_design;
}

Eigen::VectorXd ElasticBody::shape_design(const Eigen::Ref<const Eigen::VectorXd>& x,
                                          std::shared_ptr<const contact::FrictionLaw>& law) const {
  const Eigen::Index d = definition_.shape.num_controls();
  if (!orientation_design_ || x.size() != d + 1) return x;  // solve_impl checks the size
  // x = (α, s): the law turned to φ = s/k; the state records it (ContactResult::law), which is
  // where the sensitivity and the certificate read it.
  law = std::make_shared<const contact::FrictionLaw>(orientation_design_->law_for_variable(x(d)));
  return x.head(d);
}

const fem::LinearElasticity& ElasticBody::traction_kernel(std::size_t j) const {
  FRICTOPT_ASSERT(j < traction_kernels_.size(), "traction_kernel: a [[load]] of the body");
  if (!traction_kernels_[j])
    traction_kernels_[j] = std::make_unique<fem::LinearElasticity>(
        *mesh_, definition_.material, fem::PrescribedDofs{}, std::vector<fem::FaceTraction>{definition_.tractions[j]},
        definition_.linear_solver);
  return *traction_kernels_[j];
}

int ElasticBody::num_traction_kernels() const {
  return static_cast<int>(std::count_if(traction_kernels_.begin(), traction_kernels_.end(),
                                         [](const auto& k) { return k != nullptr; }));
}

BodyState ElasticBody::solve_step(const Eigen::Ref<const Eigen::VectorXd>& alpha, const StepLoads& step,
                                  const std::string& design_label) {
  const Eigen::Index n_free = fem_->dofs().num_free();
  if (step.load_change.size() != n_free || step.prescribed_change.size() != mesh_->num_dofs() ||
      (boundary_ && step.previous_tangential.size() != (mesh_->dim() - 1) * boundary_->num_nodes()))
    throw InvalidInput(fmt::format("StepLoads: sizes {}, {}, {}; expected {} free DOFs, {} DOFs and {} tangential "
                                   "contact components",
                                   step.load_change.size(), step.prescribed_change.size(),
                                   step.previous_tangential.size(), n_free, mesh_->num_dofs(),
                                   boundary_ ? (mesh_->dim() - 1) * boundary_->num_nodes() : 0));
  return solve_impl(alpha, design_label, &step);
}

BodyState ElasticBody::solve_impl(const Eigen::Ref<const Eigen::VectorXd>& x, const std::string& design_label,
                                  const StepLoads* step) {
  std::shared_ptr<const contact::FrictionLaw> law = law_;
  const Eigen::VectorXd alpha = shape_design(x, law);
  if (alpha.size() != definition_.shape.num_controls())
    throw InvalidInput(fmt::format("{}: has {} control heights; expected {}", design_label, alpha.size(),
                                   definition_.shape.num_controls()));
  BodyState state;
  state.alpha = alpha;
  state.positions = mesh_->positions(alpha);
  mesh_->check_quality(state.positions, design_label);
  state.min_scaled_jacobian = mesh_->min_scaled_jacobian(state.positions);
  state.volume = mesh_->volume(state.positions);
  StateRequest request;
  request.law = step && !step->friction ? frictionless_ : std::move(law);
  request.step = step;
  request.design_label = design_label;
  request.warm_start = &warm_start_;
  engine_->solve(state, request);
  if (!definition_.plates.empty() && state.displacement.size() == mesh_->num_dofs()) {
    const Eigen::VectorXd residual = fem_->residual(state.positions, state.displacement);
    for (const fem::LoadingPlate& plate : definition_.plates)
      state.plates.push_back(fem::read_plate(*mesh_, plate, state.displacement, residual));
  }
  return state;
}

}  // namespace frictopt::study
