// SPDX-License-Identifier: MIT
// The shape problem as an oracle: Θ(α) = J(α, S(α)) and one subgradient ξ
// (docs/theory/sensitivity.md §6), with the index sets and reports a user needs to trust them;
// results are cached per design.
#pragma once

#include <Eigen/Core>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/optim/oracle.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/index_sets.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/cost_factory.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/history.hpp"
#include "frictopt/study/load_cases.hpp"

namespace frictopt::study {

/// One evaluation of the oracle at a design.
struct Evaluation {
  bool ok = false;
  std::string message;          ///< why not ok (state solve failed, adjoint singular, ...)
  double value = kNaN;          ///< Θ(α)
  Eigen::VectorXd subgradient;  ///< ξ for the default piece (empty when not requested / not ok)
  /// ∂Θ/∂p for the friction parameters p (sensitivity::friction_parameters), same piece.
  Eigen::VectorXd friction_gradient;
  sensitivity::IndexSets index_sets;
  sensitivity::AdjointSensitivity::Summary adjoint;
  StateSummary state;
  contact::CoulombSolver::Summary contact;
  /// Total normal and tangential force, contact area and node counts of the state `contact`
  /// describes (contact::contact_resultants): what the design carries, reported per evaluation
  /// so that a design which lowers Θ by carrying less load is seen (docs/optim.md, "Outcomes").
  contact::ContactResultants resultants;
  /// The loading plates' translations and forces at that state (BodyState::plates): a plate's
  /// force stays the prescribed one whatever the design (docs/theory/loading-plate.md).
  std::vector<fem::PlateReading> plates;
  double state_seconds = 0.0;
  double subgradient_seconds = 0.0;
  /// Load cases (docs/theory/load-cases.md): J_k of every case (unweighted, in the cases' order);
  /// empty without.
  std::vector<double> case_values;
  /// Load cases: the case whose state `index_sets`, `state` and `contact` describe — for "worst"
  /// the first case attaining the max, whose subgradient ξ is (LoadCases::combine); −1 without.
  /// (Each case's state is the one its cost reads: the cost step of its loading program.)
  int selected_case = -1;
  int factorizations = 0;  ///< numeric factorizations of A for this evaluation (1 with K cases)
  /// A cost along a loading history (docs/theory/history-adjoint.md): every step's index sets
  /// (`index_sets` is the cost step's; with load cases, of the selected case's program); empty
  /// without a program.
  std::vector<sensitivity::IndexSets> step_index_sets;
  /// Load cases with combine = "worst" and case cuts on (ShapeOracle::set_case_cuts): the cut
  /// (w_k J_k, w_k ξ_k) of every other case k with w_k > 0 at its default pieces — the pieces of
  /// the max that the optimizer adds as cuts of their own (optim::OracleResult::pieces).
  /// A case whose adjoint fails is left out (its cut is optional).
  std::vector<optim::PieceCut> case_cuts;
};

/// Θ(α) and ξ ∈ ∂Θ(α) (or of the pseudodifferential, docs/theory/sensitivity.md §7) for a body with
/// contact and a cost. With [design] friction_orientation every "α" below is the optimizer's x =
/// (α, s): the body turns its law to φ = s/k per solve, states and the cache are keyed by x, and ξ
/// gets ∂Θ/∂s as its last entry (study/orientation_design.hpp; state_derivative takes α only).
/// Lifetime: `body` must outlive the oracle; the oracle owns the cost. Not thread-safe.
class ShapeOracle final : public optim::Oracle {
 public:
  /// Throws InvalidInput when the body has no contact definition.
  ShapeOracle(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost);
  /// The cost of `definition` (make_cost); a state it needs at the initial design stays cached,
  /// so the optimizer's first evaluation does not solve it again.
  ShapeOracle(ElasticBody& body, const CostDefinition& definition);

  /// Solves the state at α (throws InvalidInput for an inverting design), evaluates the cost
  /// and, if requested, the default piece's subgradient. Cached: the same α returns the same
  /// Evaluation without solving again.
  const Evaluation& evaluate_design(const Eigen::Ref<const Eigen::VectorXd>& alpha, bool with_subgradient = true);
  /// The cached evaluation at α, or nullptr (never solves).
  const Evaluation* find_evaluation(const Eigen::Ref<const Eigen::VectorXd>& alpha) const;
  /// optim::Oracle: a failed or inverting evaluation reports "could not evaluate here".
  [[nodiscard]] optim::OracleResult evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) override;

