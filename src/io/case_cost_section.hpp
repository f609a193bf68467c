// SPDX-License-Identifier: MIT
// The case's [cost] table (docs/case-format.md, "[cost]"; docs/theory/costs.md): the cost's kind
// and parameters, and the step of a loading history it reads, checked against the loads by the
// model's combination rules (study::find_combination_problem). Private to io; called by
// case_file.cpp.
#pragma once

#include <optional>
#include <string_view>

#include "frictopt/study/body_definition.hpp"
#include "frictopt/study/loading_program_definition.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [cost] without its step (nullopt without [cost]); refused without contact (`has_contact`).
std::optional<study::CostDefinition> read_cost_section(const TableReader& top, std::string_view origin, int dim,
                                                       bool has_contact);
/// [cost] step, once the loads are read (the case's program and load cases, in `cost`), and the
/// combination rules of the cost with those loads: the refusal names cost.kind or cost.step.
void read_cost_step(const TableReader& top, std::string_view origin,
                    const std::optional<study::LoadingProgramDefinition>& program, study::CostDefinition& cost);

}  // namespace frictopt::io::detail
