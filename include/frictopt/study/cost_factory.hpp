// SPDX-License-Identifier: MIT
// From a CostDefinition (study/body_definition.hpp) to the cost functional of one state, the
// rule of which costs read the state at the initial design (docs/theory/costs.md), and the rules
// of how a cost combines with the loads it reads (a loading program, load cases).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "frictopt/cost/cost_functional.hpp"
#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::study {

/// Whether the cost of `definition` reads the state at the initial design: a target pressure or
/// a target traction given as "initial_mean" (the mean of that state).
bool needs_initial_state(const CostDefinition& definition);

/// A rule of how a cost combines with the loads it reads that a definition breaks
/// (docs/theory/history-adjoint.md, docs/theory/load-cases.md), in the model's words: which part is
/// wrong and what is expected. The case reader adds the file, line and key (cost.kind, cost.step).
struct CostCombinationProblem {
  enum class Part {
    kKind,  ///< the cost's kind does not fit the loads (the compliance with a program, ...)
    kStep,  ///< the step the cost reads does not exist (or means nothing: the dissipation)
    kLoads  ///< a loading program and load cases together
  };
  Part part = Part::kKind;
  std::string expectation;  ///< "expected ..." without the word "expected"
};

/// The first combination rule `definition` breaks, or nullopt. The rules: a loading program and
/// load cases exclude each other (the program would apply to no case in particular); a history
/// cost (the dissipation, or a step) needs loads of more than one step — a program, or load cases
/// given as programs; the step is "last" (0) or within the fewest steps any history has; the
/// dissipation reads every step (no step); the compliance reads the case's own loads, so neither
/// a program nor load cases.
std::optional<CostCombinationProblem> find_combination_problem(const CostDefinition& definition);
/// Throws InvalidInput("cost: ... expected ...") for find_combination_problem's problem.
void validate_combination(const CostDefinition& definition);

/// Builds the cost of `definition` for `body`; a cost that needs_initial_state() reads
/// `initial_state` when given, else the state is solved here (ShapeOracle and ProgramHistory
/// pass their own, so that it is not solved twice). Throws InvalidInput for a cost that is not
/// one state's (dissipation: a loading program's), NumericalFailure when that state failed.
std::unique_ptr<cost::CostFunctional> make_cost(const CostDefinition& definition, ElasticBody& body,
                                                const BodyState* initial_state = nullptr);

}  // namespace frictopt::study
