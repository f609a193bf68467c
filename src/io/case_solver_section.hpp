// SPDX-License-Identifier: MIT
// The engine keys of a case's [solver] table (docs/case-format.md, "[solver]"):
// engine = "direct" | "petsc", petsc_options, and [solver.newton] for the PETSc engine's
// Newton method. Private to io; called by case_file.cpp.
#pragma once

#include "frictopt/study/body_definition.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads engine, petsc_options and [solver.newton] {max_iterations, relative_tolerance} from
/// `solver` into `out`. Throws InvalidInput naming the field, its value and the expectation
/// (petsc_options or [solver.newton] with engine = "direct" are errors: they would be ignored).
void read_solver_engine(const TableReader& solver, std::string_view origin, study::EngineDefinition& out);

}  // namespace frictopt::io::detail
