// SPDX-License-Identifier: MIT
// Isotropic linear elastic material (docs/theory/problem.md §4; thesis (3.1.1)–(3.1.2)).
#pragma once

#include <string_view>

#include "frictopt/core/enum_table.hpp"

namespace frictopt::fem {

/// 2D model (docs/theory/problem.md §4): plane strain (default, unit thickness) or plane stress.
enum class PlaneModel { kPlaneStrain, kPlaneStress };
/// The spellings of PlaneModel (case files, reports).
inline constexpr auto kPlaneModelNames = frictopt::detail::make_enum_table<PlaneModel>(
    std::pair{PlaneModel::kPlaneStrain, "plane_strain"}, std::pair{PlaneModel::kPlaneStress, "plane_stress"});
[[nodiscard]] inline std::string_view to_string(PlaneModel model) { return kPlaneModelNames.name(model); }
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
[[nodiscard]] inline PlaneModel parse_plane_model(std::string_view name) {
  return kPlaneModelNames.parse(name, "material.model");
}

/// Hooke's law τ = λ tr(ε) I + 2μ ε with Lamé constants from E and ν.
struct IsotropicMaterial {
  double young = 0.0;    ///< E > 0 [Pa]
  double poisson = 0.0;  ///< 0 <= ν < 0.5
  PlaneModel plane_model = PlaneModel::kPlaneStrain;  ///< used in 2D only

  /// Throws InvalidInput naming the field when E <= 0 or ν outside [0, 0.5).
  void validate() const;
  /// μ = E / (2(1+ν)).
  double shear_modulus() const { return young / (2.0 * (1.0 + poisson)); }
  /// λ = Eν/((1+ν)(1−2ν)); in 2D plane stress λ* = 2λμ/(λ+2μ) (docs/theory/problem.md §4).
  double lame_lambda(int dim) const;
};

}  // namespace frictopt::fem
