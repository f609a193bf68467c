// SPDX-License-Identifier: MIT
#include "frictopt/study/certificate.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "frictopt/contact/delassus.hpp"
#include "frictopt/linalg/dense_blas.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/sensitivity/piece.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "sampled_certificate.hpp"
#include "scaled_stationarity.hpp"

namespace frictopt::study {
namespace {

// The (MF1′) matrix is dense, (dim·p + m₀) × (d + dim·p), and its singular values cost O(n³)
// (LAPACK dgesdd): above this many contact unknowns it is skipped and the report says so. At
// 5,043 (punch-large) the whole certify takes ≈ 1 min on 2 cores; 8,000 bounds it at a few.
constexpr Eigen::Index kMaxMf1ContactUnknowns = 8000;
// Local rows of one node are O(1) numbers (0, ±1, ±μ, polygon vertices): rank decided at 1e-12.
constexpr double kLocalRankTolerance = 1e-12;
// Subgradients equal up to this (max norm, relative to the scale) are one generator; matches
// optim::StationarityOptions::duplicate_tolerance.
constexpr double kDuplicateTolerance = 1e-12;

std::string constraint_name(const std::string& origin, const shape::LinearConstraints& upsilon,
                            const Eigen::VectorXd& alpha) {
  // optim::GeneralForm names rows "lower[k]", "upper[k]", "A_in[j]".
  const auto open = origin.find('['), close = origin.find(']');
  if (open == std::string::npos || close == std::string::npos) return origin;
  const std::string block = origin.substr(0, open);
  const auto k = static_cast<Eigen::Index>(std::stol(origin.substr(open + 1, close - open - 1)));
  if (block == "lower") return fmt::format("bound alpha[{}] >= {:g} (alpha = {:.3e})", k, upsilon.lower(k), alpha(k));
  if (block == "upper") return fmt::format("bound alpha[{}] <= {:g} (alpha = {:.3e})", k, upsilon.upper(k), alpha(k));
  if (block == "A_in" && k < static_cast<Eigen::Index>(upsilon.inequality_names.size()))
    return fmt::format("{} <= {:g}", upsilon.inequality_names[static_cast<std::size_t>(k)], upsilon.b_in(k));
  return origin;
}

// The stationarity QP of optim with the generators divided by `scale` (results scaled back).
using detail::scaled_certificate;

// One equation of the tight system at a node, in the node's local unknowns: s·(G u)_i + c·z_i +
// gap·g_i = 0 (the form of sensitivity::linearize_piece; g_i = (B̃α)_i).
struct LocalRow {
  Eigen::VectorXd s, c;
  double gap = 0.0;
  // u_t = 0 of the contact-and-stick alternative of an I₀ node (rule R2): the rows the row table
  // (docs/theory/stationarity.md §3) does not list; it counts such nodes as (T) without (S).
  bool beyond_spec_table = false;
  Eigen::VectorXd stacked() const {
    Eigen::VectorXd v(s.size() + c.size() + 1);
    v << s, c, gap;
    return v;
  }
};

// The tight system of docs/theory/stationarity.md §3, node by node. READING: its row table lists,
// per node,
// the equations of both branches of each degenerate alternative ((T) and (S) for weak stick, (C)
// and (Z) for weak contact). We take, for every node, a basis of the span of the equations that
// any of its node alternatives imposes (sensitivity::node_alternatives, i.e. exactly the pieces
// of 𝕃). For strict nodes this is the piece's own dim rows; for K₀± and for I₀ nodes that slip it
// is the row table (one extra row each). For I₀ nodes with u_t = 0 (rule R2: zero force, or
// contact with slip+/slip−/stick) the span is {λ = 0, gap = 0, q = 0, u_t = 0}: two extra rows
// where the row table counts one, because the contact-and-stick alternative needs both λ > 0
// and |q| < μλ to be attained nearby; full row rank of this larger matrix is the sufficient
// condition for every piece of 𝕃 to be essentially active. The 3D branches (ray slip, smooth slip)
// are covered by the same construction.
std::vector<std::vector<LocalRow>> tight_rows(const sensitivity::IndexSets& sets, const contact::FrictionLaw& law,
                                              const contact::ContactState& state) {
  const int dim = state.dim;
  const auto p = static_cast<std::size_t>(state.num_nodes());
  std::vector<std::vector<sensitivity::NodePiece>> alternatives(p);
  std::size_t most = 1;
  for (std::size_t i = 0; i < p; ++i) {
    alternatives[i] = sensitivity::node_alternatives(sets.nodes[i], law);
    most = std::max(most, alternatives[i].size());
  }
  std::vector<std::vector<LocalRow>> rows(p);
  std::vector<Eigen::MatrixXd> basis(p);  // stacked rows chosen so far, per node
  // Alternative k for every node at once (nodes with fewer alternatives repeat their last): one
  // linearization per k instead of one per node and alternative.
  for (std::size_t k = 0; k < most; ++k) {
    sensitivity::Piece piece;
    for (std::size_t i = 0; i < p; ++i) piece.nodes.push_back(alternatives[i][std::min(k, alternatives[i].size() - 1)]);
    const sensitivity::PieceLinearization lin = sensitivity::linearize_piece(piece, law, state);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> S = lin.S, Cz = lin.Cz;
    std::vector<bool> is_gap(static_cast<std::size_t>(S.rows()), false);
    for (Eigen::Index r : lin.gap_rows) is_gap[static_cast<std::size_t>(r)] = true;
    for (std::size_t i = 0; i < p; ++i) {
      if (k >= alternatives[i].size()) continue;
      const Eigen::Index base = dim * static_cast<Eigen::Index>(i);
      for (int a = 0; a < dim; ++a) {
        const Eigen::Index r = base + a;
        const sensitivity::NodePiece& alternative = alternatives[i][k];
        LocalRow row{Eigen::VectorXd::Zero(dim), Eigen::VectorXd::Zero(dim), is_gap[static_cast<std::size_t>(r)] ? 1.0 : 0.0,
                     sets.nodes[i].normal == sensitivity::NormalSet::kWeakContact &&
                         alternative.normal == sensitivity::NormalBranch::kGapClosed &&
                         alternative.tangential == sensitivity::TangentialBranch::kStick && a < dim - 1};
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(S, r); it; ++it) {
          FRICTOPT_ASSERT(it.col() >= base && it.col() < base + dim, "piece rows couple nodes");
          row.s(it.col() - base) = it.value();
        }
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Cz, r); it; ++it) {
          FRICTOPT_ASSERT(it.col() >= base && it.col() < base + dim, "piece rows couple nodes");
          row.c(it.col() - base) = it.value();
        }
        const Eigen::VectorXd v = row.stacked();
        if (v.lpNorm<Eigen::Infinity>() == 0.0) continue;
        Eigen::MatrixXd trial(basis[i].rows() + 1, v.size());
        if (basis[i].rows()) trial.topRows(basis[i].rows()) = basis[i];
        trial.bottomRows(1) = v.transpose() / v.norm();
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(trial);
        const Eigen::VectorXd sv = svd.singularValues();
        if (sv(sv.size() - 1) <= kLocalRankTolerance * sv(0) || trial.rows() > v.size()) continue;
        basis[i] = trial;
        rows[i].push_back(row);
      }
    }
  }
  return rows;
}

