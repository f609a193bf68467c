// SPDX-License-Identifier: MIT
// The case's [foundation] table (docs/case-format.md, "[foundation]"): the
// rigid plane n·x = d the body rests on (normal, offset) and the first in-plane axis of the
// friction law's frame (axis1). Private to io; called by case_file.cpp.
#pragma once

#include <optional>
#include <string_view>

#include "frictopt/contact/contact_boundary.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads normal (dim numbers, nonzero, normalized), offset (a finite number, default 0) and, in
/// 3D, axis1 (3 numbers not parallel to the normal; default the projection of e1 onto the plane,
/// or of e2 when e1 is parallel to n). Throws InvalidInput naming "foundation.<key>", its value
/// and the expectation.
contact::Foundation read_foundation(const TableReader& foundation, int dim);
/// The root's [foundation] table (read_foundation with its keys), or nullopt when absent.
std::optional<contact::Foundation> read_foundation_section(const TableReader& top, std::string_view origin, int dim);

}  // namespace frictopt::io::detail
