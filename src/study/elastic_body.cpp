// SPDX-License-Identifier: MIT
#include "frictopt/study/elastic_body.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/working_set_coulomb.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/structured_mesh.hpp"
#ifdef FRICTOPT_HAVE_PETSC
#include "frictopt/petsc/contact_newton_solver.hpp"
#endif
#include "frictopt/study/floating_body.hpp"
#include "frictopt/study/build_mesh.hpp"

namespace frictopt::study {
namespace {
// From this many contact unknowns the Coulomb problem is solved on a working set of nodes: below,
// a QP product with the whole M costs microseconds and the restriction would not pay.
constexpr Eigen::Index kWorkingSetMinUnknowns = 1000;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

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
  user_prescribed_dofs_ = prescribed.dofs;
  const fem::DofMap user_dofs(mesh_->num_dofs(), prescribed);
  // A floating body (spec 07 §2): rigid modes the Dirichlet conditions leave free are held by
  // contact and friction only. Hold r DOFs off Γ_c at 0 so that the factorized block is SPD
  // (its inverse is a generalized inverse A⁺); the modes come back as Rβ in solve().
  const Eigen::MatrixXd modes = free_rigid_modes(mesh_->reference_positions(), user_prescribed_dofs_);
  if (modes.cols() > 0) {
    if (!definition_.contact)
      throw InvalidInput(fmt::format(
          "dirichlet: the Dirichlet conditions leave {} rigid-body mode{} free and the body has no contact to hold "
          "them; expected conditions that hold the body (the stiffness matrix would be singular)",
          modes.cols(), modes.cols() == 1 ? "" : "s"));
    fixing_dofs_ = study::fixing_dofs(modes, user_prescribed_dofs_,
                               mesh_->boundary(definition_.contact_surface).nodes, mesh_->dim());
    for (int d : fixing_dofs_) prescribed.dofs.push_back(d), prescribed.values.push_back(0.0);
  }
  fem_ = std::make_unique<fem::LinearElasticity>(*mesh_, definition_.material, prescribed, definition_.tractions,
                                                 definition_.linear_solver);
  admissible_ = shape::make_admissible_set(definition_.shape, definition_.admissible);
  if (definition_.friction_orientation) {
    // issue 13 item 3: x = (α, s), Υ gets the bound on s (study/orientation_design.hpp).
    if (!definition_.contact)
      throw InvalidInput("design.friction_orientation = true needs a [contact] table with an anisotropic 3D law");
    if (definition_.engine.kind == StateEngine::kPetsc)
      throw InvalidInput("design.friction_orientation = true: the PETSc engine keeps its law fixed and has no friction "
                         "gradient; expected solver.engine = \"direct\"");
    orientation_design_.emplace(*definition_.friction_orientation, definition_.contact->law,
                                definition_.admissible.upper_bound);
    admissible_ = orientation_design_->extend(admissible_);
  }
  if (definition_.engine.kind == StateEngine::kPetsc && !definition_.contact)
    throw InvalidInput("solver.engine = \"petsc\": the PETSc engine solves contact problems; expected a [contact] table");
  // The PETSc engine (issue 14) solves the static clamped problem; point forces and floating
  // bodies (issue 12) exist in the direct engine only so far.
  if (definition_.engine.kind == StateEngine::kPetsc && (!fixing_dofs_.empty() || !definition_.forces.empty()))
    throw InvalidInput(fmt::format("solver.engine = \"petsc\": {} supported by the direct engine only; expected "
                                   "engine = \"direct\" for this case",
                                   fixing_dofs_.empty() ? "[[force]] tables are" : "a floating body is"));
  if (!definition_.forces.empty()) {
    // Checked against the user's conditions (a force on a fixing DOF is carried by the floating
    // body's equilibrium, not refused).
    nodal_forces_full_ = fem::nodal_force_load(*mesh_, user_dofs, definition_.forces);
    nodal_forces_ = fem_->dofs().restrict(nodal_forces_full_);
  }
  if (definition_.contact) {
    if (definition_.contact->law.dim() != mesh_->dim())
      throw InvalidInput(fmt::format("contact.friction: a {}D friction law for a {}D body",
                                     definition_.contact->law.dim(), mesh_->dim()));
    definition_.contact->coulomb.validate();
    boundary_ = std::make_unique<contact::ContactBoundary>(*mesh_, fem_->dofs(), definition_.contact_surface,
                                                           definition_.contact->foundation);
    if (definition_.engine.kind == StateEngine::kPetsc && !boundary_->standard_foundation())
      throw InvalidInput(
          "foundation: solver.engine = \"petsc\" supports the default foundation only (normal = e_dim, offset = 0, "
          "axis1 = e1); expected engine = \"direct\" for a tilted or offset foundation (docs/petsc-engine.md)");
    if (definition_.engine.kind == StateEngine::kPetsc) {
#ifdef FRICTOPT_HAVE_PETSC
      petsc::ContactNewtonSolver::Options options;
      options.petsc_options = definition_.engine.petsc_options;
      options.relative_tolerance = definition_.engine.relative_tolerance;
      options.max_iterations = definition_.engine.max_iterations;
      options.classification_tolerance = definition_.contact->coulomb.tresca.classification_tolerance;
      petsc_engine_ = std::make_shared<petsc::ContactNewtonSolver>(*fem_, *boundary_, definition_.contact->law, options);
      fem_->set_factorization(petsc_engine_->stiffness_solver());  // the adjoint's solves, by Krylov
      return;  // no factorization: the trailing-DOF ordering below is the direct engine's
#else
      throw InvalidInput(
          "solver.engine = \"petsc\": this frictopt was built without PETSc; expected engine = \"direct\", or a "
          "build with petsc-dev installed (FRICTOPT_WITH_PETSC, docs/petsc-engine.md)");
#endif
    }
    // Contact DOFs last, in z order: the trailing factor gives the Delassus matrix (spec 02 §5).
    // A backend without that capability gets M by solves instead (solve()).
    if (fem_->factorization().supports_trailing_factor()) {
      std::vector<int> trailing;
      for (Eigen::Index i = 0; i < boundary_->num_nodes(); ++i)
        for (int c = 0; c < mesh_->dim(); ++c) trailing.push_back(boundary_->free_dof(i, c));
      fem_->set_trailing_dofs(std::move(trailing));
    }
  }
}

BodyState ElasticBody::solve(const Eigen::Ref<const Eigen::VectorXd>& alpha, const std::string& design_label) {
  step_alpha_.reset();  // a plain solve refactorizes; the next step solve must not trust the cache
  return solve_impl(shape_design(alpha), design_label, nullptr);
}

int ElasticBody::num_design_variables() const {
  return definition_.shape.num_controls() + (orientation_design_ ? 1 : 0);
}

Eigen::VectorXd ElasticBody::initial_design() const {
  return orientation_design_ ? orientation_design_->initial_design(definition_.initial_design)
                             : definition_.initial_design;
}

void ElasticBody::set_friction_law(const contact::FrictionLaw& law) {
  FRICTOPT_ASSERT(definition_.contact && !petsc_engine_ && law.dim() == definition_.contact->law.dim(),
                  "set_friction_law: a body in contact, the direct engine, a law of the body's dimension");
  definition_.contact->law = law;
}

Eigen::VectorXd ElasticBody::shape_design(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::Index d = definition_.shape.num_controls();
  if (!orientation_design_ || x.size() != d + 1) return x;  // solve_impl checks the size
  // x = (α, s): the law turned to φ = s/k for this and every later use of the state (the
  // sensitivity reads definition().contact->law), until the next design turns it again.
  set_friction_law(orientation_design_->law_for_variable(x(d)));
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
  return solve_impl(shape_design(alpha), design_label, &step);
}

BodyState ElasticBody::solve_impl(const Eigen::Ref<const Eigen::VectorXd>& alpha, const std::string& design_label,
                                  const StepLoads* step) {
  if (alpha.size() != definition_.shape.num_controls())
    throw InvalidInput(fmt::format("{}: has {} control heights; expected {}", design_label, alpha.size(),
                                   definition_.shape.num_controls()));
  BodyState state;
  state.alpha = alpha;
  state.positions = mesh_->positions(alpha);
  mesh_->check_quality(state.positions, design_label);
  state.min_scaled_jacobian = mesh_->min_scaled_jacobian(state.positions);
  state.volume = mesh_->volume(state.positions);

  if (petsc_engine_) {
    if (step != nullptr)
      throw InvalidInput(design_label + ": solver.engine = \"petsc\": loading programs are supported by the direct "
                         "engine only; expected engine = \"direct\"");
    return solve_with_petsc(std::move(state));
  }
  // A step at the design of the previous step reuses A(α), its factor and M (spec 07 §1).
  const bool reuse = step != nullptr && step_alpha_ && *step_alpha_ == alpha;
  auto start = std::chrono::steady_clock::now();
  if (!reuse) {
    step_alpha_.reset();
    fem_->assemble(state.positions);
    state.summary.assembly_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const Status status = fem_->factorize();
    state.summary.factorization_seconds = seconds_since(start);
    if (status != Status::kConverged) {
      state.summary.status = status;
      state.summary.message = fem_->factorization().message();
      return state;
    }
  }
  start = std::chrono::steady_clock::now();
  const linalg::SpdSolver& solver = fem_->factorization();
  Eigen::VectorXd rhs = fem_->load();
  if (nodal_forces_.size()) rhs += nodal_forces_;
  if (step) rhs += step->load_change;
  Eigen::VectorXd u_free = solver.solve(rhs);  // the free body's response A⁻¹l
  if (boundary_) {
    // Dual contact QP (spec 02, §7/§9.2): min ½zᵀMz + zᵀc with c = G A⁻¹ l + (0, g).
    ContactResult result;
    result.gaps = boundary_->gaps(state.positions);
    const int dim = mesh_->dim();
    Eigen::VectorXd c = boundary_->times(u_free);
    for (Eigen::Index i = 0; i < boundary_->num_nodes(); ++i) c(dim * i + dim - 1) += result.gaps(i);
    // The lifting of prescribed values enters c through A⁻¹l; their own motion at contact nodes
    // is zero (contact nodes have only free DOFs), so c needs no other Dirichlet term.
    if (step) c = contact::shift_by_previous_slip(c, step->previous_tangential, dim);
    const ContactDefinition& cd = *definition_.contact;
    result.dense_delassus = boundary_->num_unknowns() <= cd.dense_delassus_max_unknowns;
    if (reuse) {
      result.delassus = step_delassus_;
      result.delassus_matrix = step_delassus_matrix_;
    } else if (solver.trailing_size() > 0 && (boundary_->standard_foundation() || result.dense_delassus)) {
      // The Schur factor gives M = D S⁻¹ D with D the signs of the standard foundation's ±unit
      // rows of G; a tilted foundation's dense M is that turned per node (turn_delassus).
      auto schur = std::make_shared<contact::SchurDelassus>(solver.trailing_factor(), dim);
      if (result.dense_delassus) {
        // One copy of the dense M, shared by the QP operator and readers of delassus_matrix; the
        // Schur factor is released at the end of this scope.
        result.delassus_matrix = std::make_shared<const Eigen::MatrixXd>(
            boundary_->standard_foundation() ? schur->dense()
                                             : contact::turn_delassus(schur->dense(), boundary_->frame_rows()));
        result.delassus = std::make_shared<contact::DenseDelassus>(result.delassus_matrix);
      } else {
        result.delassus = std::move(schur);
      }
    } else if (result.dense_delassus) {
      // A backend without the Schur factor (or no contact unknowns): M column block by block.
      result.delassus_matrix = std::make_shared<const Eigen::MatrixXd>(contact::dense_delassus(solver, *boundary_));
      result.delassus = std::make_shared<contact::DenseDelassus>(result.delassus_matrix);
    } else {
      // Applied through the factorization: valid until the next solve() refactorizes, which is
      // how ShapeOracle uses it (the sensitivity reads M only at the last solved design).
      result.delassus = std::make_shared<contact::FactorizedDelassus>(solver, *boundary_);
    }
    if (step) {
      step_alpha_ = Eigen::VectorXd(alpha);
      step_delassus_ = result.delassus;
      step_delassus_matrix_ = result.delassus_matrix;
    }
    const linalg::LinearOperator* delassus = result.delassus.get();
    result.state = warm_start_ && warm_start_->z.size() == boundary_->num_unknowns()
                       ? *warm_start_
                       : contact::ContactState(dim, boundary_->num_nodes());
    const bool frictionless = step && !step->friction;
    const contact::FrictionLaw& law = frictionless ? contact::frictionless_law(dim) : cd.law;
    Eigen::MatrixXd modes;
    if (fixing_dofs_.empty() && boundary_->num_unknowns() >= kWorkingSetMinUnknowns) {
      // The Coulomb problem on the nodes that can touch (docs/contact.md, "Large contact surfaces").
      result.summary =
          contact::WorkingSetCoulombSolver(*result.delassus, law, cd.coulomb).solve(c, result.state).coulomb;
    } else if (fixing_dofs_.empty()) {
      const contact::CoulombSolver coulomb(*delassus, law, cd.coulomb);
      result.summary = coulomb.solve(c, result.state);
    } else {
      // Floating body (spec 07 §2): the contact forces must balance the loads, E z = e with
      // E = (G R)ᵀ and e = −Rᵀ l over every DOF the user does not prescribe, l including the
      // lifting of the prescribed values: l = f − (A u_d − l_traction) = f − residual(u_d).
      modes = free_rigid_modes(state.positions, user_prescribed_dofs_);
      if (modes.cols() != static_cast<Eigen::Index>(fixing_dofs_.size()))
        throw InvalidInput(fmt::format("{}: the body has {} free rigid-body modes at this design but {} at the "
                                       "reference; expected the same",
                                       design_label, modes.cols(), fixing_dofs_.size()));
      Eigen::VectorXd prescribed = fem_->dofs().prescribed_values();
      if (step) prescribed += step->prescribed_change;
      Eigen::VectorXd load = -fem_->residual(state.positions, prescribed);
      if (nodal_forces_full_.size()) load += nodal_forces_full_;
      if (step && step->applied_change.size()) load += step->applied_change;
      for (int d : user_prescribed_dofs_) load(d) = 0.0;  // reactions are not loads
      const Eigen::VectorXd e = -modes.transpose() * load;
      Eigen::MatrixXd E(modes.cols(), boundary_->num_unknowns());
      for (Eigen::Index j = 0; j < modes.cols(); ++j)
        E.row(j) = boundary_->times(fem_->dofs().restrict(modes.col(j))).transpose();
      // A priori: when the net load presses the body (vertical translation free), the friction
      // capacity is known before any iteration: refuse a load beyond it with its excess.
      std::string excess;
      Eigen::VectorXd translation = Eigen::VectorXd::Zero(mesh_->num_dofs());
      Eigen::Vector3d net = Eigen::Vector3d::Zero();
      bool translations_free = true;
      for (int comp = 0; comp < dim; ++comp) {
        translation.setZero();
        for (int a = 0; a < mesh_->num_nodes(); ++a) translation(a * dim + comp) = 1.0;
        net(comp) = translation.dot(load);
        for (int d : user_prescribed_dofs_) translations_free &= d % dim != comp;
      }
      if (translations_free) {
        // Σλ = −F_ν and Σq = F_t (the contact balances the net load).
        // In the foundation's frame: tangential t_k·F, normal n·F.
        const mesh::PlaneFrame& frame = boundary_->foundation().frame;
        const Eigen::VectorXd net_tangential = frame.tangents.transpose() * net.head(dim);
        excess = friction_capacity_excess(
            law, dim == 3 ? Eigen::Vector2d(net_tangential(0), net_tangential(1)) : Eigen::Vector2d(net_tangential(0), 0.0),
            -frame.normal.dot(net.head(dim)), dim);
      }
      contact::FloatingCoulombSolver::Options fo;
      fo.coulomb = cd.coulomb;
      const contact::FloatingCoulombSolver floating(*delassus, E, law, fo);
      contact::FloatingCoulombSolver::Summary fs;
      if (!excess.empty()) {
        fs.status = Status::kDiverged;
        fs.message = excess;
        result.summary.status = Status::kDiverged;
        result.summary.message = excess;
        result.rigid_motion = Eigen::VectorXd::Zero(modes.cols());
        // Not solved: no contact forces, every node reported separated.
        result.state = contact::ContactState(dim, boundary_->num_nodes());
        result.state.nodes.assign(static_cast<std::size_t>(boundary_->num_nodes()), contact::NodeClassification{});
      } else {
        fs = floating.solve(c, e, result.state, result.rigid_motion);
        result.summary = fs.inner;
        if (!fs.converged()) {
          result.summary.status = fs.status;
          result.summary.message = fs.message;
          // A posteriori: with the normal force a result, compare with the capacity at the
          // last iterate's P.
          if (dim == 3 || dim == 2) {
            Eigen::Vector2d tangential(net(0), dim == 3 ? net(1) : 0.0);
            const std::string report = friction_capacity_excess(law, tangential, result.state.normal_forces().sum(), dim);
            if (!report.empty()) result.summary.message = fs.message = report;
          }
        }
      }
      result.floating = fs;
    }
    if (result.summary.converged()) warm_start_ = result.state;
    result.resultants = contact::contact_resultants(result.state, boundary_->tributary_areas(),
                                                    boundary_->plane_coordinates(), boundary_->frame_rows());
    // u_f = A⁻¹(l + Gᵀz): the body under its loads and the contact forces.
    Eigen::VectorXd w = Eigen::VectorXd::Zero(fem_->dofs().num_free());
    boundary_->add_transpose_times(result.state.z, w);
    u_free += solver.solve(w);
    rhs += w;
    if (!result.summary.converged()) {
      state.summary.status = result.summary.status;
      state.summary.message = "contact: " + result.summary.message;
    }
    state.contact = std::move(result);
  } else if (step) {
    step_alpha_ = Eigen::VectorXd(alpha);
  }
  state.displacement = fem_->dofs().expand(u_free);
  if (step) state.displacement += step->prescribed_change;
  if (state.contact && state.contact->rigid_motion.size()) {
    // u = A⁺(l + Gᵀz) + Rβ (spec 07 §2); the rigid motion does not change A u.
    state.displacement += free_rigid_modes(state.positions, user_prescribed_dofs_) * state.contact->rigid_motion;
  }
  state.summary.solve_seconds = seconds_since(start);

  const double load_norm = rhs.norm();
  state.summary.relative_residual =
      (fem_->stiffness() * u_free - rhs).norm() / (load_norm > 0 ? load_norm : 1.0);
  state.stress = fem::recover_stresses(*mesh_, definition_.material, state.positions, state.displacement);
  state.strain_energy = fem_->strain_energy(state.positions, state.displacement);
  // The work of the definition's tractions (a loading program recomputes it with its step's loads).
  state.external_work = fem_->external_work(state.positions, state.displacement);
  if (nodal_forces_.size()) state.external_work += nodal_forces_.dot(u_free);
  if (state.summary.status == Status::kNotRun) {
    state.summary.status = Status::kConverged;
    state.summary.message = boundary_ ? "contact with Coulomb friction solved (dual QP fixed point)"
                                      : "linear elasticity solved by sparse Cholesky";
  }
  return state;
}

BodyState ElasticBody::solve_with_petsc(BodyState state) {
#ifdef FRICTOPT_HAVE_PETSC
  ContactResult result;
  result.gaps = boundary_->gaps(state.positions);
  Eigen::VectorXd u = petsc_displacement_;
  const petsc::ContactNewtonSolver::Summary s = petsc_engine_->solve(state.positions, result.gaps, u, result.state);
  if (s.converged()) petsc_displacement_ = u;
  // The engine's report in the contact summary's terms (iterations = Newton, QP = Krylov).
  result.summary.status = s.status;
  result.summary.message = s.brief_report();
  result.summary.iterations = s.newton_iterations;
  result.summary.qp_iterations = s.krylov_iterations;
  result.summary.kkt_residual = s.kkt_residual;
  result.summary.complementarity_gap = s.complementarity_gap;
  result.summary.time_seconds = s.solve_seconds;
  result.delassus = petsc_engine_->delassus();  // Krylov solves; valid until the next solve
  state.summary.assembly_seconds = s.assembly_seconds;
  state.summary.solve_seconds = s.solve_seconds;
  state.summary.relative_residual = s.relative_residual;
  state.summary.status = s.status;
  state.summary.message = (s.converged() ? "contact with Coulomb friction solved by the " : "contact: the ") + s.brief_report();
  state.displacement = std::move(u);
  state.contact = std::move(result);
  state.stress = fem::recover_stresses(*mesh_, definition_.material, state.positions, state.displacement);
  state.strain_energy = fem_->strain_energy(state.positions, state.displacement);
  state.external_work = fem_->external_work(state.positions, state.displacement);
  return state;
#else
  (void)state;
  throw InvalidInput("solver.engine = \"petsc\": this frictopt was built without PETSc");
#endif
}

sensitivity::AdjointSensitivity::Result ElasticBody::petsc_subgradient(const BodyState& state,
                                                                       const sensitivity::CostPartials& partials,
                                                                       const Eigen::MatrixXd& gap_matrix) {
#ifdef FRICTOPT_HAVE_PETSC
  FRICTOPT_ASSERT(petsc_engine_ != nullptr, "petsc_subgradient needs engine = \"petsc\"");
  const petsc::ContactNewtonSolver::SubgradientResult r =
      petsc_engine_->subgradient(state.positions, state.displacement, partials.d_alpha, partials.d_displacement,
                                 partials.d_contact, gap_matrix);
  sensitivity::AdjointSensitivity::Result result;
  result.subgradient = r.subgradient;
  result.summary.status = r.summary.status;
  result.summary.message = r.summary.brief_report();
  result.summary.relative_residual = r.summary.relative_residual;
  result.summary.time_seconds = r.summary.seconds;
  return result;
#else
  (void)state, (void)partials, (void)gap_matrix;
  throw InvalidInput("solver.engine = \"petsc\": this frictopt was built without PETSc");
#endif
}

}  // namespace frictopt::study
