// SPDX-License-Identifier: MIT
// The engine keys of a case's [solver] table (docs/case-format.md, "[solver]"):
// engine = "direct" | "petsc", petsc_options, [solver.newton] for the PETSc engine's
// Newton method, [solver.coulomb] method, and the iterative solvers' options ([solver.coulomb],
// [solver.qp], [solver.fem]). Private to io; called by case_file.cpp.
#pragma once

#include "frictopt/contact/coulomb_solver.hpp"
#include "frictopt/study/body_definition.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [solver] (absent: the defaults): the Coulomb solver's options ([solver.coulomb], [solver.qp],
/// [solver.fem] and the method), and the engine into `engine`. Throws InvalidInput naming the
/// field, its value and the expectation.
contact::CoulombSolver::Options read_solver_section(const TableReader& top, std::string_view origin,
                                                    study::EngineDefinition& engine);

/// Reads engine, petsc_options and [solver.newton] {max_iterations, relative_tolerance} from
/// `solver` into `out`. Throws InvalidInput naming the field, its value and the expectation
/// (petsc_options or [solver.newton] with engine = "direct" are errors: they would be ignored).
void read_solver_engine(const TableReader& solver, std::string_view origin, study::EngineDefinition& out);

/// Reads [solver.coulomb] method = "automatic" | "fixed_point" | "split" | "semismooth_newton"
/// (docs/case-format.md, "[solver]"; docs/contact.md, "Semismooth Newton") into `coulomb.method`;
/// absent: "automatic". With engine = "petsc" only "automatic" and "semismooth_newton" (the
/// PETSc engine's Newton on the displacements) are accepted. Throws InvalidInput naming the
/// field, its value and the expectation.
void read_coulomb_method(const TableReader& solver, std::string_view origin, const study::EngineDefinition& engine,
                         contact::CoulombSolver::Options& coulomb);

}  // namespace frictopt::io::detail
