// SPDX-License-Identifier: MIT
#include "frictopt/study/cost_factory.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "frictopt/core/error.hpp"

namespace frictopt::study {

bool needs_initial_state(const CostDefinition& definition) {
  return (definition.kind == cost::CostKind::kTargetPressure && std::isnan(definition.target_pressure)) ||
         (definition.kind == cost::CostKind::kTractionUniformity && definition.target_traction_initial_mean);
}

std::optional<CostCombinationProblem> find_combination_problem(const CostDefinition& d) {
  using Part = CostCombinationProblem::Part;
  const auto problem = [](Part part, std::string expectation) {
    return std::optional<CostCombinationProblem>(CostCombinationProblem{part, std::move(expectation)});
  };
  if (d.program && d.load_cases)
    return problem(Part::kLoads, "a loading program or load cases, not both (the program would apply to no case in "
                                 "particular; a load case may be given as its own loading program)");
  if (d.kind == cost::CostKind::kCompliance && (d.program || d.load_cases))
    return problem(Part::kKind, "a contact cost (target_pressure, normal_force_power, pressure_norm, total_slip, "
                                "traction_uniformity) or \"dissipation\" with a loading program or load cases (the "
                                "compliance reads the case's own loads, not a step's or a case's)");
  // The fewest steps of the histories the cost reads: a step beyond it would read a state that
  // history does not have.
  std::size_t steps = d.program ? d.program->steps.size() : 1;
  std::string fewest = fmt::format("the loading program has {} step{}", steps, steps == 1 ? "" : "s");
  const bool case_programs = d.load_cases && d.load_cases->has_programs();
  if (case_programs) {
    steps = std::numeric_limits<std::size_t>::max();
    for (std::size_t k = 0; k < d.load_cases->cases.size(); ++k) {
      const LoadCaseDefinition& lc = d.load_cases->cases[k];
      if (lc.num_steps() >= steps) continue;
      steps = lc.num_steps();
      fewest = lc.program ? fmt::format("load case {} \"{}\" has {} step{}", k + 1, lc.name, steps, steps == 1 ? "" : "s")
                          : fmt::format("load case {} \"{}\" is a static load: one step", k + 1, lc.name);
    }
  }
  const bool history = d.program || case_programs;
  if (!history && d.kind == cost::CostKind::kDissipation)
    return problem(Part::kKind, "a cost of one state (the loads are one step, without a loading program: "
                                "\"dissipation\" is a history cost on a one-step case)");
  if (!history && d.step != 0)
    return problem(Part::kStep, "no step: the loads are one step, without a loading program or load cases given as "
                                "programs (a history cost on a one-step case)");
  if (history && d.kind == cost::CostKind::kDissipation && d.step != 0)
    return problem(Part::kStep, "no step for \"dissipation\" (it reads every step of the program)");
  if (history && (d.step < 0 || static_cast<std::size_t>(d.step) > steps))
    return problem(Part::kStep, fmt::format("\"last\" or an integer step in [1, {}] ({})", steps, fewest));
  return std::nullopt;
}

void validate_combination(const CostDefinition& definition) {
  if (const auto problem = find_combination_problem(definition))
    throw InvalidInput("cost: expected " + problem->expectation);
}

std::unique_ptr<cost::CostFunctional> make_cost(const CostDefinition& definition, ElasticBody& body,
                                                const BodyState* initial_state) {
  using Kind = cost::CostKind;
  // The state at α⁰ for "initial_mean" targets: the caller's, or solved here.
  std::optional<BodyState> solved;
  const auto initial = [&](const char* what) -> const BodyState& {
    if (!initial_state) solved = body.solve(body.initial_design(), "initial design");
    const BodyState& s = initial_state ? *initial_state : *solved;
    if (s.summary.status != Status::kConverged)
      throw NumericalFailure(std::string("cost ") + what + " = initial_mean: the state at the initial design did not solve: " +
                             s.summary.message);
    return s;
  };
  switch (definition.kind) {
    case Kind::kTargetPressure: {
      if (!body.contact_boundary()) throw InvalidInput("cost target_pressure needs a body in contact");
      const Eigen::VectorXd& areas = body.contact_boundary()->tributary_areas();
      double pressure = definition.target_pressure;
      if (std::isnan(pressure)) {
        const BodyState& s = initial("target_pressure");
        pressure = s.contact->state.normal_forces().sum() / areas.sum();
      }
      return cost::make_target_normal_force(pressure * areas);
    }
    case Kind::kNormalForcePower: return cost::make_normal_force_power(definition.exponent);
    case Kind::kCompliance: return cost::make_compliance();
    case Kind::kPressureNorm: return cost::make_pressure_norm(definition.exponent);
    case Kind::kTotalSlip: return cost::make_total_slip(definition.smoothing);
    case Kind::kTractionUniformity: {
      if (!definition.target_traction_initial_mean) return cost::make_traction_uniformity(definition.target_traction);
      if (!body.contact_boundary()) throw InvalidInput("cost traction_uniformity needs a body in contact");
      const contact::ContactState& cs = initial("traction_uniformity target").contact->state;
      const int nt = cs.dim - 1;
      Eigen::VectorXd mean = Eigen::VectorXd::Zero(nt);
      for (Eigen::Index i = 0; i < cs.num_nodes(); ++i)
        for (int c = 0; c < nt; ++c) mean(c) -= cs.z(cs.dim * i + c);  // τ_i = −q_i
      return cost::make_traction_uniformity(mean / body.contact_boundary()->tributary_areas().sum());
    }
    case Kind::kDissipation:
      throw InvalidInput("cost.kind = \"dissipation\" reads the history of a loading program: a history cost on a "
                         "one-step case; expected [[program.step]] tables (study::ProgramHistory evaluates it)");
  }
  return nullptr;
}

}  // namespace frictopt::study
