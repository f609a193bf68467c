// SPDX-License-Identifier: MIT
// The optimality certificate of a design (thesis §5.3; docs/theory/stationarity.md): index
// sets, the pieces 𝕃 and their ξ_i, the Clarke stationarity distance, condition (MF1′) and the
// extreme-point (Mordukhovich) check.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/optim/stationarity.hpp"
#include "frictopt/sensitivity/index_sets.hpp"
#include "frictopt/study/shape_oracle.hpp"

namespace frictopt::study {

struct CertifyOptions {
  // Largest |𝕃| enumerated in full; above it a seeded sample of `cap` pieces (default piece
  // first) is used and the Mordukhovich check is skipped (docs/theory/sensitivity.md §4; the thesis
  // met 59049). >= 1.
  int cap = 4096;
  // A row of Υ is active when its slack is <= active_tolerance·max(1, |rhs|)
  // (docs/theory/stationarity.md §2). >= 0.
  double active_tolerance = 1e-8;
  // Numerical rank of the (MF1′) matrix: singular values > rank_tolerance·σ_max count, after
  // scaling rows and columns to unit 2-norm (docs/theory/stationarity.md §3). In (0, 1).
  double rank_tolerance = 1e-10;
  // ξ_i is an extreme point of conv{ξ_j} when dist(ξ_i, conv{ξ_j : ξ_j ≠ ξ_i}) >
  // extreme_tolerance·max_j‖ξ_j‖ (docs/theory/stationarity.md §4, step 1, with a margin for the
  // QP's accuracy). > 0.
  double extreme_tolerance = 1e-8;
  // The extreme-point test costs one QP over the other generators per distinct ξ_i; above this
  // many distinct ξ_i it is skipped (reported, not an error). >= 1.
  int max_extreme_point_tests = 1024;
  // Distances δ ≤ stationary_tolerance·max_i‖ξ_i‖ are reported as "stationary" (the thesis gives
  // no tolerance; docs/theory/examples.md §4 item 3 — read δ against its scale). > 0.
  double stationary_tolerance = 1e-3;
  // Compute the Clarke distance only, without (MF1′) and the extreme-point test: the final
  // check of study::optimize, which needs the distance alone (a study run that says
  // "converged" must pass this certificate).
  bool clarke_only = false;
  // Load cases, combine = "worst": case k is active when w_k J_k >= Θ −
  // case_active_tolerance·|Θ|; the generators are those of every active case (docs/theory/
  // load-cases.md: the ε-active reading, since an optimizer stops near, not at, a tie). >= 0.
  double case_active_tolerance = 1e-3;
  // A sampled (Goldstein-type) certificate in addition to the exact one (0: none): the generators
  // at α together with ξ(y_j) at `samples` admissible designs y_j with ‖y_j − α‖ ≤ sample_radius
  // (design units, m; docs/theory/stationarity.md, "Sampled certificate"). >= 0, finite.
  double sample_radius = 0.0;
  // Designs sampled when sample_radius > 0; 0 means 10(d + 1) for d design variables (more than
  // gradient sampling's usual 2d: the cells of the pieces next to a stick/slip change are thin,
  // and 2(d + 1) samples often miss one; docs/theory/stationarity.md). >= 0.
  int samples = 0;
  void validate() const;  // throws InvalidInput naming field, value, expectation
};

/// The sampled (Goldstein-type) certificate: dist(0, conv({ξ_i(α)} ∪ {ξ(y_j)}) + N_Υ(α)) over
/// subgradients at α and at admissible designs y_j within `radius` of α. Zero there certifies
/// that α is stationary in the Goldstein ε-sense for ε = radius (an element of the convex hull of
/// the Clarke subdifferentials over the ball, plus the normal cone, is near 0) — weaker than the
/// exact certificate at α, and what a nonsmooth method's own stopping test asserts; it is the
/// certificate that sees the pieces of nodes that change their status next to α.
struct SampledCertificate {
  bool computed = false;
  double radius = 0.0;       ///< requested ‖y_j − α‖ ≤ radius (the y_j lie on or inside the sphere)
  int requested = 0;         ///< samples asked for
  int evaluated = 0;         ///< y_j whose ξ entered the hull
  int failed = 0;            ///< y_j the oracle could not evaluate (skipped)
  double largest_step = 0.0;  ///< max_j ‖y_j − α‖ of the evaluated y_j
  double scale = kNaN;       ///< max ‖ξ‖ over all generators
  optim::StationarityCertificate clarke;  ///< the QP over all generators
  double relative_distance = kNaN;        ///< distance / scale
  bool stationary = false;                ///< relative_distance <= stationary_tolerance
  std::string message;
};

/// Condition (MF1′) (docs/theory/stationarity.md §3): full row rank of the tight system's Jacobian.
struct Mf1Report {
  bool computed = false;
  std::string not_computed_reason;  ///< why `computed` is false (empty when computed)
  Eigen::Index rows = 0;        ///< dim·p + m₀ (our contact-reduced form, see certificate.cpp)
  Eigen::Index cols = 0;        ///< d + dim·p
  int extra_conditions = 0;     ///< m₀: equations beyond one piece's dim·p ("other branches")
  int rank = 0;                 ///< numerical rank
  double sigma_max = kNaN;      ///< of the scaled matrix
  double sigma_min = kNaN;      ///< smallest of its min(rows, cols) singular values
  double tolerance = kNaN;      ///< absolute threshold used: rank_tolerance·σ_max
  bool full_row_rank = false;   ///< rank == rows
  /// The rows of the row table of docs/theory/stationarity.md §3 alone (which omits u_t = 0 for the
  /// contact-and-stick alternative of I₀ nodes with u_t = 0, rule R2), same columns: row count,
  /// rank, verdict.
  Eigen::Index spec_rows = 0;
  int spec_rank = 0;
  bool spec_full_row_rank = false;
};

/// The extreme-point test of docs/theory/stationarity.md §4 (needs the full 𝕃, not a sample).
struct MordukhovichReport {
  bool computed = false;
  std::string message;                 ///< why not computed, or what was concluded
  std::vector<int> extreme;            ///< columns of Certificate::subgradients that are extreme points
  std::vector<double> hull_distances;  ///< per distinct tested column: dist(ξ_i, conv(other ξ_j))
  /// δ_M = min over extreme ξ_i of dist(ξ_i, −N_Υ(α)) ≥ dist(0, ∂_MΘ + N_Υ) when (MF1′) holds.
  double distance = kNaN;
  int attaining = -1;                  ///< column attaining δ_M
  /// Thesis criterion: the minimizer of the Clarke QP puts all weight on one extreme generator.
  bool clarke_minimizer_is_extreme = false;
  bool stationary = false;             ///< δ_M ≤ stationary_tolerance·scale and (MF1′) full row rank
};

/// One load case in a certificate (docs/theory/load-cases.md §3): its value, whether it is active,
/// its index sets and 𝕃, the columns of Certificate::subgradients it contributes, its (MF1′)
/// report.
struct LoadCaseCertificate {
  std::string name;
  double value = kNaN;           ///< J_k
  double weighted_value = kNaN;  ///< w_k J_k
  bool active = false;           ///< "worst": within case_active_tolerance of Θ; "weighted": w_k > 0
  sensitivity::IndexSets index_sets;
  double cardinality = kNaN;     ///< |𝕃_k| (active cases)
  bool sampled = false;
  int num_pieces = 0;            ///< ξ_{k,i} computed
  Mf1Report mf1;                 ///< of this case's tight system (active cases, unless clarke_only)
};

/// The certificate at one design.
struct Certificate {
  Status status = Status::kNotRun;
  std::string message = "certify() has not been called";
  Eigen::VectorXd alpha;
  double value = kNaN;  ///< Θ(α)
  sensitivity::IndexSets index_sets;
  double cardinality = kNaN;   ///< |𝕃|
  bool sampled = false;        ///< ξ_i below are for a sample of 𝕃 (|𝕃| > cap)
  std::vector<std::string> piece_summaries;  ///< one per column of `subgradients`
  Eigen::MatrixXd subgradients;              ///< d × m: ξ_i, column 0 = the default piece when sampled
  int default_piece_column = 0;              ///< column of the default piece (what the optimizer saw)
  double scale = kNaN;                       ///< max_i ‖ξ_i‖
  /// δ = dist(0, conv{ξ_i} + N_Υ(α)) with weights θ and the active constraints
  /// (docs/theory/stationarity.md §2).
  optim::StationarityCertificate clarke;
  double relative_distance = kNaN;           ///< δ / scale
  /// Names of the active rows of Υ (bounds, slope rows by shape's names) and the equalities.
  std::vector<std::string> active_constraints;
  optim::StationarityCertificate default_piece;  ///< the same QP with the default ξ alone
  double default_relative_distance = kNaN;
  bool clarke_stationary = false;                ///< δ ≤ stationary_tolerance·scale
  Mf1Report mf1;
  MordukhovichReport mordukhovich;
  /// Load cases (empty without): per case. `subgradients` then holds, for "worst", the
  /// union over the active cases of w_k ξ_{k,i}; for "weighted", sums Σ_k w_k ξ_{k,i_k} (all
  /// combinations up to `cap`, else the default pieces varied one case at a time: sampled).
  std::vector<LoadCaseCertificate> load_cases;
  std::string combine;  ///< "worst" or "weighted" (empty without load cases)
  /// A cost along a loading history (empty without): per step, its index sets
  /// and |𝕃_k|; `index_sets` is the step the cost reads (the last for the dissipation), and
  /// `subgradients` the default pieces varied one step at a time (docs/theory/history-adjoint.md §4).
  /// With load cases given as programs: the lines of each active case of more than one step,
  /// prefixed by its name (its generators are its default pieces varied one step at a time).
  std::vector<std::string> history_steps;
  /// CertifyOptions::sample_radius > 0: the sampled (Goldstein-type) certificate.
  SampledCertificate goldstein;
  double time_seconds = 0.0;
  /// A few lines for the CLI.
  [[nodiscard]] std::string report() const;
};

/// Computes the certificate of α (docs/theory/stationarity.md; thesis §5.3) with the oracle's body
/// and cost: solves the state, classifies, enumerates 𝕃 (or samples it), computes every ξ_i by one
/// adjoint each, the stationarity QP, the (MF1′) matrix by d + dim·p solves with the existing
/// factorization, and the extreme-point test. Throws InvalidInput when α has the wrong size,
/// violates Υ by more than the active tolerance, or inverts an element; a failed state solve is
/// a Status in the result.
[[nodiscard]] Certificate certify(ShapeOracle& oracle, const Eigen::VectorXd& alpha, const CertifyOptions& options = {});

}  // namespace frictopt::study
