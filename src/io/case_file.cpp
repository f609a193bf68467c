// SPDX-License-Identifier: MIT
// The case-file parser: the TOML root's tables, each read by its own section
// (case_<table>_section.cpp) on a strict TableReader that rejects unknown keys before it reads
// anything (so a misspelt key is reported as such, not as the missing key it was meant to be), in
// the order the tables depend on each other. Adding a table = adding its key to the root's list,
// one section file and one call here. Schema: docs/case-format.md.
#include "frictopt/io/case_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <utility>

#include "case_boundary_section.hpp"
#include "case_contact_section.hpp"
#include "case_cost_section.hpp"
#include "case_design_section.hpp"
#include "case_foundation_section.hpp"
#include "case_geometry_section.hpp"
#include "case_identification_section.hpp"
#include "case_load_case_section.hpp"
#include "case_material_section.hpp"
#include "case_mesh_section.hpp"
#include "case_optimization_section.hpp"
#include "case_output_section.hpp"
#include "case_plate_section.hpp"
#include "case_problem_settings.hpp"
#include "case_program_section.hpp"
#include "case_solver_section.hpp"
#include "frictopt/core/error.hpp"
#include "frictopt/study/orientation_design.hpp"
#include "frictopt/study/shape_optimization.hpp"
#include "text_input.hpp"
#include "toml_reader.hpp"

