// SPDX-License-Identifier: MIT
#include "frictopt/study/history.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/sensitivity/friction_parameters.hpp"
#include "frictopt/study/orientation_design.hpp"
#include "frictopt/study/cost_factory.hpp"

namespace frictopt::study {
namespace {

// One "load case" per step, with the scales in force at that step (LoadingProgram::run's).
LoadCasesDefinition steps_as_cases(const LoadingProgramDefinition& program, const BodyDefinition& def) {
  LoadCasesDefinition cases;
  const std::vector<LoadStepDefinition> steps = program.scales_in_force(def);
  for (std::size_t k = 0; k < steps.size(); ++k)
    cases.cases.push_back(LoadCaseDefinition{fmt::format("step {}", k + 1), steps[k].load_scale,
                                             steps[k].dirichlet_scale, steps[k].force_scale, 1.0, std::nullopt});
  return cases;
}

// The dissipation's name for reports (ShapeOracle::cost()); its value and partials read the
// whole history, which a one-state CostInput does not carry: ProgramHistory computes them.
class DissipationName final : public cost::CostFunctional {
 public:
  std::string name() const override { return "dissipation"; }
  sensitivity::CostPartials evaluate(const cost::CostInput&) const override {
    throw InvalidInput("cost dissipation reads the whole loading program; it is evaluated by study::ProgramHistory, "
                       "not on one state");
  }
};

}  // namespace

ProgramHistory::ProgramHistory(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost,
                               Eigen::MatrixXd gap_matrix)
    : body_(body), static_problem_(true), gap_matrix_(std::move(gap_matrix)), step_cost_(std::move(cost)) {
  prepare_static(nullptr);
}

namespace {
void require_contact(const ElasticBody& body) {
  if (!body.contact_boundary() || !body.definition().contact)
    throw InvalidInput("a cost of the contact state needs a body in contact: add a [contact] table to the case");
}
}  // namespace

void ProgramHistory::prepare_static(const CostDefinition* definition) {
  require_contact(body_);
  states_.resize(1);
  sets_.resize(1);
  if (!definition) return;
  validate_combination(*definition);
  // A cost that reads the initial state ("initial_mean" targets) gets it solved here; the shape
  // oracle keeps it as its first state, so the optimizer's first evaluation does not solve again.
  const bool initial = needs_initial_state(*definition);
  if (initial) solve(body_.initial_design());
  step_cost_ = make_cost(*definition, body_, initial ? states_.front().get() : nullptr);
}

ProgramHistory::ProgramHistory(ElasticBody& body, const CostDefinition& definition, Eigen::MatrixXd gap_matrix,
                               std::string_view where)
    : body_(body), static_problem_(!definition.program), gap_matrix_(std::move(gap_matrix)) {
  if (static_problem_) {
    prepare_static(&definition);
    return;
  }
  require_contact(body_);
  program_ = *definition.program;
  program_.validate(body_.definition(), where);
  const int k_steps = num_steps();
  validate_combination(definition);
  dissipation_ = definition.kind == cost::CostKind::kDissipation;
  cost_step_ = definition.step == 0 ? k_steps - 1 : definition.step - 1;
  step_loads_ = std::make_unique<LoadCases>(body_, steps_as_cases(program_, body_.definition()));
  const auto n = static_cast<std::size_t>(k_steps);
  states_.resize(n);
  warm_starts_.resize(n);
  sets_.resize(n);
  if (dissipation_) {
    step_cost_ = std::make_unique<DissipationName>();
    return;
  }
  // An "initial_mean" target is the mean of the state the cost reads — the chosen step's — at α⁰:
  // "keep the pressure of the last step as even as it is on average at the start".
  const BodyState* initial = nullptr;
  if (needs_initial_state(definition)) {
    solve(body_.initial_design());
    if (!ok_ && !states_[static_cast<std::size_t>(cost_step_)])
      throw NumericalFailure("cost target = initial_mean: the program at the initial design did not solve: " + message_);
    initial = states_[static_cast<std::size_t>(cost_step_)].get();
  }
  CostDefinition one_step = definition;
  one_step.program.reset();
  step_cost_ = make_cost(one_step, body_, initial);
}

void ProgramHistory::set_warm_starts(std::vector<std::optional<contact::ContactState>> states) {
  if (states.size() != warm_starts_.size())
    throw InvalidInput(fmt::format("ProgramHistory::set_warm_starts: {} states; expected one per step ({})",
                                   states.size(), warm_starts_.size()));
  warm_starts_ = std::move(states);
}

std::string ProgramHistory::name() const {
  if (dissipation_ || static_problem_) return step_cost_->name();
  return fmt::format("{} at step {}", step_cost_->name(), cost_step_ + 1);
}

const contact::FrictionLaw& ProgramHistory::law(int k) const {
  FRICTOPT_ASSERT(states_[static_cast<std::size_t>(k)] != nullptr, "ProgramHistory::law: a solved step");
  return *states_[static_cast<std::size_t>(k)]->contact->law;  // the law the step was solved with
}

void ProgramHistory::solve_static(const Eigen::Ref<const Eigen::VectorXd>& alpha) {
  std::shared_ptr<BodyState>& state = states_.front();
  if (state && state->contact) {
    // The previous state stays readable for output; its Delassus operator (up to m² doubles)
    // is released — the sensitivity needs it only for the last design, with its factorization.
    state->contact->delassus.reset();
    state->contact->delassus_matrix.reset();
  }
  sets_.front().reset();
  partials_.reset();
  alpha_ = alpha;
  state = std::make_shared<BodyState>(body_.solve(alpha, "design"));
  factorizations_ = state->summary.factorization_seconds > 0.0 ? 1 : 0;
  ok_ = state->summary.status == Status::kConverged;
  message_ = ok_ ? std::string("solved") : state->summary.message;
}

void ProgramHistory::solve(const Eigen::Ref<const Eigen::VectorXd>& alpha) {
  if (static_problem_) return solve_static(alpha);
  const BodyDefinition& def = body_.definition();
  const mesh::Mesh& mesh = body_.mesh();
  // x = α, or (α, s) with [design] friction_orientation: solve_step turns the law to φ = s/k.
  if (alpha.size() != body_.num_design_variables())
    throw InvalidInput(fmt::format("design: has {} entries; expected {} ({} control heights{})", alpha.size(),
                                   body_.num_design_variables(), def.shape.num_controls(),
                                   body_.orientation_design() ? " and the friction orientation" : ""));
  alpha_ = alpha;
  for (auto& s : states_)
    if (s && s->contact) {
      // Earlier states stay readable for output; their Delassus operator is released.
      s->contact->delassus.reset();
      s->contact->delassus_matrix.reset();
    }
  for (auto& s : sets_) s.reset();
  partials_.reset();
  const StepLoadBuilder builder(body_, mesh.positions(alpha.head(def.shape.num_controls())));
  const Eigen::Index p = body_.contact_boundary()->num_nodes();
  tangential_.assign(1, Eigen::VectorXd::Zero((mesh.dim() - 1) * p));  // u_t^0 = 0
  ok_ = true;
  factorizations_ = 0;
  message_ = fmt::format("all {} steps solved", num_steps());
  for (int k = 0; k < num_steps(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    const LoadCaseDefinition& scales = (*step_loads_)[k];
    std::vector<fem::FaceDirichlet> dirichlet = def.dirichlet;
    for (std::size_t j = 0; j < dirichlet.size(); ++j) dirichlet[j].displacement *= scales.dirichlet_scale[j];
    const StepLoads step =
        builder.build(scales.load_scale, scales.force_scale, dirichlet, tangential_.back(), program_.steps[i].friction);
    body_.set_warm_start(warm_starts_[i]);
    const std::string label = program_.steps[i].label.empty() ? fmt::format("step {}", k + 1) : program_.steps[i].label;
    states_[i] = std::make_shared<BodyState>(body_.solve_step(alpha, step, label));
    if (states_[i]->summary.factorization_seconds > 0.0) ++factorizations_;
    if (states_[i]->summary.status != Status::kConverged) {
      ok_ = false;
      message_ = fmt::format("{}: {}", label, states_[i]->summary.message);
      for (std::size_t later = i + 1; later < states_.size(); ++later) states_[later].reset();
      return;
    }
    warm_starts_[i] = states_[i]->contact->state;
    tangential_.push_back(builder.tangential_displacement(states_[i]->displacement));
  }
}

std::shared_ptr<BodyState> ProgramHistory::cost_state() const {
  for (int k = cost_step_; k >= 0; --k)
    if (states_[static_cast<std::size_t>(k)]) return states_[static_cast<std::size_t>(k)];
  return nullptr;
}

double ProgramHistory::value() const {
  FRICTOPT_ASSERT(ok_, "ProgramHistory::value needs a solved program");
  if (!dissipation_) return partials()[static_cast<std::size_t>(cost_step_)].value;
  // D = Σ_k Σ_i ⟨q_i^k, u_t^{i,k} − u_t^{i,k−1}⟩ (docs/theory/loading-program.md §4).
  const int dim = body_.mesh().dim(), nt = dim - 1;
  double d = 0.0;
  for (int k = 0; k < num_steps(); ++k) {
    const Eigen::VectorXd& z = states_[static_cast<std::size_t>(k)]->contact->state.z;
    const Eigen::VectorXd slip = tangential_[static_cast<std::size_t>(k) + 1] - tangential_[static_cast<std::size_t>(k)];
    for (Eigen::Index i = 0; i < body_.contact_boundary()->num_nodes(); ++i)
      for (int c = 0; c < nt; ++c) d += z(dim * i + c) * slip(nt * i + c);
  }
  return d;
}

const std::vector<sensitivity::CostPartials>& ProgramHistory::partials() const {
  if (partials_) return *partials_;
  const contact::ContactBoundary& boundary = *body_.contact_boundary();
  const int dim = body_.mesh().dim(), nt = dim - 1;
  const auto n = static_cast<std::size_t>(num_steps());
  std::vector<sensitivity::CostPartials>& out = partials_.emplace(n);
  for (std::size_t k = 0; k < n; ++k) out[k].d_displacement = Eigen::VectorXd::Zero(body_.mesh().num_dofs());
  if (!dissipation_) {
    const BodyState& s = *states_[static_cast<std::size_t>(cost_step_)];
    const cost::CostInput input{body_.elasticity(), boundary, s.alpha, s.positions, s.displacement,
                                s.contact->state, boundary.tributary_areas()};
    out[static_cast<std::size_t>(cost_step_)] = step_cost_->evaluate(input);
    return out;
  }
  // ∂D/∂q^k = Δu_t^k; ∂D/∂u_k = ∂u_t^kᵀ (q^k − q^{k+1}) with u_t^k = (t_c·u_node)_c (q^{K+1} = 0).
  const Eigen::MatrixXd& tangents = boundary.foundation().frame.tangents;  // dim × (dim − 1)
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::VectorXd& z = states_[k]->contact->state.z;
    const Eigen::VectorXd slip = tangential_[k + 1] - tangential_[k];
    out[k].d_contact = Eigen::VectorXd::Zero(z.size());
    for (Eigen::Index i = 0; i < boundary.num_nodes(); ++i) {
      Eigen::VectorXd q_change(nt);
      for (int c = 0; c < nt; ++c) {
        out[k].d_contact(dim * i + c) = slip(nt * i + c);
        q_change(c) = z(dim * i + c) - (k + 1 < n ? states_[k + 1]->contact->state.z(dim * i + c) : 0.0);
      }
      const int node = boundary.nodes()[static_cast<std::size_t>(i)];
      out[k].d_displacement.segment(node * dim, dim) = tangents * q_change;
    }
  }
  return out;
}

const sensitivity::IndexSets& ProgramHistory::index_sets(int k) {
  FRICTOPT_ASSERT(ok_, "ProgramHistory::index_sets needs a solved program");
  auto& sets = sets_[static_cast<std::size_t>(k)];
  if (!sets) sets = sensitivity::classify(states_[static_cast<std::size_t>(k)]->contact->state, law(k));
  return *sets;
}

sensitivity::PieceEnumeration ProgramHistory::pieces(int k, int cap) {
  return sensitivity::enumerate_pieces(index_sets(k), law(k), cap);
}

std::vector<sensitivity::Piece> ProgramHistory::default_pieces() {
  std::vector<sensitivity::Piece> out;
  for (int k = 0; k < num_steps(); ++k) out.push_back(sensitivity::default_piece(index_sets(k)));
  return out;
}

double ProgramHistory::cardinality() {
  double product = 1.0;
  for (int k = 0; k < num_steps(); ++k) product *= pieces(k, 1).cardinality;
  return product;
}

sensitivity::PieceEnumeration ProgramHistory::cost_step_pieces(int cap) {
  sensitivity::PieceEnumeration out = pieces(cost_step_, cap);
  const double step_cardinality = out.cardinality;
  out.cardinality = cardinality();
  out.sampled = out.sampled || out.cardinality > step_cardinality;
  return out;
}

std::vector<sensitivity::AdjointSensitivity::Result> ProgramHistory::cost_step_subgradients(
    const std::vector<sensitivity::Piece>& pieces) {
  FRICTOPT_ASSERT(ok_, "ProgramHistory::cost_step_subgradients needs a solved program");
  if (static_problem_) {
    // The state engine's adjoints, all pieces at once (the PETSc engine's too).
    const BodyState& state = *states_.front();
    std::vector<sensitivity::AdjointSensitivity::Result> out =
        body_.engine().subgradients(state, pieces, partials().front(), gap_matrix_);
    for (std::size_t i = 0; i < pieces.size(); ++i)
      append_orientation_derivative(body_.orientation_design(), law(0), pieces[i], state.contact->state, out[i]);
    return out;
  }
  std::vector<sensitivity::AdjointSensitivity::Result> out;
  std::vector<sensitivity::Piece> chosen = default_pieces();
  for (const sensitivity::Piece& piece : pieces) {
    chosen[static_cast<std::size_t>(cost_step_)] = piece;
    HistorySubgradient h = subgradient(chosen);
    sensitivity::AdjointSensitivity::Result r;
    r.subgradient = std::move(h.subgradient);
    r.friction_gradient = std::move(h.friction_gradient);
    r.summary = h.summary;
    if (h.summary.status == Status::kConverged) {
      r.psi_u = std::move(h.psi_u[static_cast<std::size_t>(cost_step_)]);
      r.psi_z = std::move(h.psi_z[static_cast<std::size_t>(cost_step_)]);
    }
    out.push_back(std::move(r));
  }
  return out;
}

sensitivity::AdjointSensitivity::StateDerivative ProgramHistory::state_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& h, const sensitivity::Piece* piece) {
  if (!static_problem_)
    throw InvalidInput("ShapeOracle::state_derivative: not available for a cost along a loading history or for load "
                       "cases (the state derivative of one step depends on the earlier steps', and a case's on its "
                       "own load change)");
  FRICTOPT_ASSERT(states_.front() != nullptr, "ProgramHistory::state_derivative needs a solved state");
  const sensitivity::Piece chosen = piece ? *piece : sensitivity::default_piece(index_sets(0));
  return body_.engine().state_derivative(*states_.front(), chosen, gap_matrix_, h);
}