Mf1Report mf1_report(ShapeOracle& oracle, const sensitivity::IndexSets& sets, const CertifyOptions& options) {
  const ElasticBody& body = oracle.body();
  const BodyState& state = oracle.last_state();
  const contact::ContactState& cs = state.contact->state;
  const contact::ContactBoundary& boundary = *body.contact_boundary();
  const contact::FrictionLaw& law = *state.contact->law;  // the law the state was solved with
  const fem::LinearElasticity& fem = body.elasticity();
  const linalg::SpdSolver& stiffness = body.engine().stiffness_solver();  // A⁻¹ at the state's design
  const int dim = boundary.dim();
  const Eigen::Index m = boundary.num_unknowns();
  const Eigen::Index d = state.alpha.size();
  Mf1Report out;
  // A floating body's rows carry its equilibrium too (docs/theory/loading-plate.md §3): not
  // reported.
  if (m > kMaxMf1ContactUnknowns || fem.free_modes().cols() > 0) return out;

  const auto rows = tight_rows(sets, law, cs);
  Eigen::Index n_rows = 0;
  for (const auto& r : rows) n_rows += static_cast<Eigen::Index>(r.size());

  // M = G A⁻¹ Gᵀ and N = G A⁻¹ r_α (columns k: r_α e_k = ∂(A u − l)/∂α_k at the state), both
  // with the existing factorization (d + dim·p solves).
  // The state's dense M when it has one (no copy); else m solves with the factorization.
  Eigen::MatrixXd solved_M;
  if (!state.contact->delassus_matrix) solved_M = contact::dense_delassus(stiffness, boundary);
  const Eigen::MatrixXd& M = state.contact->delassus_matrix ? *state.contact->delassus_matrix : solved_M;
  const Eigen::MatrixXd B = boundary.gap_jacobian(body.mesh());  // B̃ from V: any mesh producer
  Eigen::MatrixXd R_alpha(fem.dofs().num_free(), d);  // r_α e_k, one column per control point
  for (Eigen::Index k = 0; k < d; ++k) {
    const Eigen::VectorXd Vh = fem.mesh().design_jacobian().col(k);
    const Eigen::MatrixXd dX =
        Eigen::Map<const Eigen::MatrixXd>(Vh.data(), dim, fem.mesh().num_nodes()).transpose();
    R_alpha.col(k) = fem.dofs().restrict_forces(fem.residual_derivative(state.positions, state.displacement, dX));
  }
  const Eigen::MatrixXd Ainv_R = stiffness.solve_many(R_alpha);  // one blocked solve for all d
  Eigen::MatrixXd N(m, d);
  for (Eigen::Index k = 0; k < d; ++k) N.col(k) = boundary.times(Ainv_R.col(k));

  // H in the unknowns (α, z) after eliminating u = A(α)⁻¹(l(α) + Gᵀz) from the equilibrium rows:
  // row s·(Gu)_i + c·z_i + gap·(B̃α)_i has ∂/∂z = s·M_(i,:) + c·e_(z_i) and
  // ∂/∂α = −s·N_(i,:) + gap·B̃_(i,:). Eliminating u with the invertible A changes neither the
  // row rank deficiency nor full row rank, so this H is equivalent to the natural
  // (3p + m₀) × (d + 3p) matrix in the variables (α, u_t, u_ν, λ) (2D): ours has p fewer rows and
  // p fewer columns (q replaces u_t, u_ν is eliminated), and the same rows − rank.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n_rows, d + m);
  Eigen::Index r = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::Index base = dim * static_cast<Eigen::Index>(i);
    for (const LocalRow& row : rows[i]) {
      H.block(r, 0, 1, d) = -row.s.transpose() * N.middleRows(base, dim) + row.gap * B.row(static_cast<Eigen::Index>(i));
      H.block(r, d, 1, m) = row.s.transpose() * M.middleRows(base, dim);
      H.block(r, d + base, 1, dim) += row.c.transpose();
      ++r;
    }
  }
  // Rows mix displacements (m/N · N) and forces: scale rows, then columns, to unit 2-norm before
  // the SVD so that the relative threshold means the same for every block. Scaling by positive
  // diagonal matrices does not change the exact rank.
  for (Eigen::Index i = 0; i < H.rows(); ++i)
    if (const double n = H.row(i).norm(); n > 0.0) H.row(i) /= n;
  for (Eigen::Index j = 0; j < H.cols(); ++j)
    if (const double n = H.col(j).norm(); n > 0.0) H.col(j) /= n;

  out.computed = true;
  out.rows = H.rows();
  out.cols = H.cols();
  out.extra_conditions = static_cast<int>(n_rows - m);
  const Eigen::VectorXd sv = linalg::blas::singular_values(H);
  out.sigma_max = sv.size() ? sv(0) : 0.0;
  out.sigma_min = sv.size() ? sv(sv.size() - 1) : 0.0;
  out.tolerance = options.rank_tolerance * out.sigma_max;
  out.rank = static_cast<int>((sv.array() > out.tolerance).count());
  out.full_row_rank = out.rank == out.rows;
  // The same test on the rows of the row table alone (without the R2 stick rows).
  std::vector<Eigen::Index> spec_rows;
  Eigen::Index index = 0;
  for (const auto& node_rows : rows)
    for (const LocalRow& row : node_rows) {
      if (!row.beyond_spec_table) spec_rows.push_back(index);
      ++index;
    }
  out.spec_rows = static_cast<Eigen::Index>(spec_rows.size());
  if (out.spec_rows == out.rows) {
    out.spec_rank = out.rank;
  } else if (out.full_row_rank) {
    // A subset of the rows of a matrix of full row rank has full row rank at the same relative
    // threshold (interlacing: its σ_min is not smaller, its σ_max not larger): no second SVD.
    out.spec_rank = static_cast<int>(out.spec_rows);
  } else {
    const Eigen::MatrixXd Hs = H(spec_rows, Eigen::all);
    const Eigen::VectorXd ss = linalg::blas::singular_values(Hs);
    out.spec_rank = ss.size() ? static_cast<int>((ss.array() > options.rank_tolerance * ss(0)).count()) : 0;
  }
  out.spec_full_row_rank = out.spec_rank == out.spec_rows;
  return out;
}

