// SPDX-License-Identifier: MIT
#include "direct_engine.hpp"

#include <fmt/format.h>

#include <chrono>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/floating_coulomb_solver.hpp"
#include "frictopt/contact/working_set_coulomb.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/floating_body.hpp"

namespace frictopt::study {
namespace {
// From this many contact unknowns the Coulomb problem is solved on a working set of nodes: below,
// a QP product with the whole M costs microseconds and the restriction would not pay.
constexpr Eigen::Index kWorkingSetMinUnknowns = 1000;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

DirectEngine::DirectEngine(const BodyDefinition& definition, const EngineSetup& setup)
    : StateEngine(setup),
      contact_(definition.contact.value_or(ContactDefinition{})),
      nodal_forces_(setup.nodal_forces),
      nodal_forces_full_(setup.nodal_forces_full),
      user_prescribed_dofs_(setup.user_prescribed_dofs),
      fixing_dofs_(setup.fixing_dofs) {
  // Contact DOFs last, in z order: the trailing factor gives the Delassus matrix
  // (docs/theory/state-problem.md §4). A backend without that capability gets M by solves.
  if (boundary_ && elasticity_.factorization().supports_trailing_factor()) {
    std::vector<int> trailing;
    for (Eigen::Index i = 0; i < boundary_->num_nodes(); ++i)
      for (int c = 0; c < mesh_.dim(); ++c) trailing.push_back(boundary_->free_dof(i, c));
    elasticity_.set_trailing_dofs(std::move(trailing));
  }
}

bool DirectEngine::factorize(BodyState& state) {
  auto start = std::chrono::steady_clock::now();
  elasticity_.assemble(state.positions);
  state.summary.assembly_seconds = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const Status status = elasticity_.factorize();
  state.summary.factorization_seconds = seconds_since(start);
  if (status == Status::kConverged) return true;
  state.summary.status = status;
  state.summary.message = elasticity_.factorization().message();
  return false;
}

std::optional<double> DirectEngine::solve_state(BodyState& state, const StateRequest& request) {
  const StepLoads* step = request.step;
  // A step at the design of the previous step reuses A(α), its factor and M
  // (docs/theory/loading-program.md).
  const bool reuse = step != nullptr && step_alpha_ && *step_alpha_ == state.alpha;
  if (!reuse) {
    step_alpha_.reset();
    if (!factorize(state)) return std::nullopt;
  }
  const auto start = std::chrono::steady_clock::now();
  const linalg::SpdSolver& solver = elasticity_.factorization();
  Eigen::VectorXd rhs = elasticity_.load();
  if (nodal_forces_.size()) rhs += nodal_forces_;
  if (step) rhs += step->load_change;
  Eigen::VectorXd u_free = solver.solve(rhs);  // the free body's response A⁻¹l
  if (boundary_) {
    // Dual contact QP (docs/theory/state-problem.md §5): min ½zᵀMz + zᵀc with c = G A⁻¹ l + (0, g).
    ContactResult result;
    result.gaps = boundary_->gaps(state.positions);
    const int dim = mesh_.dim();
    Eigen::VectorXd c = boundary_->times(u_free);
    for (Eigen::Index i = 0; i < boundary_->num_nodes(); ++i) c(dim * i + dim - 1) += result.gaps(i);
    // The lifting of prescribed values enters c through A⁻¹l; their own motion at contact nodes
    // is zero (contact nodes have only free DOFs), so c needs no other Dirichlet term.
    if (step) c = contact::shift_by_previous_slip(c, step->previous_tangential, dim);
    attach_delassus(result, reuse);
    if (step) {
      step_alpha_ = state.alpha;
      step_delassus_ = result.delassus;
      step_delassus_matrix_ = result.delassus_matrix;
    }
    solve_contact(result, c, state, request);
    // u_f = A⁻¹(l + Gᵀz): the body under its loads and the contact forces.
    Eigen::VectorXd w = Eigen::VectorXd::Zero(elasticity_.dofs().num_free());
    boundary_->add_transpose_times(result.state.z, w);
    u_free += solver.solve(w);
    rhs += w;
    if (!result.summary.converged()) {
      state.summary.status = result.summary.status;
      state.summary.message = "contact: " + result.summary.message;
    }
    state.contact = std::move(result);
  } else if (step) {
    step_alpha_ = state.alpha;
  }
  state.displacement = elasticity_.dofs().expand(u_free);
  if (step) state.displacement += step->prescribed_change;
  if (state.contact && state.contact->rigid_motion.size()) {
    // u = A⁺(l + Gᵀz) + Rβ; the rigid motion does not change A u.
    state.displacement += free_rigid_modes(state.positions, user_prescribed_dofs_, elasticity_.dofs().ties()) * state.contact->rigid_motion;
  }
  state.summary.solve_seconds = seconds_since(start);
  const double load_norm = rhs.norm();
  state.summary.relative_residual =
      (elasticity_.stiffness() * u_free - rhs).norm() / (load_norm > 0 ? load_norm : 1.0);
  if (state.summary.status == Status::kNotRun) {
    state.summary.status = Status::kConverged;
    state.summary.message =
        !state.contact ? "linear elasticity solved by sparse Cholesky"
        : state.contact->summary.method_used == contact::CoulombMethod::kSemismoothNewton
            ? "contact with Coulomb friction solved (semismooth Newton on the dual problem)"
            : "contact with Coulomb friction solved (dual QP fixed point)";
  }
  return nodal_forces_.size() ? nodal_forces_.dot(u_free) : 0.0;
}

void DirectEngine::attach_delassus(ContactResult& result, bool reuse) {
  const linalg::SpdSolver& solver = elasticity_.factorization();
  const int dim = mesh_.dim();
  result.dense_delassus = boundary_->num_unknowns() <= contact_.dense_delassus_max_unknowns;
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
    // Applied through the factorization: valid until the next solve refactorizes, which is how
    // ShapeOracle uses it (the sensitivity reads M only at the last solved design).
    result.delassus = std::make_shared<contact::FactorizedDelassus>(solver, *boundary_);
  }
}

void DirectEngine::solve_contact(ContactResult& result, const Eigen::VectorXd& c, BodyState& state,
                                 const StateRequest& request) {
  const int dim = mesh_.dim();
  const std::optional<contact::ContactState>* warm = request.warm_start;
  result.state = warm && *warm && (*warm)->z.size() == boundary_->num_unknowns()
                     ? **warm
                     : contact::ContactState(dim, boundary_->num_nodes());
  const contact::FrictionLaw& law = *request.law;
  if (fixing_dofs_.empty() && boundary_->num_unknowns() >= kWorkingSetMinUnknowns) {
    // The Coulomb problem on the nodes that can touch (docs/contact.md, "Large contact surfaces").
    result.summary =
        contact::WorkingSetCoulombSolver(*result.delassus, law, contact_.coulomb).solve(c, result.state).coulomb;
  } else if (fixing_dofs_.empty()) {
    const contact::CoulombSolver coulomb(*result.delassus, law, contact_.coulomb);
    result.summary = coulomb.solve(c, result.state);
  } else {
    solve_floating(result, c, state, request);
  }
  if (result.summary.converged() && request.warm_start) *request.warm_start = result.state;
}

void DirectEngine::solve_floating(ContactResult& result, const Eigen::VectorXd& c, const BodyState& state,
                                  const StateRequest& request) {
  // Floating body: the contact forces must balance the loads, E z = e with E = (G R)ᵀ and
  // e = −Rᵀ l over every DOF the user does not prescribe, l including the lifting of the
  // prescribed values: l = f − (A u_d − l_traction) = f − residual(u_d).
  const int dim = mesh_.dim();
  const StepLoads* step = request.step;
  const contact::FrictionLaw& law = *request.law;
  const Eigen::MatrixXd modes = free_rigid_modes(state.positions, user_prescribed_dofs_, elasticity_.dofs().ties());
  if (modes.cols() != static_cast<Eigen::Index>(fixing_dofs_.size()))
    throw InvalidInput(fmt::format("{}: the body has {} free rigid-body modes at this design but {} at the "
                                   "reference; expected the same",
                                   request.design_label, modes.cols(), fixing_dofs_.size()));
  Eigen::VectorXd prescribed = elasticity_.dofs().prescribed_values();
  if (step) prescribed += step->prescribed_change;
  Eigen::VectorXd load = -elasticity_.residual(state.positions, prescribed);
  if (nodal_forces_full_.size()) load += nodal_forces_full_;
  if (step && step->applied_change.size()) load += step->applied_change;
  for (int d : user_prescribed_dofs_) load(d) = 0.0;  // reactions are not loads
  const Eigen::VectorXd e = -modes.transpose() * load;
  Eigen::MatrixXd E(modes.cols(), boundary_->num_unknowns());
  for (Eigen::Index j = 0; j < modes.cols(); ++j)
    E.row(j) = boundary_->times(elasticity_.dofs().restrict(modes.col(j))).transpose();
  // A priori: when the net load presses the body (vertical translation free), the friction
  // capacity is known before any iteration: refuse a load beyond it with its excess.
  std::string excess;
  Eigen::VectorXd translation = Eigen::VectorXd::Zero(mesh_.num_dofs());
  Eigen::Vector3d net = Eigen::Vector3d::Zero();
  bool translations_free = true;
  for (int comp = 0; comp < dim; ++comp) {
    translation.setZero();
    for (int a = 0; a < mesh_.num_nodes(); ++a) translation(a * dim + comp) = 1.0;
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
  fo.coulomb = contact_.coulomb;
  const contact::FloatingCoulombSolver floating(*result.delassus, E, law, fo);
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
      // A posteriori: with the normal force a result, compare with the capacity at the last
      // iterate's P.
      if (dim == 3 || dim == 2) {
        Eigen::Vector2d tangential(net(0), dim == 3 ? net(1) : 0.0);
        const std::string report = friction_capacity_excess(law, tangential, result.state.normal_forces().sum(), dim);
        if (!report.empty()) result.summary.message = fs.message = report;
      }
    }
  }
  result.floating = fs;
}

}  // namespace frictopt::study
