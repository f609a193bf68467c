// SPDX-License-Identifier: MIT
// Costs along a loading history (docs/theory/history-adjoint.md): the steps of
// a loading program at one design on one factorization, a cost that reads the state after one
// step (any cost kind but the compliance) or the whole history (the friction dissipation), and
// one element ξ of its pseudodifferential by an adjoint run backward over the steps, each step
// with its own index-set piece. The static problem (the case file's own loads) is the one-step
// special case: every evaluation of the shape oracle is a cost over K >= 1 such histories.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/index_sets.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/load_cases.hpp"
#include "frictopt/study/loading_program.hpp"

namespace frictopt::study {

/// The result of one backward adjoint run.
struct HistorySubgradient {
  Eigen::VectorXd subgradient;        ///< ξ (d; d + 1 with the friction orientation: ∂Θ/∂s last)
  Eigen::VectorXd friction_gradient;  ///< Σ_k over the friction steps of ∂Θ/∂p (friction_parameters(law))
  /// The worst step's adjoint summary (the failed one, else the smallest reciprocal condition).
  sensitivity::AdjointSensitivity::Summary summary;
  /// ψ_z^k and ψ_u^k (free DOFs) per step (for tests and reports).
  std::vector<Eigen::VectorXd> psi_z, psi_u;
};

/// A loading program with a cost on its history, at one design at a time — or the static problem,
/// its one-step special case. Lifetime: `body` must outlive this object; not thread-safe (the
/// body's factorization is reused).
///
/// The static problem (no [[program.step]] tables: one step with the case file's loads) keeps the
/// static path inside: its state is ElasticBody::solve's (warm-started by the body itself, so it
/// has no warm_starts() of its own), its subgradients the state engine's (the PETSc engine's too),
/// and it alone offers state_derivative(). A one-step program through the general path gives the
/// same numbers to round-off (1e-14), this path the same bits as before the histories existed.
class ProgramHistory {
 public:
  /// `definition.program` must be set. Throws InvalidInput for the compliance (it reads the case
  /// file's own loads, not a step's), a step out of [0, K] (0 = last), a program that does not
  /// fit the body, or a body without contact. An "initial_mean" target is that of the state the
  /// cost reads (the chosen step) at the initial design, which is solved here. `where` names the
  /// program's tables in messages: "program" ([[program.step]]) or "load_case[k]" (a load
  /// case's own program; ShapeOracle holds one history per load case).
  /// Without `definition.program`: the static problem (cost.step must be 0; the cost may be the
  /// compliance).
  ProgramHistory(ElasticBody& body, const CostDefinition& definition, Eigen::MatrixXd gap_matrix,
                 std::string_view where = "program");
  /// The static problem with a given cost.
  ProgramHistory(ElasticBody& body, std::unique_ptr<cost::CostFunctional> cost, Eigen::MatrixXd gap_matrix);

  /// True for the static problem (the case file's own loads, one step; see the class comment).
  bool is_static_problem() const { return static_problem_; }
  int num_steps() const { return static_problem_ ? 1 : static_cast<int>(program_.steps.size()); }
  /// The contact state each step's next solve starts from (one per step; empty: a cold start),
  /// for a checkpoint: a resumed run continues them so that it repeats the uninterrupted run.
  /// None for the static problem, whose warm start is the body's own.
  const std::vector<std::optional<contact::ContactState>>& warm_starts() const { return warm_starts_; }
  /// Restores warm_starts(); `states` must have warm_starts().size() entries (InvalidInput otherwise).
  void set_warm_starts(std::vector<std::optional<contact::ContactState>> states);
  /// 0-based index of the step whose state the cost reads (the last for the dissipation).
  int cost_step() const { return cost_step_; }
  bool dissipation() const { return dissipation_; }
  /// The cost's name ("dissipation" or the step cost's).
  std::string name() const;
  /// The step cost; for the dissipation a functional that only names it (its evaluate() throws:
  /// the dissipation reads every step, value() and subgradient() compute it).
  const cost::CostFunctional& cost() const { return *step_cost_; }

