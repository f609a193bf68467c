// SPDX-License-Identifier: MIT
// The case's [optimization] table (docs/case-format.md, "[optimization]"): overrides of the bundle
// trust method's options (the study's defaults otherwise). Private to io; called by case_file.cpp.
#pragma once

#include <string_view>

#include "frictopt/optim/bundle_trust.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// [optimization] into `options` (absent keys keep them). Throws InvalidInput naming the field,
/// its value and the expectation.
void read_optimization_section(const TableReader& top, std::string_view origin, optim::BundleTrust::Options& options);

}  // namespace frictopt::io::detail