MordukhovichReport mordukhovich_report(const Certificate& c, const Eigen::VectorXd& alpha,
                                       const optim::LinearConstraints& upsilon, const CertifyOptions& options) {
  MordukhovichReport out;
  if (c.sampled) {
    out.message = fmt::format("not computed: |L| = {:.0f} > cap; the extreme points of a sample are not those of "
                              "conv{{xi_i : i in L}}",
                              c.cardinality);
    return out;
  }
  std::vector<Eigen::Index> group;
  const std::vector<Eigen::Index> rep = optim::distinct_columns(c.subgradients, kDuplicateTolerance, group);
  if (static_cast<int>(rep.size()) > options.max_extreme_point_tests) {
    out.message = fmt::format("not computed: {} distinct xi_i > max_extreme_point_tests = {}", rep.size(),
                              options.max_extreme_point_tests);
    return out;
  }
  const double threshold = options.extreme_tolerance * std::max(c.scale, 1e-300);
  const optim::StationarityOptions qp{options.active_tolerance};
  std::vector<bool> is_extreme(rep.size(), false);
  for (std::size_t i = 0; i < rep.size(); ++i) {
    // docs/theory/stationarity.md §4 step 1 as a distance: e_i = dist(ξ_i, conv{ξ_j : j ∈ D_i}) = dist(0, conv{ξ_j − ξ_i})
    // by the min-norm QP; the LP "ξ_i ∈ conv D_i" is infeasible iff e_i > 0.
    double e = std::numeric_limits<double>::infinity();
    if (rep.size() > 1) {
      Eigen::MatrixXd Y(c.subgradients.rows(), static_cast<Eigen::Index>(rep.size()) - 1);
      Eigen::Index col = 0;
      for (std::size_t j = 0; j < rep.size(); ++j)
        if (j != i) Y.col(col++) = c.subgradients.col(rep[j]) - c.subgradients.col(rep[i]);
      const auto hull = scaled_certificate(Y, Eigen::VectorXd::Zero(Y.rows()), {}, qp, c.scale);
      if (hull.status != Status::kConverged) {
        out.message = "extreme-point QP failed: " + hull.message;
        return out;
      }
      e = hull.distance;
    }
    out.hull_distances.push_back(e);
    is_extreme[i] = e > threshold;
    if (!is_extreme[i]) continue;
    out.extreme.push_back(static_cast<int>(rep[i]));
    // Step 2: dist(ξ_i, −N_Υ(α)), a small NNLS problem (the same QP with one generator).
    const auto single = scaled_certificate(c.subgradients.col(rep[i]), alpha, upsilon, qp, c.scale);
    if (single.status != Status::kConverged) {
      out.message = "distance QP failed: " + single.message;
      return out;
    }
    if (!(single.distance >= out.distance)) {
      out.distance = single.distance;
      out.attaining = static_cast<int>(rep[i]);
    }
  }
  out.computed = true;
  // Thesis criterion: the Clarke minimizer is one extreme generator (weights summed per group).
  if (c.clarke.weights.size() == c.subgradients.cols()) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rep.size()));
    for (Eigen::Index j = 0; j < c.subgradients.cols(); ++j) w(group[static_cast<std::size_t>(j)]) += c.clarke.weights(j);
    Eigen::Index top = 0;
    const double largest = w.maxCoeff(&top);
    out.clarke_minimizer_is_extreme = largest >= 1.0 - 1e-8 && is_extreme[static_cast<std::size_t>(top)];
  }
  // Extreme points of conv{ξ_i} lie in ∂_MΘ only when ∂Θ = conv{ξ_i}, i.e. under (MF1′).
  const bool small = !out.extreme.empty() && out.distance <= options.stationary_tolerance * c.scale;
  out.stationary = small && c.mf1.full_row_rank;
  out.message = out.extreme.empty()
                    ? "no extreme point found (all generators within tolerance of the others' hull)"
                    : fmt::format("{} of {} distinct xi_i are extreme points; delta_M = {:.6e} (relative {:.3e}) at "
                                  "column {}: {}",
                                  out.extreme.size(), rep.size(), out.distance,
                                  c.scale > 0 ? out.distance / c.scale : 0.0, out.attaining,
                                  out.stationary ? "M-stationary to this accuracy ((MF1') holds)"
                                  : small        ? "small, but (MF1') is not verified: no conclusion"
                                                 : "no M-stationarity certified");
  return out;
}

