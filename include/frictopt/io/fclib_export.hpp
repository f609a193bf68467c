// SPDX-License-Identifier: MIT
// Export of a body's frictional contact problem in the FCLIB "local" format (HDF5), so that
// other solvers (Siconos, …) can be run on exactly our problems. The mapping between our dual
// variables (docs/theory/state-problem.md §1, §5) and FCLIB's is in docs/contact.md, "FCLIB
// export".
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <string_view>

#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

/// The local FCLIB problem FC(W, q, μ): find u, r with u = W r + q, û = u + (μ‖u_T‖, 0, …) and
/// C*_μ ∋ û ⟂ r ∈ C_μ per contact, C_μ = {‖r_T‖ <= μ r_N}. Per contact the blocks are ordered
/// normal first, r = (r_N, r_T) and u = (u_N, u_T); for our static problem u is a displacement.
///
/// Relation to our dual variables z_i = (q_i, λ_i), ∇_i = (Mz + c)_i = (−u_t^i, u_ν^i + g_i):
///   r_i = (λ_i, τ_i) = (λ_i, −q_i),   u_i = (u_ν^i + g_i, u_t^i),
/// i.e. r = P z, u = P ∇ with the signed permutation P_i (orthogonal), hence W = P M Pᵀ and
/// q = P c. All quantities in the units `force_unit`, `length_unit` (SI when both are 1):
/// r/force_unit, u/length_unit, W·force_unit/length_unit, q/length_unit.
struct FclibLocalProblem {
  int spacedim = 3;    ///< 2 or 3
  Eigen::MatrixXd W;   ///< m × m, m = spacedim · num_contacts (dense, symmetric PSD)
  Eigen::VectorXd q;   ///< m
  Eigen::VectorXd mu;  ///< num_contacts: the coefficient of the isotropic cone
  Eigen::VectorXd r;   ///< our solution's reactions (see `solution_is_exact`)
  Eigen::VectorXd u;   ///< W r + q for that r
  /// True when (r, u) solves this problem up to our solver's tolerance (exact isotropic law
  /// and a converged solve); false for kind = isotropic in 3D, where r is our regular-n-gon
  /// solution and is written as an initial guess only.
  bool solution_is_exact = false;
  double force_unit = 1.0;   ///< [N] (2D: N per metre of thickness)
  double length_unit = 1.0;  ///< [m]
  std::string title;
  std::string description;
  std::string math_info;
  Eigen::Index num_contacts() const { return spacedim == 0 ? 0 : q.size() / spacedim; }
};

struct FclibExportOptions {
  /// Name of the case in the problem's title and description (e.g. the case file's path).
  std::string case_name;
  /// Write our solution: as FCLIB's /solution when it is exact for the exported problem, else
  /// as initial guess 1 (/guesses).
  bool include_solution = true;
  /// Write the problem in the units force_unit = max(‖r‖_∞) and length_unit = max(‖u‖_∞,
  /// ‖q‖_∞) of our solution (each 1 when that scale is 0), so W, q, r and u are O(1) and the
  /// tolerances of other solvers (and FCLIB's merit function) read as relative ones. The units
  /// used are recorded in the description ("Units: normalized ..."). Default: normalized —
  /// in SI units W is ~1e-10 m/N and other solvers' standard (absolute) tolerances break down;
  /// false writes SI units.
  bool normalize_units = true;
  /// Largest m = spacedim·p written: W is stored densely (m² doubles and ints, compressed
  /// column), and FCLIB indexes with int. > 0.
  Eigen::Index max_unknowns = 12000;
};

/// Throws InvalidInput (as make_fclib_local would, naming `case_name`) when `law` cannot be
/// written to FCLIB: a command checks this before it solves anything.
void require_fclib_exportable(const contact::FrictionLaw& law, std::string_view case_name);

/// Builds the local FCLIB problem of `body` at `state` (no file I/O). M is the state's own
/// Delassus operator (its dense copy or the dense M of its Schur factor), not a second
/// factorization.
///
/// `state` must be the result of the most recent `body.solve(…)`: W is assembled through the
/// factorization `body` holds (docs/theory/state-problem.md §5: M = G A⁻¹ Gᵀ), and the gradient
/// stored in the state is checked against it. Throws InvalidInput when the body has no foundation,
/// when the state is not the body's last solve, when the problem is too large
/// (options.max_unknowns), and when the friction law is not isotropic: FCLIB stores isotropic
/// Coulomb cones only, so 3D kinds polygon, ellipse and ellipse_exact and 2D polygon with μ₋ ≠ μ₊
/// are rejected. For 3D kind = isotropic (the regular n-gon) the disc of the same μ is exported and
/// the description says so.
[[nodiscard]] FclibLocalProblem make_fclib_local(const study::ElasticBody& body,
                                                 const study::BodyState& state,
                                                 const FclibExportOptions& options = {});

/// Writes `problem` to `path` (HDF5, replacing an existing file): /fclib_local (W as a dense
/// compressed-column matrix, q, μ, spacedim, info), and with `include_solution` our (r, u) as
/// /solution (exact) or /guesses/1. Throws InvalidInput naming the path if it cannot be written.
/// The file is written as a uniquely named sibling and renamed over `path`, which must be absent
/// or a regular file (links and devices are refused, see docs/contact.md). Caveat: fclib terminates the
/// process (exit) when an HDF5 call fails in the middle of a write (e.g. a full disk); what can
/// be checked beforehand (sizes, the directory) is checked and reported as InvalidInput.
void write_fclib_local(const std::filesystem::path& path, const FclibLocalProblem& problem,
                       bool include_solution = true);

/// make_fclib_local + write_fclib_local; returns the problem written.
FclibLocalProblem export_fclib_local(const std::filesystem::path& path,
                                     const study::ElasticBody& body, const study::BodyState& state,
                                     const FclibExportOptions& options = {});

/// The De Saxcé natural-map residual of (r, u = W r + q) for the problem, dimensionless:
/// max_i ‖r_i − P_{C_i}(r_i − ρ û_i)‖ / R with R = max(‖r‖_∞, tiny), U = max(‖u‖_∞, ‖q‖_∞,
/// tiny), ρ = R/U and û_i = u_i + (μ_i‖u_T^i‖, 0, …). Zero exactly at a solution; independent
/// of the units. Works for spacedim 2 and 3 (FCLIB's own merit function is 3D only).
double fclib_natural_map_residual(const FclibLocalProblem& problem,
                                  const Eigen::Ref<const Eigen::VectorXd>& r);

}  // namespace frictopt::io