  /// Solves every step at α from the unloaded body (u⁰ = 0), each warm-started from its own last
  /// converged contact state; the first step factorizes A(α), the others reuse it. Stops at the
  /// first step that does not converge. Throws InvalidInput for an inverting α.
  void solve(const Eigen::Ref<const Eigen::VectorXd>& alpha);
  const Eigen::VectorXd& alpha() const { return alpha_; }
  /// True when every step of the last solve converged.
  bool ok() const { return ok_; }
  /// Why not ok ("step k: ...").
  const std::string& message() const { return message_; }
  /// Step k's state (0-based) of the last solve; null after a failed step.
  const std::shared_ptr<BodyState>& state(int k) const { return states_[static_cast<std::size_t>(k)]; }
  /// The state the cost reads (cost_step()'s); after a failed step before it, that failed step's
  /// state (whose summary says why). Needs solve().
  std::shared_ptr<BodyState> cost_state() const;
  /// Numeric factorizations of A in the last solve (0 when the body's factorization at α was
  /// already there, e.g. from another load case's program at the same design).
  int factorizations() const { return factorizations_; }
  /// The law step k was solved with (its state's: the case's, turned to the design's orientation
  /// with friction_orientation, or W = {0} for a frictionless step); step k must be solved.
  const contact::FrictionLaw& law(int k) const;

  /// J at the solved states (needs ok()).
  double value() const;
  /// The index sets of step k (classified with that step's law; cached per solve).
  const sensitivity::IndexSets& index_sets(int k);
  /// The index sets of the cost step.
  const sensitivity::IndexSets& cost_step_index_sets() { return index_sets(cost_step_); }
  /// 𝕃 of step k.
  sensitivity::PieceEnumeration pieces(int k, int cap);
  /// Every step's default piece.
  std::vector<sensitivity::Piece> default_pieces();
  /// |𝕃| of the history: the product over the steps of |𝕃_k|.
  double cardinality();
  /// 𝕃 of the cost step, with the cardinality of the whole history (sampled when another step has
  /// a choice too): the pieces a caller varies when it sees one state (ShapeOracle::pieces).
  sensitivity::PieceEnumeration cost_step_pieces(int cap);
  /// ξ for each given piece of the cost step, every other step at its default piece.
  std::vector<sensitivity::AdjointSensitivity::Result> cost_step_subgradients(
      const std::vector<sensitivity::Piece>& pieces);

  /// ξ for one piece per step (size K) by the backward adjoint. `coupled = false` drops the
  /// steps' coupling through the slip reference (−S_{k+1} E_t G): a deliberately wrong ξ that the
  /// tests use to show the coupling matters.
  [[nodiscard]] HistorySubgradient subgradient(const std::vector<sensitivity::Piece>& pieces, bool coupled = true);

  /// The static problem: R h, the derivative of its state along h for `piece` (the default piece
  /// when null). Throws InvalidInput for a program (a step's state derivative depends on the
  /// earlier steps').
  [[nodiscard]] sensitivity::AdjointSensitivity::StateDerivative state_derivative(
      const Eigen::Ref<const Eigen::VectorXd>& h, const sensitivity::Piece* piece = nullptr);

 private:
  void solve_static(const Eigen::Ref<const Eigen::VectorXd>& alpha);
  void prepare_static(const CostDefinition* definition);
  /// The cost's partials per step at the solved states (cached per solve).
  const std::vector<sensitivity::CostPartials>& partials() const;

  ElasticBody& body_;
  bool static_problem_ = false;
  LoadingProgramDefinition program_;
  Eigen::MatrixXd gap_matrix_;
  int cost_step_ = 0;
  bool dissipation_ = false;
  std::unique_ptr<cost::CostFunctional> step_cost_;
  // Step k's scales carried over (empty lists keep the previous step's), as one "load case" per
  // step: LoadCases gives the shape derivative of a step's traction change.
  std::unique_ptr<LoadCases> step_loads_;
  Eigen::VectorXd alpha_;
  bool ok_ = false;
  std::string message_ = "solve() has not been called";
  int factorizations_ = 0;
  std::vector<std::shared_ptr<BodyState>> states_;
  std::vector<Eigen::VectorXd> tangential_;  // u_t^k of the contact nodes, k = 0..K (u_t^0 = 0)
  std::vector<std::optional<contact::ContactState>> warm_starts_;
  std::vector<std::optional<sensitivity::IndexSets>> sets_;
  mutable std::optional<std::vector<sensitivity::CostPartials>> partials_;
};

}  // namespace frictopt::study
