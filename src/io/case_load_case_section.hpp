// SPDX-License-Identifier: MIT
// The case-file sections of load cases (docs/theory/load-cases.md): [[load_case]] (a name, the
// case's scales of [[load]] / [[dirichlet]] / [[force]] tables or a loading program of its own in
// [[load_case.step]] tables, a weight) and [study] (combine = "worst" | "weighted", and optionally
// the subset `cases` to combine). Called once from parse_case after [cost] is read, before
// [cost] step is checked against the cases' programs. Schema: docs/case-format.md.
#pragma once

#include <string_view>

#include "frictopt/io/case_description.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads [[load_case]] and [study] into c.cost->load_cases. Throws InvalidInput "origin:line:
/// field = value; expected ..." (or "origin: load_case[k].field ...") for bad input: [study]
/// without [[load_case]], load cases without [cost], an unknown combination or case name,
/// duplicate names, scale lists of the wrong length, negative or all-zero weights, scales and
/// steps in one case, a step's scale list of the wrong length.
void read_load_case_sections(const TableReader& top, std::string_view origin, CaseDescription& c);

}  // namespace frictopt::io::detail
