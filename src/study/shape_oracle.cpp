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

// The state's reports (solve, contact solve, forces) that an evaluation carries.
void describe_state(Evaluation& e, const BodyState& s) {
  e.state = s.summary;
  e.contact = s.contact ? s.contact->summary : contact::CoulombSolver::Summary{};
  e.resultants = s.contact ? s.contact->resultants : contact::ContactResultants{};
  e.plates = s.plates;
}
std::vector<double> key_of(const Eigen::Ref<const Eigen::VectorXd>& alpha) { return {alpha.data(), alpha.data() + alpha.size()}; }
// Bounded memory: the bundle method revisits only the last few designs.
constexpr std::size_t kCacheSize = 512;
}  // namespace

ShapeOracle::ShapeOracle(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost)
    : body_(body), cost_(std::move(cost)) {
  if (!body_.contact_boundary())
    throw InvalidInput("the shape oracle needs a body in contact: add a [contact] table to the case");
  gap_matrix_ = body_.contact_boundary()->gap_jacobian(body_.mesh());  // B̃ from V: any mesh producer
}

ShapeOracle::ShapeOracle(ElasticBody& body, const CostDefinition& definition) : ShapeOracle(body, nullptr) {
  if (definition.load_cases) {
    if (definition.program)
      throw InvalidInput("[[load_case]] tables with [[program.step]] tables: the program would apply to no case in "
                         "particular; expected each load case's own [[load_case.step]] tables (a load case given as a "
                         "loading program)");
    // The compliance reads the work of the case file's tractions (cost::CostInput::fem), not a
    // case's: with other loads per case its value would be wrong.
    if (definition.kind == cost::CostKind::kCompliance)
      throw InvalidInput("cost.kind = \"compliance\" with [[load_case]] tables: the compliance reads the case file's own "
                         "loads; expected a contact cost (target_pressure, normal_force_power, pressure_norm, total_slip, "
                         "traction_uniformity)");
    cases_ = std::make_unique<LoadCases>(body_, *definition.load_cases);
    const bool programs = cases_->definition().has_programs();
    if (!programs && definition.step != 0)
      throw InvalidInput(fmt::format("cost.step = {} with load cases that are static loads: a history cost on one-step "
                                     "cases; expected [[load_case.step]] tables or no cost.step",
                                     definition.step));
    if (!programs && definition.kind == cost::CostKind::kDissipation)
      throw InvalidInput("cost.kind = \"dissipation\" with load cases that are static loads: a history cost on one-step "
                         "cases; expected [[load_case.step]] tables");
    // Every case as a loading program (a static load is a one-step program, which solves and
    // differentiates exactly the static problem): one mechanism for states, costs along a
    // history, initial_mean targets (each case's own) and subgradients.
    for (int k = 0; k < cases_->size(); ++k) {
      CostDefinition one = definition;
      one.load_cases.reset();
      one.program = std::make_shared<const LoadingProgramDefinition>((*cases_)[k].as_program());
      case_histories_.push_back(
          std::make_unique<ProgramHistory>(body_, one, gap_matrix_, fmt::format("load_case[{}]", k)));
    }
    return;
  }
  if (definition.program) {
    // A cost along a loading history (study/history.hpp).
    history_ = std::make_unique<ProgramHistory>(body_, definition, gap_matrix_);
    return;
  }
  if (definition.step != 0)
    throw InvalidInput(fmt::format("cost.step = {} on a case without [[program.step]] tables: a history cost on a "
                                   "one-step case; expected [[program.step]] tables or no cost.step",
                                   definition.step));
  const bool initial = needs_initial_state(definition);
  if (initial) solve_state(body_.initial_design());
  cost_ = make_cost(definition, body_, initial ? state_.get() : nullptr);
}

void ShapeOracle::remember(std::shared_ptr<BodyState> state, const Eigen::VectorXd& alpha) {
  state_ = std::move(state);
  state_alpha_ = alpha;
  recent_.push_front(state_);
  if (recent_.size() > kRecentStates) recent_.pop_back();
  ++state_solves_;
}

