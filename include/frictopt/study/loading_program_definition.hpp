// SPDX-License-Identifier: MIT
// The definition of a quasi-static loading program (docs/theory/loading-program.md): its
// steps, each scaling the body's [[load]], [[dirichlet]] and [[force]] tables. Plain data: the [[program.step]] tables of a case, or a load case's own
// [[load_case.step]] tables (docs/theory/load-cases.md §5); study/loading_program.hpp runs one,
// study/history.hpp puts a cost on its history.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace frictopt::study {

struct BodyDefinition;

/// One step of a program. A scale list is empty (keep the previous step's scales; before step 1
/// every scale is 1, the case as written) or has one entry per [[load]] / [[dirichlet]] /
/// [[force]] of the body, in their order; the step's load is Σ_j scale_j · load_j.
struct LoadStepDefinition {
  std::string label;                    ///< for reports; default "step k"
  std::vector<double> load_scale;       ///< per BodyDefinition::tractions
  std::vector<double> dirichlet_scale;  ///< per BodyDefinition::dirichlet (its displacement)
  std::vector<double> force_scale;      ///< per BodyDefinition::forces
  bool friction = true;                 ///< false: a frictionless step (W = {0})
};

/// The largest number of steps of a loading program (docs/case-format.md, "Size limits"): every
/// step is a contact solve and, in a cost on the history, a kept state; a study's load cases
/// share the bound (LoadCasesDefinition::validate).
inline constexpr std::size_t kMaxProgramSteps = 100'000;

/// [[program.step]] tables; at least one step, at most kMaxProgramSteps.
struct LoadingProgramDefinition {
  std::vector<LoadStepDefinition> steps;
  /// Throws InvalidInput naming "<where>.step[k].field" when there are no steps or a scale
  /// list has the wrong length for `body` (a step referring to a load the case does not have),
  /// a scale is not finite, or there are more than kMaxProgramSteps steps. `where` names the tables: "program" for [[program.step]],
  /// "load_case[j]" for a load case's own [[load_case.step]].
  void validate(const BodyDefinition& body, std::string_view where = "program") const;
  /// The steps with the scales in force at each: every scale list full (an empty list carries
  /// the previous step's over; before step 1 every scale is 1, the case as written).
  [[nodiscard]] std::vector<LoadStepDefinition> scales_in_force(const BodyDefinition& body) const;
};

/// The step tables a program named by `where` comes from, for messages: "[[program.step]]" for
/// "program", "[[load_case.step]]" for "load_case[j]".
[[nodiscard]] std::string step_tables(std::string_view where);

}  // namespace frictopt::study
