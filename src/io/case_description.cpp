// SPDX-License-Identifier: MIT
// Spellings of the case-file enums and the small helpers of the plain case structs.
#include "frictopt/io/case_description.hpp"

#include <functional>
#include <numeric>

#include "case_enums.hpp"

namespace frictopt::io {

std::string_view to_string(Face face) { return detail::kFaceTable.name(face); }
Face parse_face(std::string_view text) { return detail::kFaceTable.parse(text, "face"); }

std::string_view to_string(PlaneModel model) { return detail::kPlaneModelTable.name(model); }
PlaneModel parse_plane_model(std::string_view text) {
  return detail::kPlaneModelTable.parse(text, "material model");
}

std::string_view to_string(SlopeScaling scaling) {
  return detail::kSlopeScalingTable.name(scaling);
}
SlopeScaling parse_slope_scaling(std::string_view text) {
  return detail::kSlopeScalingTable.parse(text, "slope scaling");
}

std::string_view to_string(ContactLaw law) { return detail::kContactLawTable.name(law); }
ContactLaw parse_contact_law(std::string_view text) {
  return detail::kContactLawTable.parse(text, "contact law");
}

std::string_view to_string(FrictionKind kind) { return detail::kFrictionKindTable.name(kind); }
FrictionKind parse_friction_kind(std::string_view text) {
  return detail::kFrictionKindTable.parse(text, "friction kind");
}

std::string_view to_string(CostKind kind) { return detail::kCostKindTable.name(kind); }
CostKind parse_cost_kind(std::string_view text) { return detail::kCostKindTable.parse(text, "cost kind"); }

int DesignSpec::num_control_points() const {
  return std::accumulate(control_points.begin(), control_points.end(), 1, std::multiplies<>());
}

}  // namespace frictopt::io