void ShapeOracle::solve_state(const Eigen::VectorXd& alpha) {
  if (state_ && state_alpha_.size() == alpha.size() && state_alpha_ == alpha) return;
  if (cases_) return solve_cases(alpha);
  if (history_) {
    // Every step at α on one factorization; the oracle's state is the one the cost reads.
    history_->solve(alpha);
    return remember(history_->cost_state(), alpha);
  }
  if (state_ && state_->contact) {
    // The previous state stays readable for output; its Delassus operator (up to m² doubles)
    // is released — the sensitivity needs it only for the last design, with its factorization.
    state_->contact->delassus.reset();
    state_->contact->delassus_matrix.reset();
  }
  remember(std::make_shared<BodyState>(body_.solve(alpha, "design")), alpha);
}

void ShapeOracle::solve_cases(const Eigen::VectorXd& alpha) {
  // The K cases' programs at one α from the unloaded body: the first step of the first case
  // factorizes A(α) and builds M, every other step of every case reuses both
  // (ElasticBody::solve_step) — one factorization, Σ_k K_k contact solves. Each case's steps
  // start from their own last converged contact states (a neighbour case's is a poor start).
  last_factorizations_ = 0;
  for (const auto& history : case_histories_) {
    history->solve(alpha);
    last_factorizations_ += history->factorizations();
  }
  selected_ = 0;
  remember(case_histories_.front()->cost_state(), alpha);
}

ProgramHistory& ShapeOracle::case_history(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  FRICTOPT_ASSERT(cases_ && k >= 0 && k < cases_->size(), "case_history: a load case of this oracle");
  solve_state(alpha);
  return *case_histories_[static_cast<std::size_t>(k)];
}

void ShapeOracle::select_case(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  state_ = case_history(alpha, k).cost_state();
  selected_ = k;
  // Output at α (state(α)) shows the selected case.
  if (!recent_.empty() && recent_.front()->alpha == state_->alpha) recent_.front() = state_;
}

const sensitivity::IndexSets& ShapeOracle::case_index_sets(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  ProgramHistory& history = case_history(alpha, k);
  return history.index_sets(history.cost_step());
}

const BodyState& ShapeOracle::case_state(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  return *case_history(alpha, k).cost_state();
}

std::vector<sensitivity::AdjointSensitivity::Result> ShapeOracle::case_subgradients(
    const Eigen::Ref<const Eigen::VectorXd>& alpha, int k, const std::vector<sensitivity::Piece>& pieces) {
  return case_history(alpha, k).cost_step_subgradients(pieces);
}

std::vector<std::optional<contact::ContactState>> ShapeOracle::history_warm_starts() const {
  std::vector<std::optional<contact::ContactState>> out;
  if (history_) out = history_->warm_starts();
  for (const auto& h : case_histories_) out.insert(out.end(), h->warm_starts().begin(), h->warm_starts().end());
  return out;
}

void ShapeOracle::set_history_warm_starts(const std::vector<std::optional<contact::ContactState>>& states) {
  std::size_t needed = history_ ? static_cast<std::size_t>(history_->num_steps()) : 0;
  for (const auto& h : case_histories_) needed += static_cast<std::size_t>(h->num_steps());
  if (states.size() != needed)
    throw InvalidInput(fmt::format("ShapeOracle::set_history_warm_starts: {} states; expected {} (one per step of "
                                   "every loading program)",
                                   states.size(), needed));
  auto next = states.begin();
  const auto take = [&](ProgramHistory& h) {
    const auto end = next + h.num_steps();
    h.set_warm_starts({next, end});
    next = end;
  };
  if (history_) take(*history_);
  for (const auto& h : case_histories_) take(*h);
}

sensitivity::PieceEnumeration ShapeOracle::case_pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k, int cap) {
  return case_history(alpha, k).cost_step_pieces(cap);
}

