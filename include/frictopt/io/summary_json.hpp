// SPDX-License-Identifier: MIT
// JSON of every solver's Summary (the numerical modules stay JSON-free, JSON output lives
// in io). Each function writes every field under its own name, NaN as null (json.hpp), enums
// in their report spelling, so summary.json files and tests read the same names as the code.
#pragma once

#include "frictopt/contact/contact_resultants.hpp"
#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/contact/tresca_solver.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/optim/dense_qp.hpp"
#include "frictopt/optim/projected_subgradient.hpp"
#include "frictopt/sensitivity/adjoint.hpp"
#include "frictopt/study/certificate.hpp"
#include "frictopt/study/elastic_body.hpp"
#include "frictopt/study/identification.hpp"
#include "frictopt/study/loading_program.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/tribometer.hpp"

namespace frictopt::io {

/// Adds (or replaces) every member of the object `members` in the object `into`.
void add_members(JsonValue& into, const JsonValue& members);

/// The SI unit of the cost Θ of `cost` on a body of dimension `dim` (docs/theory/costs.md; in 2D
/// forces are per metre of thickness and tributary areas are lengths), e.g. "N²", "J/m".
[[nodiscard]] std::string cost_unit(const study::CostDefinition& cost, int dim);

[[nodiscard]] JsonValue to_json(const study::StateSummary& summary);
/// The conditions a run's numbers were produced under, for every command's summary (CLI and
/// Python alike): {"blas_threads": the BLAS thread policy, "blas": the BLAS loaded (implementation
/// and the library dgemm_ resolves to)}. A run is bit-reproducible only for a
/// fixed thread count (README, "Reproducibility").
[[nodiscard]] JsonValue run_environment();
/// The Bézier chart of the body's design (docs/case-format.md, [design]): patch, origin and
/// extents in the plane coordinates, control points and degree per direction, the frame (normal,
/// tangents) and the formula of the surface, so that a run's alpha rebuilds it.
[[nodiscard]] JsonValue design_chart(const study::ElasticBody& body);
/// summary.json of `solve` (CLI and Python alike): the case, the state's summary, mesh sizes, the
/// contact summary and, for a converged state, energies, volume and the largest von Mises stress.
[[nodiscard]] JsonValue solve_summary(const std::string& case_name, const study::ElasticBody& body,
                                      const study::BodyState& state);
[[nodiscard]] JsonValue to_json(const contact::TrescaSolver::Summary& summary);
[[nodiscard]] JsonValue to_json(const contact::CoulombSolver::Summary& summary);
/// Totals, areas, counts and the stick zone (the members of solve's "contact" object).
[[nodiscard]] JsonValue to_json(const contact::ContactResultants& resultants);
/// The load a design carries (a run's initial_load / final_load): total normal force, total
/// tangential force and its norm, contact area, node counts.
[[nodiscard]] JsonValue load_to_json(const contact::ContactResultants& resultants);
/// The loading plates of a state (docs/case-format.md, "[[plate]]"): per plate its part, tied and
/// held directions, translation [m], the total force it applies [N] and the prescribed force [N].
[[nodiscard]] JsonValue plates_to_json(const std::vector<fem::PlateReading>& plates);
/// One line per plate (joined by newlines, none at the end) for the console: "plate "top": u = [...] m, F = [...] N (prescribed [...])".
[[nodiscard]] std::string plates_report(const std::vector<fem::PlateReading>& plates);
/// certify's comparison of the load the design `alpha` carries with the initial design's
/// (study::load_change_warnings; a state solve per design the oracle has not cached):
/// "initial_load", "final_load" (when both solve), "warnings", "load_warning_fraction".
[[nodiscard]] JsonValue load_comparison(study::ShapeOracle& oracle, const Eigen::Ref<const Eigen::VectorXd>& alpha,
                                        const Eigen::Ref<const Eigen::VectorXd>& initial_design);
[[nodiscard]] JsonValue to_json(const sensitivity::AdjointSensitivity::Summary& summary);
/// Without the per-iteration history (history.csv holds it) and the last state (checkpoint.json).
[[nodiscard]] JsonValue to_json(const optim::BundleTrust::Summary& summary);
[[nodiscard]] JsonValue to_json(const optim::ProjectedSubgradient::Summary& summary);
[[nodiscard]] JsonValue to_json(const optim::DenseQpSolver::Summary& summary);
/// Estimates, covariance, correlation and Ceres' brief report (the full report has its own file).
[[nodiscard]] JsonValue to_json(const study::Identification::Summary& summary);
/// One angle of the virtual tribometer: onset, sliding, the law's μ(φ) and N_W(ŝ), and with
/// `with_ramp` every ramp point (pull, P, T, stick fraction, counts).
[[nodiscard]] JsonValue to_json(const study::TribometerAngleResult& angle, bool with_ramp = false);
/// The tribometer's run: status, press, counters and every angle (without their ramps).
[[nodiscard]] JsonValue to_json(const study::Tribometer::Summary& summary);
/// A loading program's run (status, message, steps_solved, factorizations, factorization_seconds,
/// contact_seconds, time_seconds).
[[nodiscard]] JsonValue to_json(const study::LoadingProgram::Summary& summary);
/// The whole certificate: index sets, pieces with ξ_i and weights, Clarke distance, (MF1) rank,
/// Mordukhovich check; `options` for the tolerances used.
[[nodiscard]] JsonValue to_json(const study::Certificate& certificate, const study::CertifyOptions& options);

}  // namespace frictopt::io
