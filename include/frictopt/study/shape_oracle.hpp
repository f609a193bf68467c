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
/// contact and a cost. Every evaluation is one path: a cost over K >= 1 loading histories
/// (ProgramHistory), combined by the load cases (docs/theory/load-cases.md) — the static problem is
/// K = 1 history of one step (the case file's loads), a cost along a loading program K = 1 history
/// of its steps, load cases K histories (each case's program, or one step with its scales), all
/// on the one factorization of A(α).
/// With [design] friction_orientation every "α" below is the optimizer's x =
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
  /// the given pieces of the selected history's cost step at α (its other steps at their default
  /// pieces; the state is re-solved if α is not the cached design).
  std::vector<sensitivity::AdjointSensitivity::Result> subgradients(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                                    const std::vector<sensitivity::Piece>& pieces);
  /// R_i h: the derivative of the state of `piece` at α along h (default piece when null); the
  /// static problem only (InvalidInput otherwise).
  sensitivity::AdjointSensitivity::StateDerivative state_derivative(const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                                                    const Eigen::Ref<const Eigen::VectorXd>& h,
                                                                    const sensitivity::Piece* piece = nullptr);
  /// 𝕃 of the selected history's cost step at α, with the cardinality of its whole history.
  sensitivity::PieceEnumeration pieces(const Eigen::Ref<const Eigen::VectorXd>& alpha, int cap = 256);

  /// The K histories: load case k's (k in [0, K)), or the one history without load cases (k = 0),
  /// solved at α. "Case k's state" is the state its cost reads (its program's cost step).
  ProgramHistory& program(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k = 0);
  int num_programs() const { return static_cast<int>(programs_.size()); }
  /// The history of a cost along a loading program ([[program.step]] tables); null for the static
  /// problem and for load cases.
  ProgramHistory* history() { return has_program_history() ? programs_.front().get() : nullptr; }
  const ProgramHistory* history() const { return has_program_history() ? programs_.front().get() : nullptr; }
  /// The warm starts of the loading programs' steps (every history's in order), which the body's
  /// own warm start does not hold; empty for the static problem. For checkpoints:
  /// set_history_warm_starts restores them (InvalidInput for another count).
  std::vector<std::optional<contact::ContactState>> history_warm_starts() const;
  void set_history_warm_starts(const std::vector<std::optional<contact::ContactState>>& states);
  /// The load cases of the cost definition (null: the case file's own loads, or its program).
  const LoadCases* load_cases() const { return cases_.get(); }
  /// Load cases: makes case k's state at α the last_state() (and the one pieces() and
  /// subgradients() read), e.g. for certify's (MF1′) of each active case.
  void select_case(const Eigen::Ref<const Eigen::VectorXd>& alpha, int k);

  const ElasticBody& body() const { return body_; }
  /// The cost (with load cases: that of case 0; each case has its own when a target is initial_mean).
  const cost::CostFunctional& cost() const { return programs_.front()->cost(); }
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
  bool has_program_history() const { return !cases_ && !programs_.front()->is_static_problem(); }
  void solve_state(const Eigen::VectorXd& alpha);
  void remember(std::shared_ptr<BodyState> state, const Eigen::VectorXd& alpha);
  /// "load case "name": " (or "loading program: " for `state_failure` of a program, "" for the
  /// static problem) before a failure's message.
  std::string failure_prefix(int k, bool state_failure) const;
  void add_subgradient(Evaluation& e, int selected);

  ElasticBody& body_;
  Eigen::MatrixXd gap_matrix_;  // B̃ at the contact nodes
  // The K histories (K >= 1) and, with load cases, their definitions and combination (null: one
  // history, Θ = its J). Each history has its cost, its states at state_alpha_ and its own warm
  // starts; state_ is the selected history's cost state.
  std::unique_ptr<LoadCases> cases_;
  std::vector<std::unique_ptr<ProgramHistory>> programs_;
  std::shared_ptr<BodyState> state_;  // the last solved design (the body's factorization is of it)
  Eigen::VectorXd state_alpha_;
  std::deque<std::shared_ptr<BodyState>> recent_;  // newest first, state_ included
  std::map<std::vector<double>, Evaluation> cache_;
  int state_solves_ = 0;
  int selected_ = 0;
  int last_factorizations_ = 0;
  bool case_cuts_ = true;
};

}  // namespace frictopt::study
