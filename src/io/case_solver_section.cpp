// SPDX-License-Identifier: MIT
#include "case_solver_section.hpp"

#include <fmt/format.h>

#include <cmath>

#include "frictopt/core/error.hpp"

namespace frictopt::io::detail {
namespace {

// Solver limits (docs/case-format.md, "[solver]"): a relative tolerance below the
// double precision floor cannot be met, so with a large iteration cap a solve would run for
// hours before reporting the cap; both are bounded. [solver.coulomb] and [solver.qp] override
// the Coulomb fixed point's and the Tresca QP's own defaults (absent keys keep them).
constexpr double kMinRelativeTolerance = 1e-15;
template <class SolverOptions>
void read_iterative_solver(const TableReader& r, int max_iterations_bound, SolverOptions& options) {
  if (const std::optional<int> n = r.optional_int("max_iterations")) {
    if (*n < 1 || *n > max_iterations_bound)
      r.fail_value("max_iterations", fmt::format("1 <= max_iterations <= {}", max_iterations_bound));
    options.max_iterations = *n;
  }
  if (const std::optional<double> tol = r.optional_number("relative_tolerance")) {
    if (!(*tol >= kMinRelativeTolerance && *tol < 1))
      r.fail_value("relative_tolerance",
                   fmt::format("{:g} <= relative_tolerance < 1 (below it double precision cannot meet it)",
                               kMinRelativeTolerance));
    options.relative_tolerance = *tol;
  }
}

// [solver] into the Coulomb solver's options (read, and validated, with or without [contact]).
contact::CoulombSolver::Options read_solver(const TableReader& r, std::string_view origin) {
  contact::CoulombSolver::Options s;
  const auto sub = [&](std::string_view key, std::initializer_list<std::string_view> keys) {
    const toml::table* t = r.optional_table(key);
    return t ? std::optional<TableReader>(std::in_place, *t, r.field(key), origin, keys)
             : std::nullopt;
  };
  if (auto coulomb = sub("coulomb", {"max_iterations", "relative_tolerance", "method"}))
    read_iterative_solver(*coulomb, 10'000, s);
  if (auto qp = sub("qp", {"max_iterations", "relative_tolerance"})) read_iterative_solver(*qp, 1'000'000, s.tresca);
  // [solver.fem] is reserved: it may appear, but has no keys yet (the direct solver has no
  // options a case should change); the empty key list makes any key an error.
  (void)sub("fem", {});
  return s;
}

}  // namespace

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

contact::CoulombSolver::Options read_solver_section(const TableReader& top, std::string_view origin,
                                                    study::EngineDefinition& engine) {
  const toml::table* table = top.optional_table("solver");
  if (table == nullptr) return {};
  const TableReader solver(*table, "solver", origin, {"coulomb", "qp", "fem", "engine", "petsc_options", "newton"});
  contact::CoulombSolver::Options coulomb = read_solver(solver, origin);
  read_solver_engine(solver, origin, engine);
  read_coulomb_method(solver, origin, engine, coulomb);
  return coulomb;
}

}  // namespace frictopt::io::detail
