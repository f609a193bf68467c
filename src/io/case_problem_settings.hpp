// SPDX-License-Identifier: MIT
// A case's problem settings: every value of the TOML file flattened to "table.key" -> canonical
// text (CaseDescription::problem_settings), the fingerprint a resumed or certified run compares.
// Private to io; called by case_file.cpp.
#pragma once

#include <map>
#include <string>

#include <toml++/toml.h>

namespace frictopt::io::detail {

std::map<std::string, std::string> problem_settings(const toml::table& root);

}  // namespace frictopt::io::detail
