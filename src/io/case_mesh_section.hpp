// SPDX-License-Identifier: MIT
// The [mesh] table of a case that imports its body from a Gmsh file (docs/meshes.md), the vertical
// grading keys of a structured [mesh], and the names of the body's boundary groups
// in [[load]] / [[dirichlet]] tables. Private to io.
#pragma once

#include <string>
#include <string_view>
#include <toml++/toml.h>

#include "frictopt/mesh/grid_resolution.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/study/body_definition.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads [mesh] vertical_grading ("power", the default, or "contact"), fine_depth [m] and
/// vertical_growth of a structured grid into `m` (m.cells and m.grading already read), and
/// checks with the mesh's own construction that the layers can be spaced so; InvalidInput
/// naming the field otherwise (docs/case-format.md, "Vertical grading").
void read_vertical_grading(const TableReader& r, double height, bool grading_given, mesh::GridResolution& m);

/// Reads [mesh] element: "hex8" (the default in 3D) or "tet4", "quad4" (the default in 2D) or
/// "tri3" — the cells of the structured grid or of an imported body (docs/case-format.md,
/// "[mesh] element"); InvalidInput naming the field for another name or one of the other dimension.
mesh::ElementFamily read_element_family(const TableReader& r, int dim);

/// Whether the root's [mesh] table names a file (an imported body) rather than grid cells.
bool names_mesh_file(const toml::table& root);

/// An imported body, read and checked, with the numbers the rest of the case reader needs.
struct ImportedBody {
  study::ImportedMeshDefinition definition;
  std::string contact_surface;  ///< the physical group that is Γ_c
  double a = 0.0, b = 1.0;      ///< the design patch's chart extents [m] (b = 1 in 2D)
  double height = 0.0;          ///< the body's extent above the patch along the normal [m]
};

/// Reads [mesh] file (relative to the case file's directory), size, contact, patch and
/// extension, and reads the mesh (mesh::GmshMesh). Throws InvalidInput naming the field: a
/// missing file, a mesh of another dimension than geometry.dim, an unknown group (the message
/// lists the groups the file has), a patch without extent on the foundation plane.
/// `design_frame` is the foundation's frame ([foundation], standard by default): the patch moves
/// along its normal and the patch chart lies in its plane.
ImportedBody read_imported_mesh(const TableReader& r, int dim, std::string_view case_origin,
                                const mesh::PlaneFrame& design_frame);

/// [mesh] of an imported body (read_imported_mesh on the root's [mesh] table with its keys).
ImportedBody read_imported_mesh_section(const TableReader& top, std::string_view case_origin, int dim,
                                        const mesh::PlaneFrame& design_frame);

/// `boundary = "Group"` of a [[load]] or [[dirichlet]] table on an imported body: the name of
/// one of the mesh's boundary groups (else InvalidInput listing them).
std::string read_boundary_group(const TableReader& r, const mesh::Mesh& mesh);

}  // namespace frictopt::io::detail
