// SPDX-License-Identifier: MIT
// The one place that maps [solver] engine to a StateEngine (study/state_engine.hpp).
#pragma once

#include <memory>

#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/state_engine.hpp"

namespace frictopt::study {

/// The engine of definition.engine for the body whose parts `setup` names. Throws InvalidInput
/// naming the [solver] field when the engine cannot solve this body (or was not built).
std::unique_ptr<StateEngine> make_state_engine(const BodyDefinition& definition, const EngineSetup& setup);

}  // namespace frictopt::study
