// SPDX-License-Identifier: MIT
// Load cases of a study (docs/theory/load-cases.md): the same body at
// the same design under K load sets, the cost J evaluated on each, combined into one objective
// Θ(α) = max_k w_k J_k(α) ("worst") or Σ_k w_k J_k(α) ("weighted"). Plain definitions only (the
// case file's [[load_case]] tables and [study] combine); study/load_cases.hpp solves them.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/study/loading_program_definition.hpp"

namespace frictopt::study {

/// How the cases' costs J_k combine into the one objective Θ the optimizer sees.
enum class CaseCombination {
  kWorst,    ///< Θ = max_k w_k J_k: the design must be good under every load (nonsmooth at ties)
  kWeighted  ///< Θ = Σ_k w_k J_k: an average service life over the loads
};

/// The spellings of CaseCombination ([study] combine, summaries).
inline constexpr auto kCaseCombinationNames = frictopt::detail::make_enum_table<CaseCombination>(
    std::pair{CaseCombination::kWorst, "worst"}, std::pair{CaseCombination::kWeighted, "weighted"});

[[nodiscard]] inline std::string_view to_string(CaseCombination c) { return kCaseCombinationNames.name(c); }
/// Inverse of to_string; throws InvalidInput listing the accepted spellings.
[[nodiscard]] inline CaseCombination parse_case_combination(std::string_view text) {
  return kCaseCombinationNames.parse(text, "study.combine");
}

/// One load case: the body's own [[load]], [[dirichlet]] and [[force]] tables scaled, as one step
/// of a loading program is (study/loading_program.hpp): the case's load is Σ_j scale_j · load_j.
/// An empty scale list means every scale 1 (the case file as written). Or a loading program of its
/// own ([[load_case.step]] tables): the case's cost then reads that history ([cost] step or the
/// dissipation; study/history.hpp), and its scale lists stay empty.
struct LoadCaseDefinition {
  std::string name;                     ///< unique among the cases; reports and [study] cases
  std::vector<double> load_scale;       ///< per BodyDefinition::tractions
  std::vector<double> dirichlet_scale;  ///< per BodyDefinition::dirichlet (its displacement)
  std::vector<double> force_scale;      ///< per BodyDefinition::forces
  double weight = 1.0;                  ///< w_k >= 0
  std::optional<LoadingProgramDefinition> program;  ///< [[load_case.step]]; none: one static load

  /// The case as a loading program: its own, or one step with its scales (the static load; a
  /// one-step program solves exactly the static problem, study/history.hpp).
  [[nodiscard]] LoadingProgramDefinition as_program() const;
  /// The number of states its cost may read: its program's steps, 1 for a static load.
  [[nodiscard]] std::size_t num_steps() const { return program ? program->steps.size() : 1; }
};

/// The largest number of load cases of a study (docs/case-format.md, "Size limits"): every
/// evaluation of the objective solves every case.
inline constexpr std::size_t kMaxLoadCases = 1'000;

/// [[load_case]] tables with [study] combine.
struct LoadCasesDefinition {
  CaseCombination combine = CaseCombination::kWorst;
  std::vector<LoadCaseDefinition> cases;
  /// Throws InvalidInput naming "load_case[k].field": no case, an empty or duplicate name, a
  /// scale list whose length is not the number of the body's tables of its kind (given here),
  /// a scale that is not finite, a weight that is negative or not finite, all weights zero, or
  /// a case with both scale lists and [[load_case.step]] tables (or a program with no steps),
  /// more than kMaxLoadCases cases, or more than kMaxProgramSteps steps over all the cases.
  void validate(std::size_t num_tractions, std::size_t num_dirichlet, std::size_t num_forces) const;
  /// True when some case has its own loading program.
  [[nodiscard]] bool has_programs() const;
};

}  // namespace frictopt::study
