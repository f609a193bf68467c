// SPDX-License-Identifier: MIT
// The case's [geometry] table and, for the structured box, its [mesh] table (docs/case-format.md,
// "[geometry]", "[mesh]"): the box (0,a)×(0,b)×(G_α, height), the grid's cells and gradings.
// An imported body's [mesh] table is case_mesh_section's. Private to io; called by case_file.cpp.
#pragma once

#include <string_view>

#include "case_table_common.hpp"
#include "frictopt/mesh/grid_resolution.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [geometry] of the structured box: dim, a, b (3D only), height. Throws InvalidInput naming the
/// field, its value and the expectation (lengths within the physical bounds).
Geometry read_geometry_section(const TableReader& top, std::string_view origin);
/// [geometry] of a body imported from a mesh file: dim only (the extents come from the mesh).
int read_imported_geometry_section(const TableReader& top, std::string_view origin);
/// [mesh] of the structured box: cells (within the size limits), grading, in-plane growth and
/// refine_box, the vertical grading.
mesh::GridResolution read_grid_section(const TableReader& top, std::string_view origin, const Geometry& geometry);

}  // namespace frictopt::io::detail
