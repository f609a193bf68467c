// SPDX-License-Identifier: MIT
// The case-file sections of friction experiments (docs/experiments.md): [[force]] (point and
// node-set forces), [[program.step]] (a quasi-static loading program) and [experiment] (the virtual
// tribometer). Called once from parse_case after [[load]] and [[dirichlet]] are read, so that
// the program's scale lists can be checked against them. Schema: docs/case-format.md.
#pragma once

#include <string_view>

#include "frictopt/io/case_description.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads [[force]] into c.body.forces, [[constraint]] into c.body.constraints, [program] into c.program and [experiment] into
/// c.experiment. `dim` is the body's dimension (geometry.dim). Throws InvalidInput "origin:line:
/// field = value; expected ...".
void read_program_sections(const TableReader& top, std::string_view origin, int dim,
                           CaseDescription& c);

/// The "step" table array of `r` as a loading program, checked against `body`'s [[load]],
/// [[dirichlet]] and [[force]] tables: `where` = "program" for [program] ([[program.step]]),
/// "load_case[k]" for a load case's own program ([[load_case.step]]).
study::LoadingProgramDefinition read_program(const TableReader& r, std::string_view origin,
                                             const study::BodyDefinition& body, std::string_view where);

}  // namespace frictopt::io::detail