void ShapeOracle::evaluate_cases(Evaluation& e, bool with_subgradient) {
  const int n_cases = cases_->size();
  e.factorizations = last_factorizations_;
  for (int k = 0; k < n_cases; ++k) {
    const ProgramHistory& history = *case_histories_[static_cast<std::size_t>(k)];
    if (!history.ok()) {
      const BodyState& s = *history.cost_state();
      describe_state(e, s);
      e.message = fmt::format("load case \"{}\": state solve failed: {}", (*cases_)[k].name, history.message());
      return;
    }
  }
  for (const auto& history : case_histories_) e.case_values.push_back(history->value());
  const CombinedValue combined = cases_->combine(e.case_values);
  e.value = combined.value;
  e.selected_case = combined.selected;
  select_case(state_alpha_, combined.selected);
  ProgramHistory& selected = *case_histories_[static_cast<std::size_t>(combined.selected)];
  describe_state(e, *state_);
  e.index_sets = selected.index_sets(selected.cost_step());
  if (selected.num_steps() > 1)
    for (int k = 0; k < selected.num_steps(); ++k) e.step_index_sets.push_back(selected.index_sets(k));
  e.ok = true;
  if (!with_subgradient) return;
  const auto start = std::chrono::steady_clock::now();
  // "worst": ξ = w_s ξ_s of the selected case s (a Clarke subgradient of the max, docs/theory/
  // load-cases.md §2), and with case cuts on the cut (w_k J_k, w_k ξ_k) of every other case with
  // w_k > 0 for the optimizer's model of the max (Evaluation::case_cuts); "weighted":
  // ξ = Σ_k w_k ξ_k. Each ξ_k of its case's default pieces (every step's, by the backward adjoint
  // over its program), on the factorization the state solve left.
  const bool worst = cases_->definition().combine == CaseCombination::kWorst;
  for (int k = 0; k < n_cases; ++k) {
    const double w = (*cases_)[k].weight;
    const bool in_xi = !worst || k == combined.selected;
    if (w == 0.0 || (!in_xi && !case_cuts_)) continue;
    ProgramHistory& history = *case_histories_[static_cast<std::size_t>(k)];
    const HistorySubgradient result = history.subgradient(history.default_pieces());
    const bool converged = result.summary.status == Status::kConverged;
    if (!in_xi) {  // a cut is optional: a case whose adjoint fails is left out
      if (converged) e.case_cuts.push_back({w * e.case_values[static_cast<std::size_t>(k)], w * result.subgradient});
      continue;
    }
    e.adjoint = result.summary;
    if (!converged) {
      e.ok = false;
      e.message = fmt::format("load case \"{}\": subgradient failed: {}", (*cases_)[k].name, result.summary.message);
      e.subgradient.resize(0);
      e.friction_gradient.resize(0);
      e.case_cuts.clear();
      break;
    }
    if (e.subgradient.size() == 0) {
      e.subgradient = w * result.subgradient;
      e.friction_gradient = w * result.friction_gradient;
    } else {
      e.subgradient += w * result.subgradient;
      e.friction_gradient += w * result.friction_gradient;
    }
  }
  e.subgradient_seconds = seconds_since(start);
}

void ShapeOracle::evaluate_history(Evaluation& e, bool with_subgradient) {
  describe_state(e, *state_);
  if (!history_->ok()) {
    e.message = "loading program: state solve failed: " + history_->message();
    return;
  }
  e.value = history_->value();
  for (int k = 0; k < history_->num_steps(); ++k) e.step_index_sets.push_back(history_->index_sets(k));
  e.index_sets = e.step_index_sets[static_cast<std::size_t>(history_->cost_step())];
  e.factorizations = 1;
  e.ok = true;
  if (!with_subgradient) return;
  const auto start = std::chrono::steady_clock::now();
  // The backward adjoint with every step's default piece (docs/theory/history-adjoint.md).
  const HistorySubgradient result = history_->subgradient(history_->default_pieces());
  e.adjoint = result.summary;
  e.subgradient_seconds = seconds_since(start);
  if (result.summary.status != Status::kConverged) {
    e.ok = false;
    e.message = "subgradient failed: " + result.summary.message;
    return;
  }
  e.subgradient = result.subgradient;
  e.friction_gradient = result.friction_gradient;
}

