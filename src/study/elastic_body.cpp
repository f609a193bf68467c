// SPDX-License-Identifier: MIT
#include "frictopt/study/elastic_body.hpp"

#include <fmt/format.h>

#include <chrono>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/contact/working_set_coulomb.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

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
  if (definition_.dirichlet.empty())
    throw InvalidInput(
        "dirichlet: no Dirichlet condition; expected at least one face with prescribed displacement "
        "(otherwise rigid-body motions are free and the stiffness matrix is singular)");
  mesh_ = std::make_unique<const mesh::Mesh>(
      mesh::StructuredMesh(definition_.shape, definition_.height, definition_.resolution).take_mesh());
  fem_ = std::make_unique<fem::LinearElasticity>(*mesh_, definition_.material,
                                                 fem::expand_dirichlet(*mesh_, definition_.dirichlet),
                                                 definition_.tractions, definition_.linear_solver);
  admissible_ = shape::make_admissible_set(definition_.shape, definition_.admissible);
  if (definition_.contact) {
    if (definition_.contact->law.dim() != mesh_->dim())
      throw InvalidInput(fmt::format("contact.friction: a {}D friction law for a {}D body",
                                     definition_.contact->law.dim(), mesh_->dim()));
    definition_.contact->coulomb.validate();
    boundary_ = std::make_unique<contact::ContactBoundary>(*mesh_, fem_->dofs(), definition_.contact_surface);
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
  if (alpha.size() != definition_.shape.num_controls())
    throw InvalidInput(fmt::format("{}: has {} control heights; expected {}", design_label, alpha.size(),
                                   definition_.shape.num_controls()));
  BodyState state;
  state.alpha = alpha;
  state.positions = mesh_->positions(alpha);
  mesh_->check_quality(state.positions, design_label);
  state.volume = mesh_->volume(state.positions);

  auto start = std::chrono::steady_clock::now();
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
  start = std::chrono::steady_clock::now();
  const linalg::SpdSolver& solver = fem_->factorization();
  Eigen::VectorXd u_free = solver.solve(fem_->load());  // the free body's response A⁻¹l
  Eigen::VectorXd rhs = fem_->load();
  if (boundary_) {
    // Dual contact QP (spec 02, §7/§9.2): min ½zᵀMz + zᵀc with c = G A⁻¹ l + (0, g).
    ContactResult result;
    result.gaps = boundary_->gaps(state.positions);
    const int dim = mesh_->dim();
    Eigen::VectorXd c = boundary_->times(u_free);
    for (Eigen::Index i = 0; i < boundary_->num_nodes(); ++i) c(dim * i + dim - 1) += result.gaps(i);
    const ContactDefinition& cd = *definition_.contact;
    result.dense_delassus = boundary_->num_unknowns() <= cd.dense_delassus_max_unknowns;
    if (solver.trailing_size() > 0) {
      auto schur = std::make_shared<contact::SchurDelassus>(solver.trailing_factor(), dim);
      if (result.dense_delassus) {
        // One copy of the dense M, shared by the QP operator and readers of delassus_matrix; the
        // Schur factor is released at the end of this scope.
        result.delassus_matrix = std::make_shared<const Eigen::MatrixXd>(schur->dense());
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
    const linalg::LinearOperator* delassus = result.delassus.get();
    result.state = warm_start_ && warm_start_->z.size() == boundary_->num_unknowns()
                       ? *warm_start_
                       : contact::ContactState(dim, boundary_->num_nodes());
    if (boundary_->num_unknowns() >= kWorkingSetMinUnknowns) {
      // The Coulomb problem on the nodes that can touch (docs/contact.md, "Large contact surfaces").
      result.summary =
          contact::WorkingSetCoulombSolver(*result.delassus, cd.law, cd.coulomb).solve(c, result.state).coulomb;
    } else {
      const contact::CoulombSolver coulomb(*delassus, cd.law, cd.coulomb);
      result.summary = coulomb.solve(c, result.state);
    }
    if (result.summary.converged()) warm_start_ = result.state;
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
  }
  state.displacement = fem_->dofs().expand(u_free);
  state.summary.solve_seconds = seconds_since(start);

  const double load_norm = rhs.norm();
  state.summary.relative_residual =
      (fem_->stiffness() * u_free - rhs).norm() / (load_norm > 0 ? load_norm : 1.0);
  state.stress = fem::recover_stresses(*mesh_, definition_.material, state.positions, state.displacement);
  state.strain_energy = fem_->strain_energy(state.positions, state.displacement);
  state.external_work = fem_->external_work(state.positions, state.displacement);
  if (state.summary.status == Status::kNotRun) {
    state.summary.status = Status::kConverged;
    state.summary.message = boundary_ ? "contact with Coulomb friction solved (dual QP fixed point)"
                                      : "linear elasticity solved by sparse Cholesky";
  }
  return state;
}

}  // namespace frictopt::study