HistorySubgradient ProgramHistory::subgradient(const std::vector<sensitivity::Piece>& pieces, bool coupled) {
  FRICTOPT_ASSERT(ok_, "ProgramHistory::subgradient needs a solved program");
  FRICTOPT_ASSERT(static_cast<int>(pieces.size()) == num_steps(), "one piece per step");
  if (static_problem_) {
    // The subgradient an evaluation reports: the engine's for the piece (its own linearization
    // for the PETSc engine, docs/petsc-engine.md).
    const BodyState& state = *states_.front();
    auto result = body_.engine().evaluation_subgradient(state, pieces.front(), partials().front(), gap_matrix_);
    append_orientation_derivative(body_.orientation_design(), law(0), pieces.front(), state.contact->state, result);
    HistorySubgradient out;
    out.subgradient = std::move(result.subgradient);
    out.friction_gradient = std::move(result.friction_gradient);
    out.summary = result.summary;
    out.psi_z.push_back(std::move(result.psi_z));
    out.psi_u.push_back(std::move(result.psi_u));
    return out;
  }
  const contact::ContactBoundary& boundary = *body_.contact_boundary();
  const fem::DofMap& dofs = body_.elasticity().dofs();
  const int dim = body_.mesh().dim();
  // One A(α), one factorization and one M for every step (the stiffness does not depend on the
  // load): the last step's solve left them in place.
  const contact::DelassusMatrix* delassus = nullptr;
  for (const auto& s : states_)
    if (s->contact->delassus) delassus = s->contact->delassus.get();
  FRICTOPT_ASSERT(delassus != nullptr, "the program's solve provides the Delassus matrix");

  const std::vector<sensitivity::CostPartials>& j = partials();
  HistorySubgradient out;
  const Eigen::Index d = body_.definition().shape.num_controls();
  out.subgradient = Eigen::VectorXd::Zero(body_.num_design_variables());
  // The parameters of the user's law (a turned law has the same ones).
  out.friction_gradient = Eigen::VectorXd::Zero(
      static_cast<Eigen::Index>(sensitivity::friction_parameters(body_.definition().contact->law).names.size()));
  out.psi_z.resize(pieces.size());
  out.psi_u.resize(pieces.size());
  out.summary.status = Status::kConverged;
  out.summary.reciprocal_condition = std::numeric_limits<double>::infinity();
  // Backward: step k's adjoint sees step k+1's rows through u_k — r_{k+1} = S_{k+1}(G u_{k+1} −
  // E_t G u_k) + C_z z_{k+1} — so its u-partial gains −Gᵀ E_t S_{k+1}ᵀ ψ_z^{k+1}
  // (docs/theory/history-adjoint.md §3).
  Eigen::VectorXd coupling_z;  // E_t S_{k+1}ᵀ ψ_z^{k+1} (dim·p); empty for k = K
  for (int k = num_steps() - 1; k >= 0; --k) {
    const auto i = static_cast<std::size_t>(k);
    const BodyState& s = *states_[i];
    sensitivity::CostPartials partial = j[i];
    if (coupled && coupling_z.size()) {
      Eigen::VectorXd w = Eigen::VectorXd::Zero(dofs.num_free());
      boundary.add_transpose_times(coupling_z, w);
      partial.d_displacement -= dofs.expand_homogeneous(w);
    }
    const bool friction = program_.steps[i].friction;
    const sensitivity::AdjointSensitivity adjoint(body_.elasticity(), boundary, gap_matrix_, law(k));
    auto result = adjoint.subgradient(pieces[i], *delassus, s.positions, s.displacement, s.contact->state, partial);
    // x = (α, s): the law's orientation enters the friction rows of every friction step,
    // ∂Θ/∂s = Σ_k (∂r_k/∂s)ᵀ ψ_z^k (docs/theory/friction-design.md; a frictionless step has none).
    if (friction) append_orientation_derivative(body_.orientation_design(), law(k), pieces[i], s.contact->state, result);
    if (result.summary.status != Status::kConverged) {
      out.summary = result.summary;
      out.summary.message = fmt::format("step {}: {}", k + 1, result.summary.message);
      return out;
    }
    out.summary.time_seconds += result.summary.time_seconds;
    if (result.summary.reciprocal_condition < out.summary.reciprocal_condition) {
      const double seconds = out.summary.time_seconds;
      out.summary = result.summary;
      out.summary.time_seconds = seconds;
    }
    // The step's residual is A(α)u_k − l_k(α): the adjoint differentiated A(α)u_k − l(α).
    out.subgradient.head(d) += result.subgradient.head(d) +
                               step_loads_->load_change_shape_derivative(k, s.positions, result.psi_full);
    if (result.subgradient.size() > d) out.subgradient.tail(1) += result.subgradient.tail(1);
    if (friction) out.friction_gradient += result.friction_gradient;
    out.psi_z[i] = result.psi_z;
    out.psi_u[i] = result.psi_u;
    coupling_z = sensitivity::linearize_piece(pieces[i], law(k), s.contact->state).S.transpose() * result.psi_z;
    for (Eigen::Index node = 0; node < boundary.num_nodes(); ++node) coupling_z(dim * node + dim - 1) = 0.0;  // E_t
  }
  out.summary.message = fmt::format("backward adjoint over {} steps; worst step: {}", num_steps(), out.summary.message);
  return out;
}

}  // namespace frictopt::study
