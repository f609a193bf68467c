// SPDX-License-Identifier: MIT
#include "case_load_case_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "case_program_section.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

std::vector<double> scales(const TableReader& r, std::string_view key) {
  if (!r.has(key)) return {};
  const std::vector<double> v = r.number_list(key, "a list of finite scale factors");
  if (v.empty()) r.fail_value(key, "a non-empty list of scale factors (omit the key: every scale 1)");
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) r.fail_entry(key, i, "a finite number");
  return v;
}

study::LoadCaseDefinition read_load_case(const TableReader& r, std::string_view origin, const study::BodyDefinition& body,
                                         std::size_t k) {
  study::LoadCaseDefinition c;
  c.name = r.required_string("name", "the case's name (unique among the [[load_case]] tables)");
  if (c.name.empty()) r.fail_value("name", "a non-empty name");
  c.load_scale = scales(r, "load_scale");
  c.dirichlet_scale = scales(r, "dirichlet_scale");
  c.force_scale = scales(r, "force_scale");
  if (const auto w = r.optional_number("weight")) {
    if (!(std::isfinite(*w) && *w >= 0.0)) r.fail_value("weight", "a finite weight >= 0");
    c.weight = *w;
  }
  if (r.has("step")) {
    // A load case given as a loading program (docs/theory/load-cases.md §5): its own steps, which
    // give the scales; the case's cost reads its history ([cost] step or the dissipation).
    for (const char* key : {"load_scale", "dirichlet_scale", "force_scale"})
      if (r.has(key))
        r.fail(key, fmt::format("load_case[{}].{} with [[load_case.step]] tables; expected either the scales of a static "
                                "load or steps (each step gives its own scales)",
                                k, key));
    c.program = read_program(r, origin, body, fmt::format("load_case[{}]", k));
  }
  return c;
}

}  // namespace

void read_load_case_sections(const TableReader& top, std::string_view origin, CaseDescription& c) {
  const toml::array* tables = top.optional_table_array("load_case", study::kMaxLoadCases);
  const toml::table* study_table = top.optional_table("study");
  if (tables == nullptr && study_table == nullptr) return;
  if (tables == nullptr || tables->empty())
    top.fail_missing("load_case", "at least one [[load_case]] table ([study] combines the costs of load cases)");
  if (!c.cost)
    top.fail("load_case", fmt::format("{}: [[load_case]] tables combine a cost over loads; expected a [cost] table",
                                      origin));
  study::LoadCasesDefinition cases;
  for (std::size_t k = 0; k < tables->size(); ++k) {
    const toml::table* t = tables->get(k)->as_table();
    const TableReader r(*t, fmt::format("load_case[{}]", k), origin,
                        {"name", "load_scale", "dirichlet_scale", "force_scale", "weight", "step"});
    cases.cases.push_back(read_load_case(r, origin, c.body, k));
    for (std::size_t j = 0; j < k; ++j)
      if (cases.cases[j].name == cases.cases[k].name)
        r.fail("name", fmt::format("load_case[{}].name = \"{}\" is the name of load_case[{}]; expected unique names", k,
                                   cases.cases[k].name, j));
  }
  if (study_table != nullptr) {
    const TableReader s(*study_table, "study", origin, {"combine", "cases"});
    if (const auto combine = s.optional_string("combine")) {
      try {
        cases.combine = study::parse_case_combination(*combine);
      } catch (const InvalidInput&) {
        s.fail_value("combine", fmt::format("one of {}", study::kCaseCombinationNames.spellings()));
      }
    }
    if (s.has("cases")) {
      // A subset of the cases, e.g. the single-load design of a worst-case study.
      const toml::array* names = s.node("cases")->as_array();
      if (names == nullptr || names->empty()) s.fail_value("cases", "a non-empty list of [[load_case]] names");
      std::vector<study::LoadCaseDefinition> chosen;
      for (std::size_t i = 0; i < names->size(); ++i) {
        const auto name = names->get(i)->value<std::string>();
        if (!name) s.fail_entry("cases", i, "the name of a [[load_case]] (a string)");
        const auto it = std::find_if(cases.cases.begin(), cases.cases.end(),
                                     [&](const study::LoadCaseDefinition& d) { return d.name == *name; });
        if (it == cases.cases.end()) {
          std::string known;
          for (const auto& d : cases.cases) known += (known.empty() ? "\"" : ", \"") + d.name + "\"";
          s.fail_entry("cases", i, fmt::format("the name of a [[load_case]]: one of {}", known));
        }
        for (const auto& d : chosen)
          if (d.name == *name) s.fail_entry("cases", i, "a name not listed before");
        chosen.push_back(*it);
      }
      cases.cases = std::move(chosen);
    }
  }
  try {
    cases.validate(c.body.tractions.size(), c.body.dirichlet.size(), c.body.forces.size());
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", origin, e.what()));
  }
  c.cost->load_cases = std::move(cases);
}

}  // namespace frictopt::io::detail
