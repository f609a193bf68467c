// SPDX-License-Identifier: MIT
// The admissible designs Υ as linear constraints on α (docs/theory/problem.md §6, 2D and 3D).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/linear_constraints.hpp"
#include "frictopt/shape/bezier_shape.hpp"

namespace frictopt::shape {

/// Slope-bound scaling (docs/theory/problem.md §6): the thesis' |Δα| ≤ C1/(m−1) (which bounds the
/// true slope by C1/a), or the exact |Δα| ≤ a·C1/(m−1) that bounds |∂G/∂x| by C1.
enum class SlopeScaling { kThesis, kExact };
/// The spellings of SlopeScaling (case files, reports).
inline constexpr auto kSlopeScalingNames = frictopt::detail::make_enum_table<SlopeScaling>(
    std::pair{SlopeScaling::kThesis, "thesis"}, std::pair{SlopeScaling::kExact, "exact"});
[[nodiscard]] inline std::string_view to_string(SlopeScaling scaling) { return kSlopeScalingNames.name(scaling); }

/// Data of Υ (thesis §5.2, with the corrected volume of docs/theory/problem.md §6).
struct AdmissibleSetParameters {
  double upper_bound = 0.0;             ///< C0 > 0: 0 <= α_k <= C0 [m]
  std::optional<double> slope_bound;    ///< C1 > 0; absent: no slope rows
  std::optional<double> volume;         ///< C2: meas Ω(α) [m² in 2D per unit thickness, m³ in 3D]; absent: no equality
  double height = 0.0;                  ///< C4: height of the flat top [m]
  SlopeScaling slope_scaling = SlopeScaling::kThesis;
};

/// Υ = {α : lower <= α <= upper, A_in α <= b_in, A_eq α = b_eq}: the core type, shared with
/// optim and study unchanged (variable_name "alpha", one name per inequality and equality).
using LinearConstraints = frictopt::LinearConstraints;

/// Builds Υ for the shape:
///  * bounds 0 <= α <= C0;
///  * slopes between neighbouring control points, both directions in 3D:
///    |α_{i+1,j} − α_{i,j}| <= δ1, |α_{i,j+1} − α_{i,j}| <= δ2, δ_c = C1/(m_c−1) (thesis) or
///    extent_c·C1/(m_c−1) (exact), as two rows each;
///  * volume: meas Ω(α) = base·C4 − ∫G_α = C2, i.e. Σ_k α_k = d·(base·C4 − C2)/base with
///    base = a (2D) or a·b (3D) — the corrected form of docs/theory/problem.md §6
///    (2D: d(C4 − C2/a)) and its 3D analogue.
/// Throws InvalidInput when a parameter is out of range or the set is obviously empty (the
/// volume asks for a mean height outside [0, C0]).
LinearConstraints make_admissible_set(const BezierShape& shape, const AdmissibleSetParameters& p);

}  // namespace frictopt::shape