namespace frictopt::io {

using detail::TableReader;

CaseDescription parse_case(std::string_view toml_text, std::string_view origin_name) {
  const std::string origin(origin_name);
  toml::table root;
  try {
    root = toml::parse(detail::without_bom(toml_text), origin_name);
  } catch (const toml::parse_error& e) {
    throw InvalidInput(fmt::format("{}:{}:{}: TOML syntax error: {}", origin, e.source().begin.line,
                                   e.source().begin.column, e.description()));
  }
  const TableReader top(root, "", origin,
                        {"geometry", "mesh", "material", "load", "dirichlet", "design", "contact",
                         "solver", "cost", "optimization", "output", "identification",
                         // friction experiments (case_program_section.hpp)
                         "force", "constraint", "program", "experiment", "foundation",
                         // load cases (case_load_case_section.hpp)
                         "load_case", "study",
                         // loading plates (case_plate_section.hpp)
                         "plate"});

  CaseDescription c;
  c.origin = origin;
  study::BodyDefinition& body = c.body;
  // An imported body ([mesh] file = ..., docs/meshes.md): the geometry's extents come from its
  // mesh.
  const bool imported = detail::names_mesh_file(root);
  detail::Geometry geometry;
  const mesh::Mesh* imported_mesh = nullptr;
  if (imported) {
    geometry.dim = detail::read_imported_geometry_section(top, origin);
    // The design moves the patch along the foundation's normal (docs/meshes.md, "The design on a
    // patch"), so a tilted [foundation] sets the motion's frame and the patch chart's plane too.
    mesh::PlaneFrame design_frame = mesh::PlaneFrame::standard(geometry.dim);
    if (const auto foundation = detail::read_foundation_section(top, origin, geometry.dim))
      design_frame = foundation->frame;
    detail::ImportedBody ib = detail::read_imported_mesh_section(top, origin, geometry.dim, design_frame);
    geometry.a = ib.a;
    geometry.b = ib.b;
    geometry.height = ib.height;
    body.contact_surface = ib.contact_surface;
    body.imported_mesh = std::move(ib.definition);
    imported_mesh = body.imported_mesh->reference.get();
  } else {
    geometry = detail::read_geometry_section(top, origin);
  }
  const int dim = geometry.dim;
  body.height = geometry.height;
  if (!imported) body.resolution = detail::read_grid_section(top, origin, geometry);
  body.material = detail::read_material_section(top, origin, dim);
  const detail::BoundaryFixings fixed_by = detail::read_boundary_sections(top, origin, geometry, imported_mesh, c);
  detail::read_program_sections(top, origin, dim, c);
  detail::read_plate_sections(top, origin, dim, imported_mesh, c);
  detail::read_design_section(top, origin, geometry, body);

  const std::optional<detail::Friction> friction = detail::read_contact_section(top, origin, dim);
  const contact::CoulombSolver::Options coulomb = detail::read_solver_section(top, origin, body.engine);
  const std::optional<contact::Foundation> foundation = detail::read_foundation_section(top, origin, dim);
  if (friction) {
    study::ContactDefinition contact_definition;
    contact_definition.law = friction->law;
    contact_definition.coulomb = coulomb;
    if (foundation) contact_definition.foundation = *foundation;
    body.contact = std::move(contact_definition);
  } else if (foundation) {
    throw InvalidInput(fmt::format("{}: [foundation] needs a [contact] table (a body without contact never meets "
                                   "the foundation); expected [contact] or no [foundation]",
                                   origin));
  }
  if (!imported) detail::check_free_unknowns(c, dim, fixed_by);  // the structured grid's layers
  if (body.friction_orientation) {
    // The law must have an orientation that matters and φ⁰ must lie within the bounds.
    if (!body.contact)
      throw InvalidInput(fmt::format("{}: design.friction_orientation = true needs a [contact] table with an "
                                     "anisotropic 3D friction law",
                                     origin));
    try {
      (void)study::OrientationDesign(*body.friction_orientation, body.contact->law, body.admissible.upper_bound);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: {}", origin, e.what()));
    }
    if (body.engine.kind == study::StateEngine::kPetsc)
      throw InvalidInput(fmt::format("{}: design.friction_orientation = true: the PETSc engine keeps its law fixed; "
                                     "expected solver.engine = \"direct\"",
                                     origin));
  }

  c.cost = detail::read_cost_section(top, origin, dim, body.contact.has_value());
  detail::read_load_case_sections(top, origin, c);
  if (c.cost) detail::read_cost_step(top, origin, c.program, *c.cost);
  c.optimization = study::default_study_options(body);
  detail::read_optimization_section(top, origin, c.optimization);
  detail::read_identification_section(top, origin, c, friction ? detail::kFrictionKindNames.name(friction->kind) : "",
                                      friction ? friction->num_vertices : 0);
  c.output = detail::read_output_section(top, origin);
  body.name = c.output.name;
  c.problem_settings = detail::problem_settings(root);
  // The mesh file by its resolved name, not as written: the same file named relative to the
  // user's case and absolutely in the run directory's copy is the same problem.
  if (c.body.imported_mesh) c.problem_settings["mesh.file"] = "\"" + c.body.imported_mesh->file.string() + "\"";
  return c;
}

const study::CostDefinition& CaseDescription::required_cost() const {
  if (!cost)
    throw InvalidInput(fmt::format("{}: no [cost] table; expected one with kind = one of {}", origin,
                                   cost::kCostKindNames.spellings()));
  return *cost;
}

const IdentificationSetup& CaseDescription::required_identification() const {
  if (!identification) throw InvalidInput(fmt::format("{}: the case has no [identification] table", origin));
  return *identification;
}

CaseDescription load_case(const std::filesystem::path& path) { return load_case(path, path.string()); }

CaseDescription load_case(const std::filesystem::path& path, std::string_view origin_name) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InvalidInput(
        fmt::format("{}: case file not found (or not a regular file)", path.string()));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput(fmt::format("{}: case file could not be opened for reading", path.string()));
  std::ostringstream text;
  // operator<< of an empty stream buffer sets failbit: an empty file is reported as such.
  if (in.peek() == std::ifstream::traits_type::eof()) {
    if (in.bad()) throw InvalidInput(fmt::format("{}: case file could not be read", path.string()));
    throw InvalidInput(fmt::format("{}: the case file is empty; expected a TOML case (docs/case-format.md)",
                                   path.string()));
  }
  text << in.rdbuf();
  if (in.bad() || !text) throw InvalidInput(fmt::format("{}: case file could not be read", path.string()));
  return parse_case(text.str(), origin_name);
}

}  // namespace frictopt::io