// The generators of one loading history's pseudodifferential (docs/theory/
// history-adjoint.md §4): the default ξ (every step's default piece) first, then each step's
// pieces varied one step at a time with the others at their defaults. That is all of
// 𝕃 = Π_k 𝕃_k when at most one step has more than one piece (always for one step: a static load
// case); otherwise (or when a step's 𝕃_k is sampled) the generators are a sample.
struct HistoryGenerators {
  std::vector<Eigen::VectorXd> columns;  // the static problem: column default_column is its default piece
  int default_column = 0;                // programs: column 0, the default pieces
  std::vector<std::string> summaries;
  double cardinality = 1.0;
  bool sampled = false;
  std::vector<std::string> step_lines;  // per step (programs of more than one step)
  std::string failure;                  // why a piece's adjoint failed (then the rest is partial)
};

// The static problem: the pieces of 𝕃 as enumerated (all of them up to the cap, else a sample
// that starts with the default piece), their ξ_i by the state engine in one call.
HistoryGenerators static_problem_generators(ProgramHistory& history, const CertifyOptions& options) {
  HistoryGenerators out;
  const sensitivity::PieceEnumeration enumeration = history.cost_step_pieces(options.cap);
  out.cardinality = enumeration.cardinality;
  out.sampled = enumeration.sampled;
  const auto results = history.cost_step_subgradients(enumeration.pieces);
  const sensitivity::Piece default_piece = sensitivity::default_piece(history.index_sets(0));
  for (std::size_t i = 0; i < results.size(); ++i) {
    // A singular piece gives a finite but meaningless ξ_i: it must not enter conv{ξ_i}.
    if (results[i].summary.status != Status::kConverged || !results[i].subgradient.allFinite()) {
      out.failure = fmt::format("piece {} ({}): {}", i, enumeration.pieces[i].summary(), results[i].summary.brief_report());
      return out;
    }
    out.columns.push_back(results[i].subgradient);
    out.summaries.push_back(enumeration.pieces[i].summary());
    if (enumeration.pieces[i].nodes == default_piece.nodes) out.default_column = static_cast<int>(i);
  }
  return out;
}

