// SPDX-License-Identifier: MIT
// Coulomb friction as a fixed point over given-friction (Tresca) problems
// (docs/theory/state-problem.md §6; thesis §5.1, §6.1.3): the slip bound s ← λ (the coefficient μ
// is absorbed in the friction set W), each step a warm-started dual QP; and the split variant of
// docs/theory/state-problem.md §6 (steps I/II alternating; thesis §5.1).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/contact/contact_state.hpp"
#include "frictopt/contact/friction_law.hpp"
#include "frictopt/linalg/linear_operator.hpp"
#include "frictopt/contact/tresca_solver.hpp"
#include "frictopt/core/status.hpp"

namespace frictopt::contact {

/// How the Coulomb problem is solved (docs/theory/state-problem.md §6; docs/contact.md,
/// "Semismooth Newton").
enum class CoulombMethod {
  kFixedPoint,  ///< s_{k+1} = λ(s_k): a full Tresca QP per step (thesis §5.1, §6.1.3)
  kSplit,       ///< thesis §5.1: per step one tangential solve (I) and one normal solve (II)
  /// Semismooth Newton on the Alart–Curnier function: of the condensed dual problem in
  /// CoulombSolver (SemismoothNewtonCoulombSolver), of the displacements in the PETSc engine
  /// (docs/petsc-engine.md).
  kSemismoothNewton,
  /// The fixed point, handed over to the semismooth Newton method when the problem is large
  /// (NewtonOptions::automatic_min_unknowns) and the fixed point has used
  /// NewtonOptions::automatic_applications_per_unknown · m products with M without converging.
  kAutomatic
};
/// "fixed_point", "split", "semismooth_newton", "automatic".
std::string_view to_string(CoulombMethod method);
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
CoulombMethod parse_coulomb_method(std::string_view text);

/// What the callback sees after each fixed-point iteration.
struct CoulombIterationSummary {
  int iteration = 0;                 ///< 1-based
  double relative_increment = kNaN;  ///< ‖s_{k+1} − s_k‖ / ‖s_k‖ (∞ when s_k = 0 ≠ s_{k+1})
  int qp_iterations = 0;             ///< QP steps of this iteration
  Status qp_status = Status::kNotRun;
};
/// Called after every fixed-point iteration; returning kStop ends the solve with
/// Status::kStoppedByCallback.
using CoulombIterationCallback = std::function<CallbackResult(const CoulombIterationSummary&)>;

/// Solver of the discrete Coulomb problem q_i ∈ λ_i ∂N_W(u_t^i), λ ⟂ u_ν + g >= 0, in the dual
/// variables of TrescaSolver (whose Options it carries). `delassus` must outlive the solver.
class CoulombSolver {
 public:
  struct Options {
    /// Stop when ‖s_{k+1} − s_k‖₂ <= relative_tolerance·‖s_k‖₂ (s_k = 0 = s_{k+1} counts as
    /// converged: no contact anywhere). Split method: the increment of (q, λ) relative to
    /// ‖(q, λ)‖. In (0, 1).
    double relative_tolerance = 1e-10;
    /// Cap on fixed-point iterations. >= 1.
    int max_iterations = 50;
    /// ω ∈ (0, 1]: s_{k+1} = (1 − ω) s_k + ω λ(s_k). ω = 1 is plain successive approximation.
    double relaxation = 1.0;
    CoulombMethod method = CoulombMethod::kAutomatic;
    /// The semismooth Newton method (kSemismoothNewton, kAutomatic; docs/contact.md,
    /// "Semismooth Newton").
    struct NewtonOptions {
      /// Cap on Newton steps before the fallback to the fixed point. >= 1.
      int max_iterations = 60;
      /// Up to this many contact unknowns each Newton step is solved by a dense LU in double
      /// precision; above, by GMRES preconditioned with a single-precision LU of a recent
      /// Jacobian. >= 0.
      Eigen::Index direct_max_unknowns = 600;
      /// GMRES iterations after which the preconditioner is refactorized at the current
      /// Jacobian (the Jacobian of the last factorization then differs too much). An LU costs
      /// about m/6 GMRES iterations (2m³/3 against ≈ 4m² flops), so an old preconditioner is
      /// kept for long. >= 1.
      int gmres_max_iterations = 100;
      /// kAutomatic hands over to Newton only from this many contact unknowns (below, the fixed
      /// point's products cost microseconds). >= 0.
      Eigen::Index automatic_min_unknowns = 3000;
      /// kAutomatic hands over once the fixed point has used this many products with M per
      /// contact unknown without converging: m/10 products take about as long as the whole
      /// Newton solve (one or two LUs and ≈ 150 products, docs/contact.md "Semismooth Newton":
      /// measured break-even; m/3 cost 2× more on the slip-heavy states there). > 0.
      double automatic_applications_per_unknown = 0.1;
      /// When Newton does not converge, solve by the fixed point instead (reported in the
      /// summary's message and `fallback`); otherwise its status is returned.
      bool fallback_to_fixed_point = true;
    };
    NewtonOptions newton;
    /// kDiverged when the increment grows in this many consecutive iterations. >= 2.
    int divergence_window = 5;
    /// Inner QP solver. Its relative_tolerance is the floor of the adaptive inner tolerance:
    /// iteration k solves to max(floor, min(1e-6, 1e-2·(last relative increment))), so early
    /// iterations are cheap and the final ones are as accurate as a standalone Tresca solve.
    TrescaSolver::Options tresca;
    /// Optional observer.
    CoulombIterationCallback on_iteration;
    /// Throws InvalidInput naming the field, its value and the expectation (also for `tresca`).
    void validate() const;
  };

