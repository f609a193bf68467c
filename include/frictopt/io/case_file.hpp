// SPDX-License-Identifier: MIT
// Reading a case file (TOML) into a validated CaseDescription. The schema, with a full 2D
// and 3D example, is in docs/case-format.md. The TOML library stays inside src/io.
#pragma once

#include <filesystem>
#include <string_view>

#include "frictopt/io/case_description.hpp"

namespace frictopt::io {

/// Parses and validates the TOML text of a case.
///
/// `origin_name` prefixes every message (usually the file path) and its stem is the default
/// output.name. Throws InvalidInput on a TOML syntax error, an unknown key or table, a
/// missing required field, a value of the wrong type, a value out of range, or a size that
/// does not match geometry.dim; the message names the field, its value and what was
/// expected, with the line where known, e.g.
/// "case.toml:7: material.poisson = 0.6; expected 0 <= poisson < 0.5".
[[nodiscard]] CaseDescription parse_case(std::string_view toml_text, std::string_view origin_name);

/// Reads `path` and calls parse_case with origin_name = path.string().
/// Throws InvalidInput if the file cannot be read, and as parse_case.
[[nodiscard]] CaseDescription load_case(const std::filesystem::path& path);
/// Reads `path` but parses it as `origin_name` (messages, the default output.name and relative
/// paths follow the origin): a run directory's copy of a case is the user's case file.
[[nodiscard]] CaseDescription load_case(const std::filesystem::path& path, std::string_view origin_name);

}  // namespace frictopt::io
