// SPDX-License-Identifier: MIT
// Contact with given (Tresca) friction in its dual form (docs/theory/state-problem.md §3, §5):
//   min ½ zᵀMz + zᵀc  s.t.  λ_i >= 0,  q_i ∈ s_i·W_i,
// solved by Dostál's MPGP over the product of the per-node sets, or by a split variant that
// alternates MPRGP on the normal forces with MPGP on the tangential forces
// (docs/theory/state-problem.md §6).
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/core/status.hpp"

namespace frictopt::contact {

/// Which QP algorithm the Tresca solver runs.
enum class TrescaAlgorithm {
  kAutomatic,  ///< currently always kJointMpgp (the faster variant on every benchmark)
  kJointMpgp,  ///< MPGP over the joint product set {λ >= 0} × Π s_i·W_i
  kSplit       ///< block Gauss–Seidel: tangential MPGP (λ fixed) ⇄ normal MPRGP (q fixed)
};
/// "automatic", "joint_mpgp", "split".
std::string_view to_string(TrescaAlgorithm algorithm);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
TrescaAlgorithm parse_tresca_algorithm(std::string_view text);

/// Solver of the dual Tresca QP for one Delassus operator M and friction laws W_i.
///
/// Unknowns z ∈ R^{dim·p} node-interleaved (q_i, λ_i) (ContactState). With G = per-node rows
/// (−T_i; N_i), M = G A⁻¹ Gᵀ and c = G A⁻¹ l + (0, g): ∇ = Mz + c = (−u_t^i, u_ν^i + g_i),
/// so the KKT conditions are non-penetration/complementarity in the normal direction and
/// q_i ∈ s_i ∂N_W(u_t^i) (maximal dissipation) in the tangential one.
///
/// `delassus` must outlive the solver. The constructor estimates ‖M‖ by power iteration
/// (Options::norm_estimate_iterations applies of M). solve() is const and may be called from
/// several threads only if `delassus.apply` is thread-safe.
class TrescaSolver {
 public:
  struct Options {
    /// Stop when ‖g̃_ᾱ(z)‖₂ <= relative_tolerance·‖c‖₂, with the reduced projected gradient
    /// g̃_ᾱ(z) = (z − P(z − ᾱ∇))/ᾱ (Dostál 2009, §5.3 and Dostál–Kozubek 2012). The default
    /// is tight because the sensitivity analysis classifies nodes by exact equalities
    /// (docs/theory/state-problem.md §6). In (0, 1).
    double relative_tolerance = 1e-10;
    /// Cap on the QP iterations (CG + expansion + proportioning steps, summed over the split
    /// variant's inner solves). >= 1.
    int max_iterations = 20000;
    /// Algorithm (given); Summary::algorithm_used says what ran.
    TrescaAlgorithm algorithm = TrescaAlgorithm::kAutomatic;
    /// Γ > 0 of the proportioning test ‖β̃‖² <= Γ² φ̃ᵀφ. Γ = 1 is Dostál's recommended
    /// default (Dostál, Optimal Quadratic Programming Algorithms, Springer 2009, §5.8).
    double proportioning_gamma = 1.0;
    /// ᾱ = step_length_factor / ‖M‖_est for expansion (and MPGP proportioning) steps; the
    /// theory needs ᾱ ∈ (0, 2/‖M‖]; 1.9 is the value used by Dostál et al. In (0, 2].
    double step_length_factor = 1.9;
    /// Power iterations for ‖M‖ (from a fixed non-symmetric start vector). >= 1.
    int norm_estimate_iterations = 30;
    /// ‖M‖_est = norm_safety_factor · (power-iteration value), which is a lower bound of ‖M‖;
    /// the margin keeps ᾱ <= 2/‖M‖ when the estimate has not converged. >= 1.
    double norm_safety_factor = 1.05;
    /// Split variant: cap on the outer (block Gauss–Seidel) sweeps. >= 1.
    int max_split_sweeps = 1000;
    /// ε_cl of the node classification (docs/theory/sensitivity.md §3); must exceed the relative
    /// KKT residual.
    double classification_tolerance = 1e-8;
    /// Throws InvalidInput naming the field, its value and the expectation.
    void validate() const;
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "solve() has not been called";
    int iterations = 0;               ///< all QP steps
    int cg_steps = 0;
    int expansion_steps = 0;
    int proportioning_steps = 0;
    int split_sweeps = 0;             ///< outer sweeps of the split variant (0 for joint)
    int operator_applications = 0;    ///< applies of M in this solve (not the norm estimate)
    double relative_projected_gradient = kNaN;  ///< ‖g̃_ᾱ(z)‖/‖c‖ at exit (stopping quantity)
    double kkt_residual = kNaN;        ///< ContactResiduals::kkt_residual at exit
    double complementarity_gap = kNaN; ///< ContactResiduals::complementarity_gap at exit
    double objective = kNaN;           ///< ½zᵀMz + zᵀc at exit
    double time_seconds = 0.0;
    TrescaAlgorithm algorithm_given = TrescaAlgorithm::kAutomatic;
    TrescaAlgorithm algorithm_used = TrescaAlgorithm::kAutomatic;
    bool converged() const { return status == Status::kConverged; }
    /// One line for logs and the CLI.
    std::string brief_report() const;
  };

