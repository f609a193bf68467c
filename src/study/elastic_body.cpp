// SPDX-License-Identifier: MIT
#include "frictopt/study/elastic_body.hpp"

#include <fmt/format.h>

#include <chrono>

#include "frictopt/core/error.hpp"

namespace frictopt::study {
namespace {
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
  mesh_ = std::make_unique<mesh::StructuredMesh>(definition_.shape, definition_.height, definition_.resolution);
  fem_ = std::make_unique<fem::LinearElasticity>(*mesh_, definition_.material,
                                                 fem::expand_dirichlet(*mesh_, definition_.dirichlet),
                                                 definition_.tractions);
  admissible_ = shape::make_admissible_set(definition_.shape, definition_.admissible);
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
  state.displacement = fem_->solve();
  state.summary.solve_seconds = seconds_since(start);

  const Eigen::VectorXd u_free = fem_->dofs().restrict(state.displacement);
  const double load_norm = fem_->load().norm();
  state.summary.relative_residual =
      (fem_->stiffness() * u_free - fem_->load()).norm() / (load_norm > 0 ? load_norm : 1.0);
  state.stress = fem::recover_stresses(*mesh_, definition_.material, state.positions, state.displacement);
  state.strain_energy = fem_->strain_energy(state.positions, state.displacement);
  state.external_work = fem_->external_work(state.positions, state.displacement);
  state.summary.status = Status::kConverged;
  state.summary.message = "linear elasticity solved by sparse Cholesky";
  return state;
}

}  // namespace frictopt::study
