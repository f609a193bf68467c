// SPDX-License-Identifier: MIT
// `frictopt solve`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/io/run_directory.hpp"
#include "frictopt/io/summary_json.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/study/build_mesh.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

int run_solve(const std::filesystem::path& case_path, const std::filesystem::path& out_dir) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  if (description.program) return run_program(case_path, out_dir, description);
  study::ElasticBody body(description.body);
  const auto& mesh = body.mesh();
  fmt::print("{}: {}D body, {} nodes, {} elements ({}, smallest scaled Jacobian {:.3g} at α⁰), {} unknowns, {} design "
             "variables\n",
             case_path.string(), mesh.dim(), mesh.num_nodes(), mesh.num_elements(), mesh::to_string(mesh.element_kind()),
             mesh.min_scaled_jacobian(mesh.positions(body.definition().initial_design)), body.elasticity().dofs().num_free(),
             body.definition().shape.num_controls());
  // The dense contact algebra grows like m² in memory and m³ in time (m contact unknowns): said
  // before the solve starts (docs/scaling.md, "Contact nodes").
  if (const contact::ContactBoundary* boundary = body.contact_boundary())
    if (const std::string note = study::contact_cost_note(mesh.dim(), boundary->num_nodes()); !note.empty())
      fmt::print("warning: {}\n", note);
  // x⁰: α⁰, with friction_orientation (α⁰, k φ⁰) — Υ is over x.
  const std::string violation = body.admissible_set().describe_violation(body.initial_design(), 1e-9);
  if (!violation.empty()) fmt::print("warning: the initial design is outside the admissible set: {}\n", violation);
  io::RunDirectory run(out_dir, io::RunOpening::kOutput, case_path);

  study::BodyState state = body.solve(body.definition().initial_design, "initial design");
  if (state.contact) {
    fmt::print("{}\n", state.contact->summary.brief_report());
    if (state.contact->floating) fmt::print("{}\n", state.contact->floating->brief_report());
    fmt::print("{}\n", state.contact->resultants.brief_report());
  }
  if (!state.plates.empty()) fmt::print("{}\n", io::plates_report(state.plates));
  fmt::print("{}\n", state.summary.brief_report());
  const io::JsonValue summary = io::solve_summary(case_path.string(), body, state);
  if (state.summary.status != Status::kConverged) {
    // The failure is reported in summary.json too, so a script sees why.
    run.write_json_file(io::RunDirectory::kSummary, summary);
    return kExitNumericalFailure;
  }
  fmt::print("strain energy {:.6e} J, work of loads {:.6e} J, volume {:.6e}, max von Mises {:.6e} Pa\n",
             state.strain_energy, state.external_work, state.volume, state.stress.nodal_von_mises.maxCoeff());
  const std::string name = body.definition().name;
  if (description.output.vtk) {
    const auto vtu = run.file(name + ".vtu");
    io::write_state_vtu(vtu, body, state);
    fmt::print("wrote {}\n", vtu.string());
  }
  if (state.contact && mesh.dim() == 2) {
    const auto csv = run.file(name + "_contact.csv");
    io::write_contact_csv(csv, body, *state.contact);
    fmt::print("wrote {}\n", csv.string());
  }
  run.write_json_file(io::RunDirectory::kSummary, summary);
  return kExitOk;
}

}  // namespace frictopt::app
