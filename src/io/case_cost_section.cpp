// SPDX-License-Identifier: MIT
#include "case_cost_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "case_table_common.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/cost_factory.hpp"

namespace frictopt::io::detail {
namespace {

TableReader cost_table(const TableReader& top, std::string_view origin) {
  return required_table(top, "cost", origin, {"kind", "target", "exponent", "smoothing", "step"});
}

// [cost] step and the rules of how the cost combines with the loads it reads
// (study::find_combination_problem, worded in the model's terms; here with the file's line and
// key): the state after step `step` of the [[program.step]] tables — or, with load cases given
// as programs ([[load_case.step]]), of every case's program (a static case is one step).
void read_cost_history(const TableReader& r, const std::optional<study::LoadingProgramDefinition>& program,
                       study::CostDefinition& c) {
  if (program) c.program = std::make_shared<const study::LoadingProgramDefinition>(*program);
  // The step as the model reads it (0 = "last"); `named` is what the rules see: "last" names a
  // step too (1 exists in every history), anything but "last" or an integer >= 1 none that exists.
  std::optional<int> named;
  if (const toml::node* step = r.node("step")) {
    named = -1;
    if (step->is_string() && step->value<std::string>().value_or("") == "last") {
      c.step = 0;
      named = 1;
    } else if (const std::int64_t k = step->value<std::int64_t>().value_or(0); step->is_integer() && k >= 1) {
      c.step = static_cast<int>(std::min<std::int64_t>(k, std::numeric_limits<int>::max()));
      named = c.step;
    }
  }
  study::CostDefinition checked = c;
  if (named) checked.step = *named;
  const std::optional<study::CostCombinationProblem> problem = study::find_combination_problem(checked);
  if (!problem) return;
  switch (problem->part) {
    case study::CostCombinationProblem::Part::kKind: r.fail_value("kind", problem->expectation);
    case study::CostCombinationProblem::Part::kStep: r.fail_value("step", problem->expectation);
    case study::CostCombinationProblem::Part::kLoads:
      r.fail("step", fmt::format("[[program.step]] tables with [[load_case]] tables; expected {} ([[load_case.step]] "
                                 "tables)",
                                 problem->expectation));
  }
}

// [cost] into the study's cost definition (docs/theory/costs.md). `dim` checks the traction target.
study::CostDefinition read_cost(const TableReader& r, int dim) {
  using cost::CostKind;
  study::CostDefinition c;
  const std::string kind_what = fmt::format("one of {}", cost::kCostKindNames.spellings());
  (void)r.required_string("kind", kind_what);
  c.kind = *read_enum(r, "kind", cost::kCostKindNames);
  // The pressure norm's default exponent differs from the force power's (thesis: 4).
  if (c.kind == CostKind::kPressureNorm) c.exponent = 8.0;
  if (c.kind == CostKind::kTargetPressure) {
    const toml::node* target = r.node("target");
    if (target == nullptr) r.fail_missing("target", "a target pressure [Pa] or \"initial_mean\"");
    if (target->is_string()) {
      if (target->value<std::string>().value_or("") != "initial_mean")
        r.fail_value("target", "a number (pressure in Pa) or \"initial_mean\"");
      // NaN: the initial total normal force spread as a uniform pressure (study::CostDefinition).
      c.target_pressure = std::numeric_limits<double>::quiet_NaN();
    } else {
      c.target_pressure = r.required_number("target", "a target pressure [Pa] or \"initial_mean\"");
      if (!(c.target_pressure >= 0)) r.fail_value("target", "target >= 0");
    }
  } else if (c.kind == CostKind::kTractionUniformity) {
    // Optional: "mean" (the default), "initial_mean" or the target traction [Pa], dim − 1 numbers.
    if (const toml::node* target = r.node("target"); target != nullptr) {
      if (target->is_string()) {
        const std::string word = target->value<std::string>().value_or("");
        if (word != "mean" && word != "initial_mean")
          r.fail_value("target", "\"mean\", \"initial_mean\" or a list of dim − 1 tangential tractions [Pa]");
        c.target_traction_initial_mean = word == "initial_mean";
      } else {
        const std::vector<double> t = r.number_list("target", "the target tangential traction [Pa]");
        if (t.size() != static_cast<std::size_t>(dim - 1))
          r.fail("target", fmt::format("cost.target has {} components; expected {} (the tangential traction [Pa] of "
                                       "a {}D body) or \"mean\"",
                                       t.size(), dim - 1, dim));
        c.target_traction = Eigen::Map<const Eigen::VectorXd>(t.data(), static_cast<Eigen::Index>(t.size()));
      }
    }
  } else if (r.has("target")) {
    r.fail_value("target", "no target for this kind (only target_pressure and traction_uniformity have one)");
  }
  if (const std::optional<double> exponent = r.optional_number("exponent")) {
    if (c.kind != CostKind::kNormalForcePower && c.kind != CostKind::kPressureNorm)
      r.fail_value("exponent", "no exponent for this kind");
    if (!(*exponent >= 2)) r.fail_value("exponent", "exponent >= 2");
    c.exponent = *exponent;
  }
  if (const std::optional<double> smoothing = r.optional_number("smoothing")) {
    if (c.kind != CostKind::kTotalSlip) r.fail_value("smoothing", "no smoothing for this kind");
    if (!(*smoothing > 0)) r.fail_value("smoothing", "smoothing > 0");
    c.smoothing = *smoothing;
  }
  return c;
}

}  // namespace

std::optional<study::CostDefinition> read_cost_section(const TableReader& top, std::string_view origin, int dim,
                                                       bool has_contact) {
  if (!top.optional_table("cost")) return std::nullopt;
  if (!has_contact)
    throw InvalidInput(fmt::format("{}: [cost] needs a [contact] table: every cost reads the contact state", origin));
  return read_cost(cost_table(top, origin), dim);
}

void read_cost_step(const TableReader& top, std::string_view origin,
                    const std::optional<study::LoadingProgramDefinition>& program, study::CostDefinition& cost) {
  read_cost_history(cost_table(top, origin), program, cost);
}

}  // namespace frictopt::io::detail