HistoryGenerators history_generators(ProgramHistory& history, const CertifyOptions& options) {
  if (history.is_static_problem()) return static_problem_generators(history, options);
  HistoryGenerators out;
  const std::vector<sensitivity::Piece> defaults = history.default_pieces();
  const bool one_step = history.num_steps() == 1;
  const auto add = [&](const std::vector<sensitivity::Piece>& pieces, std::string summary) {
    const HistorySubgradient r = history.subgradient(pieces);
    if (r.summary.status != Status::kConverged || !r.subgradient.allFinite()) {
      out.failure = fmt::format("{}: {}", summary, r.summary.brief_report());
      return false;
    }
    out.columns.push_back(r.subgradient);
    out.summaries.push_back(std::move(summary));
    return true;
  };
  if (!add(defaults, one_step ? defaults.front().summary() : "every step's default piece")) return out;
  int steps_with_choices = 0;
  for (int k = 0; k < history.num_steps(); ++k) {
    const sensitivity::PieceEnumeration enumeration = history.pieces(k, options.cap);
    out.cardinality *= enumeration.cardinality;
    out.sampled |= enumeration.sampled;
    if (!one_step)
      out.step_lines.push_back(fmt::format("step {}: {}; |L_k| = {:.0f}{}", k + 1, history.index_sets(k).summary(),
                                           enumeration.cardinality, enumeration.sampled ? " (sampled)" : ""));
    steps_with_choices += enumeration.cardinality > 1.0;
    for (const sensitivity::Piece& piece : enumeration.pieces) {
      if (piece.nodes == defaults[static_cast<std::size_t>(k)].nodes) continue;
      std::vector<sensitivity::Piece> chosen = defaults;
      chosen[static_cast<std::size_t>(k)] = piece;
      if (!add(chosen, one_step ? piece.summary() : fmt::format("step {}: {}", k + 1, piece.summary()))) return out;
    }
  }
  out.sampled |= steps_with_choices > 1;
  return out;
}

