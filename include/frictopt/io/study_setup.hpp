// SPDX-License-Identifier: MIT
// Turns a validated case description into the numeric modules' definitions (io's enums into
// shape/mesh/fem types). Lives in io because io is the only module that knows both.
#pragma once

#include "frictopt/io/case_description.hpp"
#include "frictopt/optim/bundle_trust.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::io {

/// The body of a case: shape, mesh resolution, material, Γ_u, Γ_p, Υ and α⁰.
[[nodiscard]] study::BodyDefinition make_body_definition(const CaseDescription& description);

/// The cost of a case ([cost] table); throws InvalidInput when the case has none.
[[nodiscard]] study::CostDefinition make_cost_definition(const CaseDescription& description);

/// The bundle trust options of a shape study (study::default_study_options) with the case's
/// [optimization] settings applied.
[[nodiscard]] optim::BundleTrust::Options make_optimizer_options(const CaseDescription& description,
                                                                 const study::ElasticBody& body);

}  // namespace frictopt::io
