// SPDX-License-Identifier: MIT
#include "frictopt/study/load_cases.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <set>

#include "frictopt/core/error.hpp"
#include "frictopt/study/loading_program.hpp"

namespace frictopt::study {
namespace {

void check_scales(const std::vector<double>& scales, std::size_t expected, std::size_t k, const char* field,
                  const char* table) {
  if (scales.empty()) return;
  if (scales.size() != expected)
    throw InvalidInput(fmt::format("load_case[{}].{} has {} entries, but the case has {} [[{}]] table{}; expected one "
                                   "scale per [[{}]] (or none: every scale 1)",
                                   k, field, scales.size(), expected, table, expected == 1 ? "" : "s", table));
  for (std::size_t j = 0; j < scales.size(); ++j)
    if (!std::isfinite(scales[j]))
      throw InvalidInput(fmt::format("load_case[{}].{}[{}] = {}; expected a finite number", k, field, j, scales[j]));
}

}  // namespace

void LoadCasesDefinition::validate(std::size_t num_tractions, std::size_t num_dirichlet, std::size_t num_forces) const {
  if (cases.empty())
    throw InvalidInput("load_case: no load case; expected at least one [[load_case]] table");
  if (cases.size() > kMaxLoadCases)
    throw InvalidInput(fmt::format("load_case: {} load cases; expected at most {} [[load_case]] tables (every "
                                   "evaluation solves each; docs/case-format.md, \"Size limits\")",
                                   cases.size(), kMaxLoadCases));
  std::size_t total_steps = 0;
  for (const LoadCaseDefinition& c : cases) total_steps += c.num_steps();
  if (total_steps > kMaxProgramSteps)
    throw InvalidInput(fmt::format("load_case.step: the load cases have {} steps in all; expected at most {} (every "
                                   "evaluation solves each; docs/case-format.md, \"Size limits\")",
                                   total_steps, kMaxProgramSteps));
  std::set<std::string> names;
  double total_weight = 0.0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const LoadCaseDefinition& c = cases[k];
    if (c.name.empty()) throw InvalidInput(fmt::format("load_case[{}].name is empty; expected a name", k));
    if (!names.insert(c.name).second)
      throw InvalidInput(fmt::format("load_case[{}].name = \"{}\" is used by an earlier case; expected unique names", k,
                                     c.name));
    if (c.program && !(c.load_scale.empty() && c.dirichlet_scale.empty() && c.force_scale.empty()))
      throw InvalidInput(fmt::format("load_case[{}] (\"{}\") has both scale lists and [[load_case.step]] tables; expected "
                                     "one of them: the scales of a static load, or steps that each give their own",
                                     k, c.name));
    if (c.program && c.program->steps.empty())
      throw InvalidInput(fmt::format("load_case[{}].step: the program has no steps; expected at least one "
                                     "[[load_case.step]] table",
                                     k));
    check_scales(c.load_scale, num_tractions, k, "load_scale", "load");
    check_scales(c.dirichlet_scale, num_dirichlet, k, "dirichlet_scale", "dirichlet");
    check_scales(c.force_scale, num_forces, k, "force_scale", "force");
    if (!(std::isfinite(c.weight) && c.weight >= 0.0))
      throw InvalidInput(fmt::format("load_case[{}].weight = {}; expected a finite number >= 0", k, c.weight));
    total_weight += c.weight;
  }
  if (!(total_weight > 0.0))
    throw InvalidInput(fmt::format("load_case.weight: all {} weights are 0; expected at least one > 0 (a zero weight "
                                   "drops a case from the objective)",
                                   cases.size()));
}

LoadingProgramDefinition LoadCaseDefinition::as_program() const {
  if (program) return *program;
  return LoadingProgramDefinition{{LoadStepDefinition{name, load_scale, dirichlet_scale, force_scale, true}}};
}

bool LoadCasesDefinition::has_programs() const {
  for (const LoadCaseDefinition& c : cases)
    if (c.program) return true;
  return false;
}

LoadCases::LoadCases(const ElasticBody& body, LoadCasesDefinition definition)
    : body_(body), definition_(std::move(definition)) {
  const BodyDefinition& def = body_.definition();
  definition_.validate(def.tractions.size(), def.dirichlet.size(), def.forces.size());
  for (std::size_t k = 0; k < definition_.cases.size(); ++k)
    if (definition_.cases[k].program) definition_.cases[k].program->validate(def, fmt::format("load_case[{}]", k));
  if (!body_.contact_boundary())
    throw InvalidInput("load_case: load cases combine a contact cost; expected a [contact] table");
}

Eigen::VectorXd LoadCases::load_change_shape_derivative(int k, const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                        const Eigen::Ref<const Eigen::VectorXd>& psi) const {
  const LoadCaseDefinition& c = (*this)[k];
  Eigen::VectorXd out = Eigen::VectorXd::Zero(body_.definition().shape.num_controls());
  if (c.load_scale.empty()) return out;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(body_.mesh().num_dofs());
  for (std::size_t j = 0; j < c.load_scale.size(); ++j) {
    const double change = c.load_scale[j] - 1.0;
    if (change == 0.0) continue;
    // The body's kernel of load j (built on first use, shared by every case and step).
    // shape_derivative(X, 0, ψ) = ∇_α[ψᵀ(A·0 − l_j(α))] = −∇_α[ψᵀ l_j(α)].
    out += change * body_.traction_kernel(j).shape_derivative(X, zero, psi);
  }
  return out;
}

CombinedValue LoadCases::combine(std::span<const double> values) const {
  FRICTOPT_ASSERT(values.size() == definition_.cases.size(), "one value per load case");
  CombinedValue out;
  double largest = -std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (definition_.cases[k].weight == 0.0) continue;  // dropped from Θ (and never selected)
    const double weighted = definition_.cases[k].weight * values[k];
    sum += weighted;
    // Strictly greater: a tie keeps the lower index (a deterministic choice; docs/theory/load-cases.md).
    if (out.selected < 0 || weighted > largest) {
      largest = weighted;
      out.selected = static_cast<int>(k);
    }
  }
  out.value = definition_.combine == CaseCombination::kWorst ? largest : sum;
  return out;
}

}  // namespace frictopt::study