const BodyState& ShapeOracle::state(const Eigen::Ref<const Eigen::VectorXd>& alpha) {
  for (const auto& s : recent_)
    if (s->alpha.size() == alpha.size() && s->alpha == alpha) return *s;
  solve_state(alpha);
  return *state_;
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
  if (cases_) {
    evaluate_cases(e, with_subgradient);
    return cache_[key_of(alpha)] = e;
  }
  if (history_) {
    evaluate_history(e, with_subgradient);
    return cache_[key_of(alpha)] = e;
  }
  describe_state(e, *state_);
  if (state_->summary.status != Status::kConverged) {
    e.message = "state solve failed: " + state_->summary.message;
    return cache_[key_of(alpha)] = e;
  }
  const sensitivity::CostPartials j = partials();
  e.value = j.value;
  const contact::FrictionLaw& law = *state_->contact->law;  // the law the state was solved with
  e.index_sets = sensitivity::classify(state_->contact->state, law);
  e.ok = true;
  if (with_subgradient) {
    start = std::chrono::steady_clock::now();
    const sensitivity::Piece piece = sensitivity::default_piece(e.index_sets);
    auto result = body_.engine().evaluation_subgradient(*state_, piece, j, gap_matrix_);
    append_orientation_derivative(body_.orientation_design(), law, piece, state_->contact->state, result);
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
    optim::OracleResult result = optim::OracleResult::success(e.value, e.subgradient);
    result.pieces = e.case_cuts;
    return result;
  } catch (const InvalidInput& error) {
    // An inverting trial design: the optimizer shrinks its step.
    return optim::OracleResult::failure(error.what());
  }
}

std::vector<sensitivity::AdjointSensitivity::Result> ShapeOracle::subgradients(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                       const std::vector<sensitivity::Piece>& pieces) {
  solve_state(alpha);
  if (cases_) return case_subgradients(alpha, selected_, pieces);
  // The pieces are the cost step's; every other step keeps its default piece.
  if (history_) return history_->cost_step_subgradients(pieces);
  std::vector<sensitivity::AdjointSensitivity::Result> out =
      body_.engine().subgradients(*state_, pieces, partials(), gap_matrix_);
  for (std::size_t i = 0; i < pieces.size(); ++i)
    append_orientation_derivative(body_.orientation_design(), *state_->contact->law, pieces[i],
                                  state_->contact->state, out[i]);
  return out;
}

sensitivity::AdjointSensitivity::StateDerivative ShapeOracle::state_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& alpha, const Eigen::Ref<const Eigen::VectorXd>& h,
    const sensitivity::Piece* piece) {
  solve_state(alpha);
  if (history_ || cases_)
    throw InvalidInput("ShapeOracle::state_derivative: not available for a cost along a loading history or for load "
                       "cases (the state derivative of one step depends on the earlier steps', and a case's on its "
                       "own load change)");
  const sensitivity::Piece chosen =
      piece ? *piece : sensitivity::default_piece(sensitivity::classify(state_->contact->state, *state_->contact->law));
  return body_.engine().state_derivative(*state_, chosen, gap_matrix_, h);
}

sensitivity::PieceEnumeration ShapeOracle::pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int cap) {
  solve_state(alpha);
  if (cases_) return case_pieces(alpha, selected_, cap);
  if (history_) return history_->cost_step_pieces(cap);
  const contact::FrictionLaw& law = *state_->contact->law;
  return sensitivity::enumerate_pieces(sensitivity::classify(state_->contact->state, law), law, cap);
}

}  // namespace frictopt::study
