// SPDX-License-Identifier: MIT
// The case's [material] table (docs/case-format.md, "[material]"): Young's modulus, Poisson's
// ratio within the physical bounds, the 2D plane model. Private to io; called by case_file.cpp.
#pragma once

#include <string_view>

#include "frictopt/fem/material.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [material]: young, poisson, model (2D only). Throws InvalidInput naming the field, its value
/// and the expectation.
fem::IsotropicMaterial read_material_section(const TableReader& top, std::string_view origin, int dim);

}  // namespace frictopt::io::detail
