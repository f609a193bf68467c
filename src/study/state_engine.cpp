// SPDX-License-Identifier: MIT
#include "frictopt/study/state_engine.hpp"

#include <stdexcept>

#include "frictopt/contact/contact_resultants.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/fem/stress_recovery.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {

void StateEngine::solve(BodyState& state, const StateRequest& request) {
  FRICTOPT_ASSERT(!boundary_ || request.law != nullptr, "a state solve with contact names its friction law");
  const std::optional<double> point_load_work = solve_state(state, request);
  if (!point_load_work) return;  // stopped before u (a failed factorization)
  if (state.contact) {
    // What every engine reports of its contact state, from z alone: the law it was solved
    // with, total forces, areas and node counts (contact::contact_resultants).
    state.contact->law = request.law;
    state.contact->resultants = contact::contact_resultants(state.contact->state, boundary_->tributary_areas(),
                                                            boundary_->plane_coordinates(), boundary_->frame_rows());
  }
  state.stress = fem::recover_stresses(mesh_, material_, state.positions, state.displacement);
  state.strain_energy = elasticity_.strain_energy(state.positions, state.displacement);
  // The work of the definition's tractions (a loading program recomputes it with its step's loads).
  state.external_work = elasticity_.external_work(state.positions, state.displacement);
  if (*point_load_work != 0.0) state.external_work += *point_load_work;
}

std::vector<sensitivity::AdjointSensitivity::Result> StateEngine::subgradients(
    const BodyState& state, const std::vector<sensitivity::Piece>& pieces, const sensitivity::CostPartials& j,
    const Eigen::MatrixXd& gap_matrix) {
  if (!(state.contact && state.contact->delassus && state.contact->law))  // checked in Release too
    throw std::logic_error("subgradients: expected the last solved state in contact, with its Delassus operator");
  const sensitivity::AdjointSensitivity adjoint(elasticity_, *boundary_, gap_matrix, *state.contact->law);
  std::vector<sensitivity::AdjointSensitivity::Result> out;
  for (const sensitivity::Piece& piece : pieces)
    out.push_back(adjoint.subgradient(piece, *state.contact->delassus, state.positions, state.displacement,
                                      state.contact->state, j));
  return out;
}

sensitivity::AdjointSensitivity::StateDerivative StateEngine::state_derivative(
    const BodyState& state, const sensitivity::Piece& piece, const Eigen::MatrixXd& gap_matrix,
    const Eigen::Ref<const Eigen::VectorXd>& h) const {
  if (!(state.contact && state.contact->delassus && state.contact->law))  // checked in Release too
    throw std::logic_error("state_derivative: expected the last solved state in contact, with its Delassus operator");
  const sensitivity::AdjointSensitivity adjoint(elasticity_, *boundary_, gap_matrix, *state.contact->law);
  return adjoint.state_derivative(piece, *state.contact->delassus, state.positions, state.displacement,
                                  state.contact->state, h);
}

}  // namespace frictopt::study
