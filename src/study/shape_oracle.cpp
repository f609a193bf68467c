// SPDX-License-Identifier: MIT
#include "frictopt/study/shape_oracle.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::study {
namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
std::vector<double> key_of(const Eigen::Ref<const Eigen::VectorXd>& alpha) { return {alpha.data(), alpha.data() + alpha.size()}; }
// Bounded memory: the bundle method revisits only the last few designs.
constexpr std::size_t kCacheSize = 512;
}  // namespace

std::unique_ptr<cost::CostFunctional> make_cost(const CostDefinition& definition, ElasticBody& body,
                                                const BodyState* initial_state) {
  using Kind = cost::CostKind;
  // The state at α⁰ for "initial_mean" targets: the caller's, or solved here.
  std::optional<BodyState> solved;
  const auto initial = [&](const char* what) -> const BodyState& {
    if (!initial_state) solved = body.solve(body.definition().initial_design, "initial design");
    const BodyState& s = initial_state ? *initial_state : *solved;
    if (s.summary.status != Status::kConverged)
      throw NumericalFailure(std::string("cost ") + what + " = initial_mean: the state at the initial design did not solve: " +
                             s.summary.message);
    return s;
  };
  switch (definition.kind) {
    case Kind::kTargetPressure: {
      if (!body.contact_boundary()) throw InvalidInput("cost target_pressure needs a body in contact");
      const Eigen::VectorXd& areas = body.contact_boundary()->tributary_areas();
      double pressure = definition.target_pressure;
      if (std::isnan(pressure)) {
        const BodyState& s = initial("target_pressure");
        pressure = s.contact->state.normal_forces().sum() / areas.sum();
      }
      return cost::make_target_normal_force(pressure * areas);
    }
    case Kind::kNormalForcePower: return cost::make_normal_force_power(definition.exponent);
    case Kind::kCompliance: return cost::make_compliance();
    case Kind::kPressureNorm: return cost::make_pressure_norm(definition.exponent);
    case Kind::kTotalSlip: return cost::make_total_slip(definition.smoothing);
    case Kind::kTractionUniformity: {
      if (!definition.target_traction_initial_mean) return cost::make_traction_uniformity(definition.target_traction);
      if (!body.contact_boundary()) throw InvalidInput("cost traction_uniformity needs a body in contact");
      const contact::ContactState& cs = initial("traction_uniformity target").contact->state;
      const int nt = cs.dim - 1;
      Eigen::VectorXd mean = Eigen::VectorXd::Zero(nt);
      for (Eigen::Index i = 0; i < cs.num_nodes(); ++i)
        for (int c = 0; c < nt; ++c) mean(c) -= cs.z(cs.dim * i + c);  // τ_i = −q_i
      return cost::make_traction_uniformity(mean / body.contact_boundary()->tributary_areas().sum());
    }
  }
  return nullptr;
}

ShapeOracle::ShapeOracle(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost)
    : body_(body), cost_(std::move(cost)) {
  if (!body_.contact_boundary())
    throw InvalidInput("the shape oracle needs a body in contact: add a [contact] table to the case");
  gap_matrix_ = body_.contact_boundary()->gap_jacobian(body_.mesh());  // B̃ from V: any mesh producer
}

ShapeOracle::ShapeOracle(ElasticBody& body, const CostDefinition& definition) : ShapeOracle(body, nullptr) {
  const bool needs_initial_state =
      (definition.kind == cost::CostKind::kTargetPressure && std::isnan(definition.target_pressure)) ||
      (definition.kind == cost::CostKind::kTractionUniformity && definition.target_traction_initial_mean);
  if (needs_initial_state) solve_state(body_.definition().initial_design);
  cost_ = make_cost(definition, body_, needs_initial_state ? state_.get() : nullptr);
}

void ShapeOracle::solve_state(const Eigen::VectorXd& alpha) {
  if (state_ && state_alpha_.size() == alpha.size() && state_alpha_ == alpha) return;
  if (state_ && state_->contact) {
    // The previous state stays readable for output; its Delassus operator (up to m² doubles)
    // is released — the sensitivity needs it only for the last design, with its factorization.
    state_->contact->delassus.reset();
    state_->contact->delassus_matrix.reset();
  }
  state_ = std::make_shared<BodyState>(body_.solve(alpha, "design"));
  state_alpha_ = alpha;
  delassus_ = state_->contact ? state_->contact->delassus : nullptr;
  recent_.push_front(state_);
  if (recent_.size() > kRecentStates) recent_.pop_back();
  ++state_solves_;
}

const BodyState& ShapeOracle::state(const Eigen::Ref<const Eigen::VectorXd>& alpha) {
  for (const auto& s : recent_)
    if (s->alpha.size() == alpha.size() && s->alpha == alpha) return *s;
  solve_state(alpha);
  return *state_;
}

