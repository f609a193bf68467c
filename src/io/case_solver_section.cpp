// SPDX-License-Identifier: MIT
#include "case_solver_section.hpp"

#include <fmt/format.h>

#include <cmath>

namespace frictopt::io::detail {

void read_solver_engine(const TableReader& solver, std::string_view origin, study::EngineDefinition& out) {
  if (const std::optional<std::string> engine = solver.optional_string("engine")) {
    if (*engine == "direct")
      out.kind = study::StateEngine::kDirect;
    else if (*engine == "petsc")
      out.kind = study::StateEngine::kPetsc;
    else
      solver.fail_value("engine", "one of direct, petsc");
  }
  const bool petsc = out.kind == study::StateEngine::kPetsc;
  if (const std::optional<std::string> options = solver.optional_string("petsc_options")) {
    if (!petsc) solver.fail("petsc_options", "solver.petsc_options needs engine = \"petsc\" (the direct engine has no PETSc)");
    out.petsc_options = *options;
  }
  if (const toml::table* newton = solver.optional_table("newton")) {
    if (!petsc) solver.fail("newton", "[solver.newton] needs engine = \"petsc\" (the direct engine's iterations are [solver.coulomb])");
    const TableReader r(*newton, solver.field("newton"), origin, {"max_iterations", "relative_tolerance"});
    if (const std::optional<int> n = r.optional_int("max_iterations")) {
      if (*n < 1 || *n > 10'000) r.fail_value("max_iterations", "1 <= max_iterations <= 10000");
      out.max_iterations = *n;
    }
    if (const std::optional<double> tol = r.optional_number("relative_tolerance")) {
      // Below 1e-15 double precision cannot meet it (the Newton residual stagnates at rounding).
      if (!(*tol >= 1e-15 && *tol < 1)) r.fail_value("relative_tolerance", "1e-15 <= relative_tolerance < 1");
      out.relative_tolerance = *tol;
    }
  }
}

void read_coulomb_method(const TableReader& solver, std::string_view origin, const study::EngineDefinition& engine,
                         contact::CoulombSolver::Options& coulomb) {
  const toml::table* table = solver.optional_table("coulomb");
  if (!table) return;
  const TableReader r(*table, solver.field("coulomb"), origin, {"max_iterations", "relative_tolerance", "method"});
  const std::optional<std::string> method = r.optional_string("method");
  if (!method) return;
  if (*method == "automatic")
    coulomb.method = contact::CoulombMethod::kAutomatic;
  else if (*method == "fixed_point")
    coulomb.method = contact::CoulombMethod::kFixedPoint;
  else if (*method == "split")
    coulomb.method = contact::CoulombMethod::kSplit;
  else if (*method == "semismooth_newton")
    coulomb.method = contact::CoulombMethod::kSemismoothNewton;
  else
    r.fail_value("method", "one of automatic, fixed_point, split, semismooth_newton");
  const bool newton = coulomb.method == contact::CoulombMethod::kAutomatic ||
                      coulomb.method == contact::CoulombMethod::kSemismoothNewton;
  if (engine.kind == study::StateEngine::kPetsc && !newton)
    r.fail_value("method", "automatic or semismooth_newton with engine = \"petsc\" (the PETSc engine solves by "
                           "semismooth Newton on the displacements; the fixed point is the direct engine's)");
}

}  // namespace frictopt::io::detail
