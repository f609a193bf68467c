// SPDX-License-Identifier: MIT
// `frictopt export-fclib`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/core/error.hpp"
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/fclib_export.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

// `frictopt export-fclib CASE OUT.hdf5`: the contact problem at the initial design in FCLIB's
// local format, with our solution (docs/contact.md, "FCLIB export").
int run_export_fclib(const std::filesystem::path& case_path, const std::filesystem::path& out_path,
                     const std::string& units, bool include_solution) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  const study::BodyDefinition& definition = description.body;
  if (!definition.contact)
    throw InvalidInput(fmt::format("{}: the case has no [contact]; there is no contact problem to export",
                                   case_path.string()));
  // Refusals first: nothing is solved for a law or a target FCLIB cannot take.
  io::require_fclib_exportable(definition.contact->law, case_path.string());
  study::ElasticBody body(definition);
  study::BodyState state = body.solve(body.definition().initial_design, "initial design");
  if (!state.contact) {  // the elasticity factorization failed before the contact solve
    fmt::print("{}\n", state.summary.brief_report());
    return kExitNumericalFailure;
  }
  fmt::print("{}\n", state.contact->summary.brief_report());
  io::FclibExportOptions options;
  options.case_name = case_path.string();
  options.normalize_units = units != "si";
  options.include_solution = include_solution;
  const io::FclibLocalProblem problem = io::export_fclib_local(out_path, body, state, options);
  fmt::print("wrote {}: FCLIB local problem, spacedim {}, {} contacts, mu = {:.6g}, {} units {:.6g} N / {:.6g} m; {}\n",
             out_path.string(), problem.spacedim, problem.num_contacts(),
             problem.mu.size() > 0 ? problem.mu(0) : 0.0, options.normalize_units ? "normalized" : "SI",
             problem.force_unit, problem.length_unit,
             !include_solution ? "no solution stored"
             : problem.solution_is_exact
                 ? fmt::format("solution stored (natural-map residual {:.2e})",
                               io::fclib_natural_map_residual(problem, problem.r))
                 : "our solution stored as initial guess only (not exact for this problem)");
  if (!state.contact->summary.converged())
    fmt::print("warning: the contact solve did not converge; the problem is exported, our solution only as a guess\n");
  return kExitOk;
}

}  // namespace frictopt::app
