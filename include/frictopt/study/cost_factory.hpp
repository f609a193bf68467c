// SPDX-License-Identifier: MIT
// From a CostDefinition (study/body_definition.hpp) to the cost functional of one state, and the
// rule of which costs read the state at the initial design (docs/theory/costs.md).
#pragma once

#include <memory>

#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {

/// Whether the cost of `definition` reads the state at the initial design: a target pressure or
/// a target traction given as "initial_mean" (the mean of that state).
bool needs_initial_state(const CostDefinition& definition);

/// Builds the cost of `definition` for `body`; a cost that needs_initial_state() reads
/// `initial_state` when given, else the state is solved here (ShapeOracle and ProgramHistory
/// pass their own, so that it is not solved twice). Throws InvalidInput for a cost that is not
/// one state's (dissipation: a loading program's), NumericalFailure when that state failed.
std::unique_ptr<cost::CostFunctional> make_cost(const CostDefinition& definition, ElasticBody& body,
                                                const BodyState* initial_state = nullptr);

}  // namespace frictopt::study
