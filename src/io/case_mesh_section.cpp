// SPDX-License-Identifier: MIT
#include "case_mesh_section.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/gmsh_mesh.hpp"
#include "frictopt/mesh/graded_coordinates.hpp"
#include "frictopt/study/build_mesh.hpp"

namespace frictopt::io::detail {
namespace {

std::string group_list(const mesh::Mesh& mesh) {
  std::string names;
  for (const std::string& name : mesh.boundary_names()) names += (names.empty() ? "\"" : ", \"") + name + "\"";
  return names.empty() ? "none: the file has no named physical groups of the boundary's dimension" : names;
}

std::string read_group(const TableReader& r, std::string_view key, const mesh::Mesh& mesh, std::string_view meaning,
                       const std::string& file) {
  const std::string group =
      r.required_string(key, fmt::format("the name of a physical group of {} ({})", file, meaning));
  if (!mesh.has_boundary(group))
    r.fail_value(key, fmt::format("the name of a physical group of dimension {} in {} ({}); the file has {}",
                                  mesh.dim() - 1, file, meaning, group_list(mesh)));
  return group;
}

}  // namespace

void read_vertical_grading(const TableReader& r, double height, bool grading_given, mesh::GridResolution& m) {
  const std::string kind = r.optional_string("vertical_grading").value_or("power");
  const bool contact = kind == "contact";
  if (!contact && kind != "power") r.fail_value("vertical_grading", "one of \"power\", \"contact\"");
  if (!contact) {
    for (std::string_view key : {"fine_depth", "vertical_growth"})
      if (r.has(key))
        r.fail(key, fmt::format("{} is only for mesh.vertical_grading = \"contact\"; the grid's vertical grading is "
                                "\"{}\"",
                                r.field(key), kind));
    return;
  }
  if (grading_given)
    r.fail("grading", fmt::format("{} is the power law of mesh.vertical_grading = \"power\"; expected no grading with "
                                  "vertical_grading = \"contact\" (its layers are set by fine_depth and vertical_growth)",
                                  r.field("grading")));
  m.vertical_grading = mesh::VerticalGrading::kContact;
  const double depth = r.required_number(
      "fine_depth", fmt::format("a depth in (0, geometry.height = {}) m below the contact surface that keeps the "
                                "thinnest layers (about the contact radius)",
                                height));
  if (!(depth > 0 && depth < height))
    r.fail_value("fine_depth", fmt::format("a depth in (0, geometry.height = {}) m", height));
  m.fine_depth = depth;
  if (const auto growth = r.optional_number("vertical_growth")) {
    if (!(*growth > 1.0 && *growth <= 2.0))
      r.fail_value("vertical_growth", "1 < vertical_growth <= 2 (ratio of neighbouring layer thicknesses)");
    m.vertical_growth = *growth;
  }
  try {
    (void)mesh::contact_layer_coordinates(height, m.cells[2], m.fine_depth, m.vertical_growth);
  } catch (const InvalidInput& e) {
    r.fail("cells", e.what());
  }
}

mesh::ElementFamily read_element_family(const TableReader& r, int dim) {
  const std::string tensor = dim == 2 ? "quad4" : "hex8", simplex = dim == 2 ? "tri3" : "tet4";
  const std::string name = r.optional_string("element").value_or(tensor);
  if (name == simplex) return mesh::ElementFamily::kSimplex;
  if (name != tensor)
    r.fail_value("element", fmt::format("\"{}\" (Q1 cells, the default) or \"{}\" (P1 simplices) for a {}D body",
                                        tensor, simplex, dim));
  return mesh::ElementFamily::kTensorProduct;
}

bool names_mesh_file(const toml::table& root) {
  const toml::table* mesh = root["mesh"].as_table();
  return mesh != nullptr && mesh->contains("file");
}

ImportedBody read_imported_mesh(const TableReader& r, int dim, std::string_view case_origin,
                                const mesh::PlaneFrame& design_frame) {
  const std::string file_text = r.required_string("file", "a Gmsh .msh or .geo file, relative to the case file");
  // The name Gmsh would open ends at a NUL: "m.msh\0.geo" would pass the extension check as a
  // .geo and open the .msh.
  if (file_text.find('\0') != std::string::npos)
    r.fail("file", fmt::format("{} = \"{}\\u0000…\" has a NUL byte; expected a file name without NUL bytes", r.field("file"),
                               std::string(file_text.c_str())));
  std::filesystem::path file(file_text);
  if (file.is_relative()) file = std::filesystem::path(case_origin).parent_path() / file;
  // One name per file: the run directory's copy of the case names it absolutely
  // (RunDirectory::store_case), and a resume compares the two cases' settings.
  std::error_code ec;
  if (const auto canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(file), ec); !ec)
    file = canonical;
  mesh::GmshMeshOptions options;
  options.budget_unknowns = study::max_unknowns_within_memory();  // --max-memory bounds Gmsh too
  if (const auto size = r.optional_number("size")) {
    if (!(*size > 0 && std::isfinite(*size))) r.fail_value("size", "a mesh size > 0 [m] for the .geo file");
    if (file.extension() != ".geo")
      r.fail("size", fmt::format("{} = {} is only for a .geo file, which frictopt meshes; {} is read as it is",
                                 r.field("size"), *size, file_text));
    options.size = *size;
  }
  options.family = read_element_family(r, dim);
  std::shared_ptr<const mesh::Mesh> reference;
  std::vector<std::filesystem::path> sources;
  try {
    mesh::GmshMesh gmsh(file, options);
    sources = gmsh.source_files();
    reference = std::make_shared<const mesh::Mesh>(std::move(gmsh).take_mesh());
  } catch (const InvalidInput& e) {
    r.fail("file", fmt::format("{}: {}", r.field("file"), e.what()));
  }
  if (reference->dim() != dim)
    r.fail_value("file", fmt::format("a {}D mesh as geometry.dim = {}; {} holds a {}D body", dim, dim, file_text,
                                     reference->dim()));

