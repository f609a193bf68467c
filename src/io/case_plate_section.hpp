// SPDX-License-Identifier: MIT
// The case's [[plate]] tables (docs/case-format.md, "[[plate]]"): rigid loading plates, a face of
// the box or a physical group of an imported mesh moved rigidly by a prescribed total force
// (docs/theory/loading-plate.md). Private to io; called once by case_file.cpp after
// [[dirichlet]] is read.
#pragma once

#include <string_view>

#include "frictopt/io/case_description.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads [[plate]] into c.body.plates: `face` (the box) or `boundary` (an imported body,
/// `imported` non-null), `force` (dim numbers, N), and the directions `tied` (force-driven; default
/// every direction not held) and `held` (zero displacement; default none) as "x", "y", "z".
/// Throws InvalidInput "origin:line: field = value; expected ..." for a wrong part, a direction
/// named twice, held and tied at once, a force in a direction that is not tied, a face that a
/// [[dirichlet]] table fixes in a direction the plate acts in, or two plates on one part.
void read_plate_sections(const TableReader& top, std::string_view origin, int dim, const mesh::Mesh* imported,
                         CaseDescription& c);

}  // namespace frictopt::io::detail
