// SPDX-License-Identifier: MIT
// `frictopt solve`: see apps/frictopt/commands.hpp.
#include "commands.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include "frictopt/io/case_file.hpp"
#include "frictopt/io/json.hpp"
#include "frictopt/study/shape_oracle.hpp"
#include "frictopt/io/state_output.hpp"
#include "frictopt/study/elastic_body.hpp"

namespace frictopt::app {

int run_solve(const std::filesystem::path& case_path, const std::filesystem::path& out_dir) {
  using namespace frictopt;
  const io::CaseDescription description = io::load_case(case_path);
  study::ElasticBody body(description.body);
  const auto& mesh = body.mesh();
  fmt::print("{}: {}D body, {} nodes, {} elements, {} unknowns, {} design variables\n", case_path.string(),
             mesh.dim(), mesh.num_nodes(), mesh.num_elements(), body.elasticity().dofs().num_free(),
             body.definition().shape.num_controls());
  const std::string violation = body.admissible_set().describe_violation(body.definition().initial_design, 1e-9);
  if (!violation.empty()) fmt::print("warning: the initial design is outside the admissible set: {}\n", violation);

  study::BodyState state = body.solve(body.definition().initial_design, "initial design");
  if (state.contact) fmt::print("{}\n", state.contact->summary.brief_report());
  fmt::print("{}\n", state.summary.brief_report());
  if (state.summary.status != Status::kConverged) return kExitNumericalFailure;
  fmt::print("strain energy {:.6e} J, work of loads {:.6e} J, volume {:.6e}, max von Mises {:.6e} Pa\n",
             state.strain_energy, state.external_work, state.volume, state.stress.nodal_von_mises.maxCoeff());

  std::filesystem::create_directories(out_dir);
  const std::string name = body.definition().name;
  if (description.output.vtk) {
    const auto vtu = out_dir / (name + ".vtu");
    io::write_state_vtu(vtu, body, state);
    fmt::print("wrote {}\n", vtu.string());
  }
  if (state.contact && mesh.dim() == 2) {
    const auto csv = out_dir / (name + "_contact.csv");
    io::write_contact_csv(csv, body, *state.contact);
    fmt::print("wrote {}\n", csv.string());
  }
  io::JsonValue summary = io::JsonValue::object();
  summary["case"] = case_path.string();
  summary["command"] = "solve";
  summary["status"] = std::string(to_string(state.summary.status));
  summary["message"] = state.summary.message;
  summary["dim"] = mesh.dim();
  summary["num_nodes"] = mesh.num_nodes();
  summary["num_unknowns"] = body.elasticity().dofs().num_free();
  summary["alpha"] = state.alpha;
  summary["relative_residual"] = state.summary.relative_residual;
  summary["strain_energy"] = state.strain_energy;
  summary["external_work"] = state.external_work;
  summary["volume"] = state.volume;
  if (state.contact) {
    const auto& c = *state.contact;
    io::JsonValue contact = io::JsonValue::object();
    contact["status"] = std::string(to_string(c.summary.status));
    contact["message"] = c.summary.message;
    contact["fixed_point_iterations"] = c.summary.iterations;
    contact["qp_iterations"] = c.summary.qp_iterations;
    contact["kkt_residual"] = c.summary.kkt_residual;
    contact["complementarity_gap"] = c.summary.complementarity_gap;
    contact["num_contact_nodes"] = static_cast<int>(c.state.num_nodes());
    contact["dense_delassus"] = c.dense_delassus;
    contact["total_normal_force"] = c.state.normal_forces().sum();
    summary["contact"] = contact;
  }
  summary["max_von_mises"] = state.stress.nodal_von_mises.maxCoeff();
  summary["assembly_seconds"] = state.summary.assembly_seconds;
  summary["factorization_seconds"] = state.summary.factorization_seconds;
  summary["solve_seconds"] = state.summary.solve_seconds;
  io::write_json(out_dir / "summary.json", summary);
  return kExitOk;
}

}  // namespace frictopt::app