// Load cases (docs/theory/load-cases.md §2): the generators of the composite's Clarke
// subdifferential. "worst": Θ = max_k w_k J_k, ∂Θ(α) ⊂ conv ∪_{k active} w_k ∂J_k(α), so the
// columns are the union of the active cases' w_k ξ_{k,i}. "weighted": ∂Θ ⊂ Σ_k w_k ∂J_k, and
// Σ_k conv G_k = conv{Σ_k g_k : g_k ∈ G_k}, so the columns are the sums over one generator per
// case. A case's generators are those of its loading program (history_generators; one step for
// a static load). Returns false (with c.status set) when a piece's adjoint fails.
bool load_case_generators(ShapeOracle& oracle, const Eigen::VectorXd& alpha, const std::vector<double>& values,
                          double theta, int selected, const CertifyOptions& options, Certificate& c) {
  const LoadCases& cases = *oracle.load_cases();
  const bool worst = cases.definition().combine == CaseCombination::kWorst;
  c.combine = std::string(to_string(cases.definition().combine));
  const auto n_cases = static_cast<std::size_t>(cases.size());
  std::vector<std::vector<Eigen::VectorXd>> generators(n_cases);
  std::vector<std::vector<std::string>> summaries(n_cases);
  for (std::size_t k = 0; k < n_cases; ++k) {
    const int kk = static_cast<int>(k);
    LoadCaseCertificate lc;
    lc.name = cases[kk].name;
    const double w = cases[kk].weight;
    lc.value = values[k];
    lc.weighted_value = w * values[k];
    lc.active = w > 0.0 && (!worst || lc.weighted_value >= theta - options.case_active_tolerance * std::abs(theta));
    ProgramHistory& history = oracle.program(alpha, kk);
    lc.index_sets = history.cost_step_index_sets();
    if (lc.active) {
      HistoryGenerators g = history_generators(history, options);
      if (!g.failure.empty()) {
        c.status = Status::kNumericalFailure;
        c.message = fmt::format("load case \"{}\", {}", lc.name, g.failure);
        return false;
      }
      lc.cardinality = g.cardinality;
      lc.sampled = g.sampled;
      lc.num_pieces = static_cast<int>(g.columns.size());
      for (Eigen::VectorXd& column : g.columns) generators[k].push_back(w * column);
      summaries[k] = std::move(g.summaries);
      for (const std::string& line : g.step_lines) c.history_steps.push_back(lc.name + ", " + line);
    }
    c.load_cases.push_back(std::move(lc));
  }
  c.index_sets = c.load_cases[static_cast<std::size_t>(selected)].index_sets;
  std::vector<Eigen::VectorXd> columns;
  c.sampled = false;
  if (worst) {
    c.cardinality = 0.0;
    for (std::size_t k = 0; k < n_cases; ++k) {
      if (!c.load_cases[k].active) continue;
      if (static_cast<int>(k) == selected) c.default_piece_column = static_cast<int>(columns.size());
      c.cardinality += c.load_cases[k].cardinality;
      c.sampled |= c.load_cases[k].sampled;
      for (std::size_t i = 0; i < generators[k].size(); ++i) {
        columns.push_back(generators[k][i]);
        c.piece_summaries.push_back(c.load_cases[k].name + ": " + summaries[k][i]);
      }
    }
  } else {
    std::vector<std::size_t> active;
    double combinations = 1.0;
    c.cardinality = 1.0;
    for (std::size_t k = 0; k < n_cases; ++k)
      if (c.load_cases[k].active) {
        active.push_back(k);
        combinations *= static_cast<double>(generators[k].size());
        c.cardinality *= c.load_cases[k].cardinality;
        c.sampled |= c.load_cases[k].sampled;
      }
    const auto add = [&](const std::vector<std::size_t>& choice) {
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(alpha.size());
      std::string text;
      for (std::size_t a = 0; a < active.size(); ++a) {
        sum += generators[active[a]][choice[a]];
        text += (a ? " | " : "") + c.load_cases[active[a]].name + ": " + summaries[active[a]][choice[a]];
      }
      columns.push_back(std::move(sum));
      c.piece_summaries.push_back(std::move(text));
    };
    // Each case's generator 0 is its default pieces: column 0 is the ξ the optimizer saw.
    const std::vector<std::size_t> defaults(active.size(), 0);
    c.default_piece_column = 0;
    add(defaults);
    if (combinations <= static_cast<double>(options.cap)) {
      // Every combination (mixed radix over the active cases), the all-default one already in.
      std::vector<std::size_t> choice(active.size(), 0);
      for (;;) {
        if (choice != defaults) add(choice);
        std::size_t a = 0;
        while (a < active.size() && ++choice[a] == generators[active[a]].size()) choice[a++] = 0;
        if (a == active.size()) break;
      }
    } else {
      // Too many: the default combination varied in one case at a time (a sample of the sums).
      c.sampled = true;
      for (std::size_t a = 0; a < active.size(); ++a)
        for (std::size_t i = 1; i < generators[active[a]].size(); ++i) {
          std::vector<std::size_t> choice = defaults;
          choice[a] = i;
          add(choice);
        }
    }
  }
  c.subgradients.resize(alpha.size(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t j = 0; j < columns.size(); ++j) c.subgradients.col(static_cast<Eigen::Index>(j)) = columns[j];
  c.scale = c.subgradients.colwise().norm().maxCoeff();
  return true;
}

// One history (the static problem or a cost along a loading program): its generators
// (history_generators).
bool single_history_generators(ShapeOracle& oracle, const Eigen::VectorXd& alpha, const CertifyOptions& options,
                               Certificate& c) {
  // program() re-solves if the oracle's cache answered without touching the state: from here on
  // the history's states (and the body's factorization) are those at α.
  ProgramHistory& history = oracle.program(alpha);
  HistoryGenerators g = history_generators(history, options);
  if (!g.failure.empty()) {
    c.status = Status::kNumericalFailure;
    c.message = g.failure;
    return false;
  }
  c.default_piece_column = g.default_column;
  c.cardinality = g.cardinality;
  c.sampled = g.sampled;
  c.history_steps = std::move(g.step_lines);
  c.piece_summaries = std::move(g.summaries);
  c.index_sets = history.cost_step_index_sets();
  c.subgradients.resize(alpha.size(), static_cast<Eigen::Index>(g.columns.size()));
  for (std::size_t j = 0; j < g.columns.size(); ++j) c.subgradients.col(static_cast<Eigen::Index>(j)) = g.columns[j];
  c.scale = c.subgradients.colwise().norm().maxCoeff();
  return true;
}

}  // namespace