  /// The adjoint results (ξ_i and each solve's status: a singular piece is kNumericalFailure) for
  /// the given pieces at α (the state is re-solved if α is not the cached design).
  std::vector<sensitivity::AdjointSensitivity::Result> subgradients(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                                    const std::vector<sensitivity::Piece>& pieces);
  /// R_i h: the derivative of the state of `piece` at α along h (default piece when null).
  sensitivity::AdjointSensitivity::StateDerivative state_derivative(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                                    const Eigen::Ref<const Eigen::VectorXd>& h,
                                                                    const sensitivity::Piece* piece = nullptr);
  /// The index sets and 𝕃 at α (with load cases: of the selected case).
  sensitivity::PieceEnumeration pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int cap = 256);

  /// The history of a cost along a loading program (null: the static problem). With it, the
  /// state, pieces() and subgradients() are those of the step the cost reads (the last for the
  /// dissipation), the other steps keeping their default pieces; pieces()' cardinality is that of
  /// the whole history (the product over the steps). state_derivative() is not available.
  ProgramHistory* history() { return history_.get(); }
  const ProgramHistory* history() const { return history_.get(); }
  /// The warm starts of the loading programs' steps (the history's, or every load case's in
  /// order), which the body's own warm start does not hold; empty for the static problem. For
  /// checkpoints: set_history_warm_starts restores them (InvalidInput for another count).
  std::vector<std::optional<contact::ContactState>> history_warm_starts() const;
  void set_history_warm_starts(const std::vector<std::optional<contact::ContactState>>& states);
  /// The load cases of the cost definition (null: the case file's own loads). Each case is solved
  /// as a loading program — its own [[load_case.step]] tables, or one step with its scales (the
  /// static load) — on the one factorization of A(α) (study/history.hpp); "case k's state" below
  /// is the state its cost reads (its program's cost step).
  const LoadCases* load_cases() const { return cases_.get(); }
  /// Load cases: case k's history, solved at α.
  ProgramHistory& case_history(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k);
  /// Load cases: ξ_i of J_k (case k's own cost, unweighted) for the given pieces of case k's cost
  /// step at α (its other steps at their default pieces).
  std::vector<sensitivity::AdjointSensitivity::Result> case_subgradients(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                                         int k,
                                                                         const std::vector<sensitivity::Piece>& pieces);
  /// Load cases: 𝕃 of case k's cost step at α (the cardinality that of its whole history).
  sensitivity::PieceEnumeration case_pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k, int cap = 256);
  /// Load cases: the index sets of case k's state at α.
  const sensitivity::IndexSets& case_index_sets(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k);
  /// Load cases: case k's state at α (solved now if α is not the last solved design).
  const BodyState& case_state(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k);
  /// Load cases: makes case k's state at α the last_state() (and the one pieces() and
  /// subgradients() read), e.g. for certify's (MF1′) of each active case.
  void select_case(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k);

  const ElasticBody& body() const { return body_; }
  /// The cost (with load cases: that of case 0; each case has its own when a target is initial_mean).
  const cost::CostFunctional& cost() const {
    return cost_ ? *cost_ : history_ ? history_->cost() : case_histories_.front()->cost();
  }
  /// The state of the last solved design.
  const BodyState& last_state() const { return *state_; }
  /// The state at α for output (VTK, reports): one of the last kRecentStates solved states when
  /// α is among them — without its Delassus operator unless it is the last — else solved now.
  const BodyState& state(const Eigen::Ref<const Eigen::VectorXd>& alpha);
  static constexpr std::size_t kRecentStates = 8;
  int num_state_solves() const { return state_solves_; }
  /// Worst-case load cases: whether an evaluation with subgradient also returns the cuts of the
  /// other cases (Evaluation::case_cuts: K − 1 further adjoints on the same factorization), which
  /// the bundle method models the max with (docs/theory/load-cases.md §2). Default on.
  void set_case_cuts(bool on) { case_cuts_ = on; }

 private:
  void solve_state(const Eigen::VectorXd& alpha);
  void solve_cases(const Eigen::VectorXd& alpha);
  void remember(std::shared_ptr<BodyState> state, const Eigen::VectorXd& alpha);
  sensitivity::CostPartials partials() const;
  void evaluate_cases(Evaluation& e, bool with_subgradient);
  void evaluate_history(Evaluation& e, bool with_subgradient);

  ElasticBody& body_;
  std::unique_ptr<cost::CostFunctional> cost_;
  Eigen::MatrixXd gap_matrix_;  // B̃ at the contact nodes
  std::shared_ptr<BodyState> state_;  // the last solved design (the body's factorization is of it)
  Eigen::VectorXd state_alpha_;
  std::deque<std::shared_ptr<BodyState>> recent_;  // newest first, state_ included
  std::map<std::vector<double>, Evaluation> cache_;
  int state_solves_ = 0;
  // Load cases: their definitions and combination, one history per case (each with
  // its cost, its states at state_alpha_ and its own warm starts; state_ is the selected case's).
  std::unique_ptr<LoadCases> cases_;
  std::vector<std::unique_ptr<ProgramHistory>> case_histories_;
  int selected_ = 0;
  int last_factorizations_ = 0;
  bool case_cuts_ = true;
  std::unique_ptr<ProgramHistory> history_;  // a cost along a loading program
};

}  // namespace frictopt::study
