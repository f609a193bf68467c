// SPDX-License-Identifier: MIT
// The case's [output] table (docs/case-format.md, "[output]"): VTK output, its frequency and the
// run's name (default: the case file's stem, or its directory's name for cases*/NAME/case.toml).
// Private to io; called by case_file.cpp.
#pragma once

#include <string_view>

#include "frictopt/io/case_description.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [output], or its defaults with the name from `origin`. Throws InvalidInput naming the field,
/// its value and the expectation (a name too long for the files the run writes).
OutputSpec read_output_section(const TableReader& top, std::string_view origin);

}  // namespace frictopt::io::detail
