// SPDX-License-Identifier: MIT
// The spelling tables of the case-file enums, shared by case_description.cpp (to_string,
// parse_*) and the case parser (which adds the field and line to its messages).
#pragma once

#include "frictopt/core/enum_table.hpp"
#include "frictopt/io/case_description.hpp"

namespace frictopt::io::detail {

using frictopt::detail::EnumTable;
using frictopt::detail::make_enum_table;

inline constexpr auto kFaceTable = make_enum_table<Face>(
    std::pair{Face::kLeft, "left"}, std::pair{Face::kRight, "right"},
    std::pair{Face::kFront, "front"}, std::pair{Face::kBack, "back"}, std::pair{Face::kTop, "top"});

inline constexpr auto kPlaneModelTable =
    make_enum_table<PlaneModel>(std::pair{PlaneModel::kPlaneStrain, "plane_strain"},
                                std::pair{PlaneModel::kPlaneStress, "plane_stress"});

inline constexpr auto kSlopeScalingTable = make_enum_table<SlopeScaling>(
    std::pair{SlopeScaling::kThesis, "thesis"}, std::pair{SlopeScaling::kExact, "exact"});

inline constexpr auto kContactLawTable =
    make_enum_table<ContactLaw>(std::pair{ContactLaw::kCoulomb, "coulomb"});

inline constexpr auto kFrictionKindTable = make_enum_table<FrictionKind>(
    std::pair{FrictionKind::kNone, "none"}, std::pair{FrictionKind::kIsotropic, "isotropic"},
    std::pair{FrictionKind::kPolygon, "polygon"}, std::pair{FrictionKind::kEllipse, "ellipse"},
    std::pair{FrictionKind::kEllipseExact, "ellipse_exact"},
    std::pair{FrictionKind::kDiscExact, "disc_exact"});

inline constexpr auto kCostKindTable = make_enum_table<CostKind>(
    std::pair{CostKind::kTargetPressure, "target_pressure"},
    std::pair{CostKind::kNormalForcePower, "normal_force_power"}, std::pair{CostKind::kCompliance, "compliance"},
    std::pair{CostKind::kPressureNorm, "pressure_norm"}, std::pair{CostKind::kTotalSlip, "total_slip"},
    std::pair{CostKind::kTractionUniformity, "traction_uniformity"});

}  // namespace frictopt::io::detail
