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

Eigen::MatrixXd gap_matrix_of(const ElasticBody& body) {
  if (!body.contact_boundary())
    throw InvalidInput("the shape oracle needs a body in contact: add a [contact] table to the case");
  return body.contact_boundary()->gap_jacobian(body.mesh());  // B̃ from V: any mesh producer
}
}  // namespace

ShapeOracle::ShapeOracle(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost)
    : body_(body), gap_matrix_(gap_matrix_of(body)) {
  if (!cost) throw InvalidInput("ShapeOracle: no cost functional; expected a cost (cost::make_... or study::make_cost)");
  programs_.push_back(std::make_unique<ProgramHistory>(body_, std::move(cost), gap_matrix_));
}

ShapeOracle::ShapeOracle(ElasticBody& body, const CostDefinition& definition)
    : body_(body), gap_matrix_(gap_matrix_of(body)) {
  validate_combination(definition);  // the cost and its loads (cost_factory.hpp)
  if (!definition.load_cases) {
    // One history: the static problem, or the cost's loading program (study/history.hpp).
    programs_.push_back(std::make_unique<ProgramHistory>(body_, definition, gap_matrix_));
    // A static cost that read the initial state solved it: it is the first state, so the
    // optimizer's first evaluation does not solve it again.
    if (programs_.front()->is_static_problem() && programs_.front()->cost_state())
      remember(programs_.front()->cost_state(), body_.initial_design());
    return;
  }
  cases_ = std::make_unique<LoadCases>(body_, *definition.load_cases);
  // Every case as a loading program (a static load is a one-step program, which solves and
  // differentiates the static problem to round-off): one mechanism for states, costs along a
  // history, initial_mean targets (each case's own) and subgradients.
  for (int k = 0; k < cases_->size(); ++k) {
    CostDefinition one = definition;
    one.load_cases.reset();
    one.program = std::make_shared<const LoadingProgramDefinition>((*cases_)[k].as_program());
    programs_.push_back(std::make_unique<ProgramHistory>(body_, one, gap_matrix_, fmt::format("load_case[{}]", k)));
  }
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
  // The K histories at one α from the unloaded body: the first step of the first history
  // factorizes A(α) and builds M, every other step of every history reuses both
  // (ElasticBody::solve_step) — one factorization, Σ_k K_k contact solves. Each history's steps
  // start from their own last converged contact states (a neighbour case's is a poor start).
  last_factorizations_ = 0;
  for (const auto& program : programs_) {
    program->solve(alpha);
    last_factorizations_ += program->factorizations();
  }
  selected_ = 0;
  remember(programs_.front()->cost_state(), alpha);
}

ProgramHistory& ShapeOracle::program(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  FRICTOPT_ASSERT(k >= 0 && k < num_programs(), "ShapeOracle::program: one of its histories");
  solve_state(alpha);
  return *programs_[static_cast<std::size_t>(k)];
}

void ShapeOracle::select_case(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k) {
  state_ = program(alpha, k).cost_state();
  selected_ = k;
  // Output at α (state(α)) shows the selected case.
  if (!recent_.empty() && recent_.front()->alpha == state_->alpha) recent_.front() = state_;
}

std::vector<std::optional<contact::ContactState>> ShapeOracle::history_warm_starts() const {
  std::vector<std::optional<contact::ContactState>> out;
  for (const auto& h : programs_) out.insert(out.end(), h->warm_starts().begin(), h->warm_starts().end());
  return out;
}

void ShapeOracle::set_history_warm_starts(const std::vector<std::optional<contact::ContactState>>& states) {
  std::size_t needed = 0;
  for (const auto& h : programs_) needed += h->warm_starts().size();
  if (states.size() != needed)
    throw InvalidInput(fmt::format("ShapeOracle::set_history_warm_starts: {} states; expected {} (one per step of "
                                   "every loading program)",
                                   states.size(), needed));
  auto next = states.begin();
  for (const auto& h : programs_) {
    const auto end = next + static_cast<std::ptrdiff_t>(h->warm_starts().size());
    h->set_warm_starts({next, end});
    next = end;
  }
}

std::string ShapeOracle::failure_prefix(int k, bool state_failure) const {
  if (cases_) return fmt::format("load case \"{}\": ", (*cases_)[k].name);
  return state_failure && !programs_.front()->is_static_problem() ? "loading program: " : "";
}