  struct Summary {
    Status status = Status::kNotRun;
    std::string message = "solve() has not been called";
    int iterations = 0;                 ///< fixed-point iterations
    int qp_iterations = 0;              ///< QP steps summed over all inner solves
    int operator_applications = 0;      ///< applies of M (not counting the norm estimate)
    int inner_not_converged = 0;        ///< inner solves that stopped on their iteration cap
    double last_relative_increment = kNaN;
    double kkt_residual = kNaN;         ///< ContactResiduals with s = λ (Coulomb conditions)
    double complementarity_gap = kNaN;  ///< idem
    double time_seconds = 0.0;
    CoulombMethod method_given = CoulombMethod::kFixedPoint;
    /// What produced the solution: kSemismoothNewton when Newton converged (after the fixed
    /// point's first iterations with kAutomatic), the fixed point otherwise (also after a
    /// fallback).
    CoulombMethod method_used = CoulombMethod::kFixedPoint;
    int newton_iterations = 0;          ///< semismooth Newton steps (0 without Newton)
    int linear_iterations = 0;          ///< GMRES iterations (or direct solves) of the Newton steps
    int factorizations = 0;             ///< LU factorizations of Newton Jacobians
    bool fallback = false;              ///< Newton failed and the fixed point solved instead
    /// ‖g̃_ᾱ(z)‖/‖c‖ of the Tresca QP with s = λ at exit: the fixed point's inner stopping
    /// quantity (TrescaSolver::Options::relative_tolerance), Newton's stopping quantity.
    double relative_projected_gradient = kNaN;
    bool converged() const { return status == Status::kConverged; }
    std::string brief_report() const;
  };

  /// One friction law for all nodes (W includes μ). Throws InvalidInput on bad options or
  /// sizes; estimates ‖M‖ once (TrescaSolver).
  CoulombSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law, Options options);
  CoulombSolver(const linalg::LinearOperator& delassus, const FrictionLaw& law);
  /// One law per node.
  CoulombSolver(const linalg::LinearOperator& delassus, std::vector<FrictionLaw> laws, Options options);

  /// Solves for the linear term c (size dim·p). Warm start: if state.z has size dim·p the
  /// fixed point starts from s_0 = λ(state.z) and z = state.z; otherwise from the frictionless
  /// problem (s_0 = 0). On return `state` holds z, ∇ = Mz + c, slip_bound = λ and the node
  /// classification.
  [[nodiscard]] Summary solve(const Eigen::Ref<const Eigen::VectorXd>& c, ContactState& state) const;

  /// What every method's result gets (state.z and state.gradient = Mz + c set): slip_bound = λ,
  /// the Coulomb residuals, the projected gradient at s = λ, the node classification and the
  /// message of summary.status.
  void finish(const Eigen::VectorXd& c, ContactState& state, Summary& summary) const;

  const TrescaSolver& tresca() const { return tresca_; }
  const Options& options() const { return options_; }

 private:
  /// `application_budget` > 0: stop (status kMaxIterations) once that many products with M
  /// are used without converging (the handover of kAutomatic).
  Summary solve_fixed_point(const Eigen::VectorXd& c, ContactState& state, long application_budget = 0) const;
  Summary solve_automatic(const Eigen::VectorXd& c, ContactState& state) const;

  Summary solve_split(const Eigen::VectorXd& c, ContactState& state) const;
  double inner_tolerance(double last_increment) const;

  Options options_;
  TrescaSolver tresca_;
};

/// Quasi-static (incremental) Coulomb friction (docs/theory/loading-program.md §2):
/// at step k the friction law acts on the slip increment u_t − u_t^{k−1}, so the dual QP of
/// step k has the same M and the linear term c with its tangential blocks shifted by the
/// previous tangential displacement, c_q^k = c_q + u_t^{k−1}; then ∇_q = Mz + c = −(u_t − u_t^{k−1})
/// and every solver and classification below reads the increment as "the slip". Returns that c.
/// `previous_tangential` has (dim−1)·p entries, node-interleaved as q. Throws InvalidInput on a
/// size mismatch.
[[nodiscard]] Eigen::VectorXd shift_by_previous_slip(const Eigen::Ref<const Eigen::VectorXd>& c,
                                                     const Eigen::Ref<const Eigen::VectorXd>& previous_tangential,
                                                     int dim);

/// The frictionless law W = {0} of dimension dim (2: interval [0, 0], 3: disc of radius 0), for
/// a frictionless load step (e.g. Cattaneo–Mindlin's normal loading).
[[nodiscard]] FrictionLaw frictionless_law(int dim);

}  // namespace frictopt::contact