const contact::DelassusMatrix& ShapeOracle::delassus() {
  FRICTOPT_ASSERT(delassus_ != nullptr, "the state solve provides the Delassus matrix");
  return *delassus_;
}

sensitivity::CostPartials ShapeOracle::partials() const {
  const BodyState& s = *state_;
  const cost::CostInput input{body_.elasticity(), *body_.contact_boundary(), s.alpha, s.positions, s.displacement,
                              s.contact->state, body_.contact_boundary()->tributary_areas()};
  return cost_->evaluate(input);
}

const Evaluation& ShapeOracle::evaluate_design(const Eigen::Ref<const Eigen::VectorXd>& alpha_ref, bool with_subgradient) {
  const Eigen::VectorXd alpha = alpha_ref;
  auto cached = cache_.find(key_of(alpha));
  if (cached != cache_.end() && (!with_subgradient || cached->second.subgradient.size() || !cached->second.ok))
    return cached->second;
  if (cache_.size() >= kCacheSize) cache_.clear();

  Evaluation e;
  auto start = std::chrono::steady_clock::now();
  solve_state(alpha);
  e.state_seconds = seconds_since(start);
  e.state = state_->summary;
  e.contact = state_->contact->summary;
  if (state_->summary.status != Status::kConverged) {
    e.message = "state solve failed: " + state_->summary.message;
    return cache_[key_of(alpha)] = e;
  }
  const sensitivity::CostPartials j = partials();
  e.value = j.value;
  e.index_sets = sensitivity::classify(state_->contact->state, body_.definition().contact->law);
  e.ok = true;
  if (with_subgradient) {
    start = std::chrono::steady_clock::now();
    const sensitivity::AdjointSensitivity adjoint(body_.elasticity(), *body_.contact_boundary(), gap_matrix_,
                                                  body_.definition().contact->law);
    // The PETSc engine (issue 14): one transposed Krylov solve on its Newton piece, which is
    // the default piece wherever the classification is strict (tests/petsc).
    const auto result = body_.uses_petsc_engine()
                            ? body_.petsc_subgradient(*state_, j, gap_matrix_)
                            : adjoint.subgradient(sensitivity::default_piece(e.index_sets), delassus(), state_->positions,
                                                  state_->displacement, state_->contact->state, j);
    e.adjoint = result.summary;
    e.subgradient_seconds = seconds_since(start);
    if (result.summary.status != Status::kConverged) {
      e.ok = false;
      e.message = "subgradient failed: " + result.summary.message;
    } else {
      e.subgradient = result.subgradient;
      e.friction_gradient = result.friction_gradient;
    }
  }
  return cache_[key_of(alpha)] = e;
}

const Evaluation* ShapeOracle::find_evaluation(const Eigen::Ref<const Eigen::VectorXd>& alpha) const {
  const auto it = cache_.find(key_of(alpha));
  return it == cache_.end() ? nullptr : &it->second;
}

optim::OracleResult ShapeOracle::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) {
  try {
    const Evaluation& e = evaluate_design(x, true);
    if (!e.ok) return optim::OracleResult::failure(e.message);
    return optim::OracleResult::success(e.value, e.subgradient);
  } catch (const InvalidInput& error) {
    // An inverting trial design: the optimizer shrinks its step.
    return optim::OracleResult::failure(error.what());
  }
}

std::vector<sensitivity::AdjointSensitivity::Result> ShapeOracle::subgradients(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                       const std::vector<sensitivity::Piece>& pieces) {
  solve_state(alpha);
  const sensitivity::CostPartials j = partials();
  const sensitivity::AdjointSensitivity adjoint(body_.elasticity(), *body_.contact_boundary(), gap_matrix_,
                                                body_.definition().contact->law);
  std::vector<sensitivity::AdjointSensitivity::Result> out;
  for (const sensitivity::Piece& piece : pieces)
    out.push_back(
        adjoint.subgradient(piece, delassus(), state_->positions, state_->displacement, state_->contact->state, j));
  return out;
}

sensitivity::AdjointSensitivity::StateDerivative ShapeOracle::state_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& alpha, const Eigen::Ref<const Eigen::VectorXd>& h,
    const sensitivity::Piece* piece) {
  solve_state(alpha);
  const sensitivity::AdjointSensitivity adjoint(body_.elasticity(), *body_.contact_boundary(), gap_matrix_,
                                                body_.definition().contact->law);
  const sensitivity::Piece chosen =
      piece ? *piece
            : sensitivity::default_piece(sensitivity::classify(state_->contact->state, body_.definition().contact->law));
  return adjoint.state_derivative(chosen, delassus(), state_->positions, state_->displacement, state_->contact->state, h);
}

sensitivity::PieceEnumeration ShapeOracle::pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int cap) {
  solve_state(alpha);
  const auto sets = sensitivity::classify(state_->contact->state, body_.definition().contact->law);
  return sensitivity::enumerate_pieces(sets, body_.definition().contact->law, cap);
}

}  // namespace frictopt::study