// Θ, the selected history and its index sets, then ξ (docs/theory/load-cases.md §2): "worst"
// (and one history): ξ = w_s ξ_s of the selected history s (a Clarke subgradient of the max),
// with case cuts on the cut (w_k J_k, w_k ξ_k) of every other case with w_k > 0 for the
// optimizer's model of the max (Evaluation::case_cuts); "weighted": ξ = Σ_k w_k ξ_k. Each ξ_k of
// its history's default pieces (every step's, by the backward adjoint over its program), on the
// factorization the state solve left. One history has w = 1 (and 1·ξ is ξ, bit for bit).
void ShapeOracle::add_subgradient(Evaluation& e, int selected) {
  const auto start = std::chrono::steady_clock::now();
  const bool worst = !cases_ || cases_->definition().combine == CaseCombination::kWorst;
  for (int k = 0; k < num_programs(); ++k) {
    const double w = cases_ ? (*cases_)[k].weight : 1.0;
    const bool in_xi = !worst || k == selected;
    if (w == 0.0 || (!in_xi && !case_cuts_)) continue;
    ProgramHistory& history = *programs_[static_cast<std::size_t>(k)];
    const HistorySubgradient result = history.subgradient(history.default_pieces());
    const bool converged = result.summary.status == Status::kConverged;
    if (!in_xi) {  // a cut is optional: a case whose adjoint fails is left out
      if (converged) e.case_cuts.push_back({w * e.case_values[static_cast<std::size_t>(k)], w * result.subgradient});
      continue;
    }
    e.adjoint = result.summary;
    if (!converged) {
      e.ok = false;
      e.message = failure_prefix(k, false) + "subgradient failed: " + result.summary.message;
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

const BodyState& ShapeOracle::state(const Eigen::Ref<const Eigen::VectorXd>& alpha) {
  for (const auto& s : recent_)
    if (s->alpha.size() == alpha.size() && s->alpha == alpha) return *s;
  solve_state(alpha);
  return *state_;
}


const Evaluation& ShapeOracle::evaluate_design(const Eigen::Ref<const Eigen::VectorXd>& alpha_ref, bool with_subgradient) {
  const Eigen::VectorXd alpha = alpha_ref;
  auto cached = cache_.find(key_of(alpha));
  if (cached != cache_.end() && (!with_subgradient || cached->second.subgradient.size() || !cached->second.ok))
    return cached->second;
  if (cache_.size() >= kCacheSize) cache_.clear();

  Evaluation e;
  const auto start = std::chrono::steady_clock::now();
  solve_state(alpha);
  e.state_seconds = seconds_since(start);
  e.factorizations = last_factorizations_;
  for (int k = 0; k < num_programs(); ++k) {
    const ProgramHistory& history = *programs_[static_cast<std::size_t>(k)];
    if (!history.ok()) {
      describe_state(e, *history.cost_state());
      e.message = failure_prefix(k, true) + "state solve failed: " + history.message();
      return cache_[key_of(alpha)] = e;
    }
  }
  int selected = 0;
  if (cases_) {
    for (const auto& history : programs_) e.case_values.push_back(history->value());
    const CombinedValue combined = cases_->combine(e.case_values);
    e.value = combined.value;
    selected = e.selected_case = combined.selected;
    select_case(state_alpha_, selected);
  } else {
    e.value = programs_.front()->value();
  }
  ProgramHistory& history = *programs_[static_cast<std::size_t>(selected)];
  describe_state(e, *state_);
  e.index_sets = history.cost_step_index_sets();
  // Every step's sets for a program (a load case's: when it has more than one step).
  if (!history.is_static_problem() && (!cases_ || history.num_steps() > 1))
    for (int k = 0; k < history.num_steps(); ++k) e.step_index_sets.push_back(history.index_sets(k));
  e.ok = true;
  if (with_subgradient) add_subgradient(e, selected);
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
  // The pieces are the cost step's; every other step keeps its default piece.
  return programs_[static_cast<std::size_t>(selected_)]->cost_step_subgradients(pieces);
}

sensitivity::AdjointSensitivity::StateDerivative ShapeOracle::state_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& alpha, const Eigen::Ref<const Eigen::VectorXd>& h,
    const sensitivity::Piece* piece) {
  solve_state(alpha);
  if (cases_)  // even K = 1 static load: its load change enters as in a program step
    throw InvalidInput("ShapeOracle::state_derivative: not available for a cost along a loading history or for load "
                       "cases (the state derivative of one step depends on the earlier steps', and a case's on its "
                       "own load change)");
  return programs_.front()->state_derivative(h, piece);
}

sensitivity::PieceEnumeration ShapeOracle::pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int cap) {
  solve_state(alpha);
  return programs_[static_cast<std::size_t>(selected_)]->cost_step_pieces(cap);
}

}  // namespace frictopt::study