  ImportedBody body;
  body.contact_surface = read_group(r, "contact", *reference, "the contact surface Γ_c", file_text);
  study::ImportedMeshDefinition& definition = body.definition;
  definition.file = file;
  definition.sources = std::move(sources);
  definition.motion.patch = r.has("patch") ? read_group(r, "patch", *reference, "the design patch", file_text)
                                           : body.contact_surface;
  definition.motion.frame = design_frame;
  if (const auto extension = r.optional_string("extension")) {
    try {
      definition.motion.extension = mesh::parse_extension_kind(*extension);
    } catch (const InvalidInput&) {
      r.fail_value("extension", "one of laplace, sweep");
    }
  }
  mesh::PatchChart chart;
  try {
    chart = mesh::patch_chart(*reference, definition.motion.patch, definition.motion.frame);
  } catch (const InvalidInput& e) {
    r.fail("patch", fmt::format("{}: {}", file_text, e.what()));
  }
  body.a = chart.extents(0);
  body.b = dim == 3 ? chart.extents(1) : 1.0;
  const Eigen::VectorXd t = reference->reference_positions() * definition.motion.frame.normal;
  double t_patch = INFINITY;
  for (int node : reference->boundary(definition.motion.patch).nodes) t_patch = std::min(t_patch, t(node));
  body.height = t.maxCoeff() - t_patch;
  definition.reference = std::move(reference);
  return body;
}

std::string read_boundary_group(const TableReader& r, const mesh::Mesh& mesh) {
  const std::string group = r.required_string("boundary", "the name of a physical group of the mesh file");
  if (!mesh.has_boundary(group))
    r.fail_value("boundary", fmt::format("the name of a physical group of the mesh file; it has {}", group_list(mesh)));
  return group;
}

ImportedBody read_imported_mesh_section(const TableReader& top, std::string_view case_origin, int dim,
                                        const mesh::PlaneFrame& design_frame) {
  const toml::table* table = top.optional_table("mesh");
  if (table == nullptr) top.fail_missing("mesh", "a table [mesh]");
  return read_imported_mesh(TableReader(*table, "mesh", case_origin, {"file", "size", "contact", "patch", "extension", "element"}),
                            dim, case_origin, design_frame);
}

}  // namespace frictopt::io::detail