  /// One law for every node. Throws InvalidInput if M.size() is not a multiple of law.dim()
  /// or the options are invalid.
  TrescaSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law, Options options);
  TrescaSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law);
  /// One law per node (laws.size() = p = M.size()/dim), all of the same dimension.
  TrescaSolver(const linalg::LinearOperator& delassus, std::vector<FrictionLaw> laws, Options options);

  /// Solves the QP for linear term `c` (size dim·p) and slip bounds `slip_bound` (size p,
  /// >= 0; throws InvalidInput otherwise). Warm start: if state.z has size dim·p it is the
  /// initial guess (projected onto the feasible set first); otherwise the solve starts at 0.
  /// On return state.z, state.gradient (fresh Mz + c), state.slip_bound, state.nodes are set.
  [[nodiscard]] Summary solve(const Eigen::Ref<const Eigen::VectorXd>& c,
                              const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                              ContactState& state) const;

  /// As solve(), with the stopping tolerance `relative_tolerance` in (0, 1) instead of
  /// Options::relative_tolerance (used by the Coulomb fixed point to tighten as it converges).
  [[nodiscard]] Summary solve_to(const Eigen::Ref<const Eigen::VectorXd>& c,
                                 const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                 ContactState& state, double relative_tolerance) const;

  /// Which block solve_block() minimizes over.
  enum class Block {
    kTangential,  ///< step (I) of docs/theory/state-problem.md §6: q ∈ s·W with λ fixed (MPGP)
    kNormal       ///< step (II) of docs/theory/state-problem.md §6: λ >= 0 with q fixed (MPRGP)
  };
  /// Minimizes the QP over one block with the other fixed at state.z (which must have size
  /// dim·p), to ‖g̃_ᾱ‖ <= relative_tolerance·‖c‖ on that block. The split Coulomb method.
  [[nodiscard]] Summary solve_block(Block block, const Eigen::Ref<const Eigen::VectorXd>& c,
                                    const Eigen::Ref<const Eigen::VectorXd>& slip_bound,
                                    ContactState& state, double relative_tolerance) const;

  int dim() const { return dim_; }
  Eigen::Index num_nodes() const { return num_nodes_; }
  const Options& options() const { return options_; }
  const std::vector<FrictionLaw>& laws() const { return laws_; }
  const linalg::LinearOperator& delassus() const { return delassus_; }
  /// ‖M‖_est (with the safety factor) and ᾱ = step_length_factor/‖M‖_est.
  double operator_norm_estimate() const { return norm_estimate_; }
  double step_length() const { return alpha_bar_; }

 private:
  Summary solve_impl(const Eigen::Ref<const Eigen::VectorXd>& c,
                     const Eigen::Ref<const Eigen::VectorXd>& slip_bound, ContactState& state,
                     double relative_tolerance, int part) const;

  const linalg::LinearOperator& delassus_;
  std::vector<FrictionLaw> laws_;
  Options options_;
  int dim_ = 3;
  Eigen::Index num_nodes_ = 0;
  double norm_estimate_ = kNaN;
  double alpha_bar_ = kNaN;
};

}  // namespace frictopt::contact
