// SPDX-License-Identifier: MIT
// Turns a validated case description into the numeric modules' definitions (io's enums into
// shape/mesh/fem types). Lives in io because io is the only module that knows both.
#pragma once

#include "frictopt/io/case_description.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::io {

/// The body of a case: shape, mesh resolution, material, Γ_u, Γ_p, Υ and α⁰.
[[nodiscard]] study::BodyDefinition make_body_definition(const CaseDescription& description);

/// The cost of a case ([cost] table); throws InvalidInput when the case has none.
[[nodiscard]] study::CostDefinition make_cost_definition(const CaseDescription& description);

}  // namespace frictopt::io
