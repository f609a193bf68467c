// SPDX-License-Identifier: MIT
// The case's [[load]] and [[dirichlet]] tables (docs/case-format.md): tractions and prescribed
// displacements on a face of the structured box or a physical group of an imported body, and the
// checks that need them all (a load on a fixed component, no free unknown left). Private to io;
// called by case_file.cpp.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "case_table_common.hpp"
#include "frictopt/io/case_description.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// (boundary, component) -> the index of the [[dirichlet]] table that fixes it (first).
using BoundaryFixings = std::map<std::pair<std::string, int>, std::size_t>;

/// [[load]] and [[dirichlet]] into c.body (tractions, dirichlet); `imported` is the imported body's
/// mesh (null: the structured box). Refuses a component fixed twice, a load on a fixed component,
/// and no [[dirichlet]] without [contact] or [[constraint]] (rigid-body modes). Returns the fixings.
BoundaryFixings read_boundary_sections(const TableReader& top, std::string_view origin, const Geometry& geometry,
                                       const mesh::Mesh* imported, CaseDescription& c);

/// The structured box with contact: at least one unknown above the contact surface is free.
void check_free_unknowns(const CaseDescription& c, int dim, const BoundaryFixings& fixed_by);

}  // namespace frictopt::io::detail
