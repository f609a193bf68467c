// SPDX-License-Identifier: MIT
// The case's [design] table (docs/case-format.md, "[design]"): the Bézier net over the
// geometry's base, the admissible set Υ (bounds, slope, volume), α⁰, and the friction law's
// orientation as a design variable. Private to io; called by case_file.cpp.
#pragma once

#include <string_view>

#include "case_table_common.hpp"
#include "frictopt/study/body_definition.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [design] into `body` (shape, admissible, initial_design, friction_orientation). Throws
/// InvalidInput naming the field, its value and the expectation.
void read_design_section(const TableReader& top, std::string_view origin, const Geometry& geometry,
                         study::BodyDefinition& body);

}  // namespace frictopt::io::detail
