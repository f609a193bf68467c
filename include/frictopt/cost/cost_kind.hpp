// SPDX-License-Identifier: MIT
// The cost functionals a study can name (docs/theory/costs.md), with their one spelling table: case
// files, summaries and the CLI read and print these names.
#pragma once

#include <string_view>

#include "frictopt/core/enum_table.hpp"

namespace frictopt::cost {

enum class CostKind {
  kTargetPressure,     ///< Σ(λ̄ − λ)² with λ̄_i = p̄·a_i (thesis ex. 5.2.1)
  kNormalForcePower,   ///< Σ λ_i^p (thesis ex. 5.2.2 with p = 4)
  kCompliance,         ///< −uᵀAu + lᵀu (thesis ex. 5.2.3)
  kPressureNorm,       ///< (Σ a_i p_i^p)^{1/p}: smooth peak-pressure surrogate
  kTotalSlip,          ///< Σ √(|u_t|² + δ²) − δ
  kTractionUniformity,  ///< Σ a_i ‖t_i − t̄‖²: tangential traction about a target or its mean
  /// Σ_k Σ_i ⟨q_i^k, Δu_t^{i,k}⟩: the work friction dissipates over a loading program (a
  /// history cost, study/history.hpp; docs/theory/history-adjoint.md)
  kDissipation
};

/// The spellings of CostKind (case files, summaries, messages).
inline constexpr auto kCostKindNames = frictopt::detail::make_enum_table<CostKind>(
    std::pair{CostKind::kTargetPressure, "target_pressure"},
    std::pair{CostKind::kNormalForcePower, "normal_force_power"}, std::pair{CostKind::kCompliance, "compliance"},
    std::pair{CostKind::kPressureNorm, "pressure_norm"}, std::pair{CostKind::kTotalSlip, "total_slip"},
    std::pair{CostKind::kTractionUniformity, "traction_uniformity"},
    std::pair{CostKind::kDissipation, "dissipation"});

[[nodiscard]] inline std::string_view to_string(CostKind kind) { return kCostKindNames.name(kind); }
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
[[nodiscard]] inline CostKind parse_cost_kind(std::string_view text) {
  return kCostKindNames.parse(text, "cost kind");
}

}  // namespace frictopt::cost