void CertifyOptions::validate() const {
  if (cap < 1) throw InvalidInput(fmt::format("CertifyOptions::cap = {}; expected >= 1", cap));
  if (!(active_tolerance >= 0.0))
    throw InvalidInput(fmt::format("CertifyOptions::active_tolerance = {}; expected >= 0", active_tolerance));
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0))
    throw InvalidInput(fmt::format("CertifyOptions::rank_tolerance = {}; expected in (0, 1)", rank_tolerance));
  if (!(extreme_tolerance > 0.0))
    throw InvalidInput(fmt::format("CertifyOptions::extreme_tolerance = {}; expected > 0", extreme_tolerance));
  if (max_extreme_point_tests < 1)
    throw InvalidInput(
        fmt::format("CertifyOptions::max_extreme_point_tests = {}; expected >= 1", max_extreme_point_tests));
  if (!(stationary_tolerance > 0.0))
    throw InvalidInput(fmt::format("CertifyOptions::stationary_tolerance = {}; expected > 0", stationary_tolerance));
  if (!(case_active_tolerance >= 0.0))
    throw InvalidInput(fmt::format("CertifyOptions::case_active_tolerance = {}; expected >= 0", case_active_tolerance));
  if (!(std::isfinite(sample_radius) && sample_radius >= 0.0))
    throw InvalidInput(fmt::format("CertifyOptions::sample_radius = {}; expected a finite radius >= 0 (0: no sampled "
                                   "certificate)",
                                   sample_radius));
  if (samples < 0) throw InvalidInput(fmt::format("CertifyOptions::samples = {}; expected >= 0 (0: 10(d + 1))", samples));
}

std::string Certificate::report() const {
  std::string s;
  if (status != Status::kConverged) return fmt::format("certificate: {}: {}\n", to_string(status), message);
  s += fmt::format("Theta(alpha) = {:.6e}\n", value);
  if (!load_cases.empty()) {
    s += fmt::format("load cases (combine = {}): case, J_k, w_k J_k, active, index sets, |L_k|\n", combine);
    for (const LoadCaseCertificate& lc : load_cases)
      s += fmt::format("  {:<16} {:.6e} {:.6e} {:<6} {} {}\n", lc.name, lc.value, lc.weighted_value,
                       lc.active ? "active" : "-", lc.index_sets.summary(),
                       lc.active ? fmt::format("|L_k| = {:.0f}{}", lc.cardinality, lc.sampled ? " (sampled)" : "") : "-");
  }
  if (!history_steps.empty()) {
    s += load_cases.empty()
             ? fmt::format("loading history: {} steps, generators = the default pieces varied one step at a time\n",
                           history_steps.size())
             : std::string("loading histories of the active cases given as programs: generators = each case's default "
                           "pieces varied one step at a time\n");
    for (const std::string& line : history_steps) s += "  " + line + "\n";
  }
  s += fmt::format("index sets: {} ({} weak nodes)\n", index_sets.summary(), index_sets.num_weak_nodes());
  s += fmt::format("|L| = {:.0f}{}; {} subgradients computed, {} distinct; scale max_i |xi_i| = {:.6e}\n", cardinality,
                   sampled ? " (sampled: > cap)" : "", subgradients.cols(), clarke.num_distinct_subgradients, scale);
  s += fmt::format("Clarke distance dist(0, conv{{xi_i}} + N_Upsilon) = {:.6e} (relative {:.3e}): {}\n", clarke.distance,
                   relative_distance, clarke_stationary ? "stationary at the stated tolerance" : "not stationary");
  int used = 0;
  for (Eigen::Index j = 0; j < clarke.weights.size(); ++j) used += clarke.weights(j) > 1e-12 ? 1 : 0;
  s += fmt::format("  weights on {} piece(s); |normal-cone part| = {:.3e}; active constraints ({}):\n", used,
                   clarke.normal_part.norm(), active_constraints.size());
  for (const std::string& name : active_constraints) s += "    " + name + "\n";
  s += fmt::format("default piece alone: distance {:.6e} (relative {:.3e})\n", default_piece.distance,
                   default_relative_distance);
  if (!mf1.computed)
    s += "(MF1') not computed: " +
         (mf1.not_computed_reason.empty()
              ? fmt::format("more than {} contact unknowns (the dense singular values cost O(n^3))", kMaxMf1ContactUnknowns)
              : mf1.not_computed_reason) +
         "\n";
  if (mf1.computed)
    s += fmt::format("(MF1') matrix {} x {} (m0 = {} extra conditions), rank {} (tol {:.1e} sigma_max, sigma_min/sigma_max "
                     "= {:.3e}): {}\n",
                     mf1.rows, mf1.cols, mf1.extra_conditions, mf1.rank, mf1.tolerance / mf1.sigma_max,
                     mf1.sigma_min / mf1.sigma_max,
                     mf1.full_row_rank ? "full row rank, so dTheta = conv{xi_i}"
                                       : fmt::format("rank deficient by {}", mf1.rows - mf1.rank));
  if (mf1.computed && mf1.spec_rows != mf1.rows)
    s += fmt::format("  rows of the (MF1') row table only (no R2 stick rows): {} x {}, rank {}: {}\n", mf1.spec_rows,
                     mf1.cols, mf1.spec_rank, mf1.spec_full_row_rank ? "full row rank" : "rank deficient");
  s += "Mordukhovich (extreme-point test): " + mordukhovich.message + "\n";
  if (goldstein.computed) s += "sampled certificate: " + goldstein.message + "\n";
  return s;
}

Certificate certify(ShapeOracle& oracle, const Eigen::VectorXd& alpha, const CertifyOptions& options) {
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  const ElasticBody& body = oracle.body();
  require_admissible_design(body, alpha, options.active_tolerance, "certify");
  const shape::LinearConstraints& upsilon = body.admissible_set();
  const LinearConstraints& constraints = upsilon;  // one type: shape builds it, optim uses it
  Certificate c;
  c.alpha = alpha;
  const Evaluation& e = oracle.evaluate_design(alpha, false);  // ξ of every piece follows below
  c.value = e.value;
  if (!e.ok) {
    c.status = Status::kNumericalFailure;
    c.message = e.message;
    return c;
  }
  const std::vector<double> case_values = e.case_values;  // copies: `e` lives in the oracle's cache
  const int selected_case = e.selected_case;
  if (oracle.load_cases()) {
    if (!load_case_generators(oracle, alpha, case_values, c.value, selected_case, options, c)) return c;
  } else if (!single_history_generators(oracle, alpha, options, c)) {
    return c;
  }

  const optim::StationarityOptions qp{options.active_tolerance};
  c.clarke = scaled_certificate(c.subgradients, alpha, constraints, qp, c.scale);
  c.default_piece = scaled_certificate(c.subgradients.col(c.default_piece_column), alpha, constraints, qp, c.scale);
  if (c.clarke.status != Status::kConverged || c.default_piece.status != Status::kConverged) {
    c.status = Status::kNumericalFailure;
    c.message = c.clarke.status != Status::kConverged ? c.clarke.message : c.default_piece.message;
    return c;
  }
  const double scale = c.scale > 0.0 ? c.scale : 1.0;  // all ξ_i = 0: distances are 0 anyway
  c.relative_distance = c.clarke.distance / scale;
  c.default_relative_distance = c.default_piece.distance / scale;
  c.clarke_stationary = c.clarke.distance <= options.stationary_tolerance * c.scale;
  for (const std::string& origin : c.clarke.active_names) c.active_constraints.push_back(constraint_name(origin, upsilon, alpha));
  for (Eigen::Index r = 0; r < upsilon.A_eq.rows(); ++r)
    c.active_constraints.push_back(fmt::format("volume: sum_k alpha_k = {:.6g} (equality{})", upsilon.b_eq(r),
                                               upsilon.A_eq.rows() > 1 ? fmt::format(" {}", r) : std::string()));

  if (options.clarke_only) {
    c.mf1.not_computed_reason = "not asked for (Clarke distance only)";
    c.mordukhovich.message = "not asked for (Clarke distance only)";
  } else if (oracle.history()) {
    c.mf1.not_computed_reason =
        "not computed for a cost along a loading history (the tight system couples the steps; "
        "docs/theory/history-adjoint.md §4)";
    c.mordukhovich.message = "not computed for a cost along a loading history";
  } else if (oracle.load_cases()) {
    // (MF1′) per active case: each case's tight system at its own state (same A(α) and M); a
    // case given as a program of several steps is a history (above).
    for (std::size_t k = 0; k < c.load_cases.size(); ++k) {
      if (!c.load_cases[k].active) continue;
      if (oracle.program(alpha, static_cast<int>(k)).num_steps() > 1) {
        c.load_cases[k].mf1.not_computed_reason =
            "not computed for a load case given as a loading program (the tight system couples the steps; "
            "docs/theory/history-adjoint.md §4)";
        continue;
      }
      oracle.select_case(alpha, static_cast<int>(k));
      c.load_cases[k].mf1 = mf1_report(oracle, c.load_cases[k].index_sets, options);
    }
    oracle.select_case(alpha, selected_case);
    c.mf1 = c.load_cases[static_cast<std::size_t>(selected_case)].mf1;
    c.mordukhovich.message =
        "not computed for load cases: the extreme points of the union of the cases' generators are not known to lie "
        "in the Mordukhovich subdifferential of the combination";
  } else {
    c.mf1 = mf1_report(oracle, c.index_sets, options);
    c.mordukhovich = mordukhovich_report(c, alpha, constraints, options);
  }
  if (options.sample_radius > 0.0) {
    // Last: it solves the oracle at other designs (the state at α is no longer the last one).
    c.goldstein = detail::sampled_certificate(oracle, alpha, c.subgradients, upsilon, options);
    if (c.goldstein.clarke.status != Status::kConverged) {
      c.status = Status::kNumericalFailure;
      c.message = c.goldstein.message;
      return c;
    }
  }
  c.status = Status::kConverged;
  c.message.clear();
  c.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return c;
}

}  // namespace frictopt::study
