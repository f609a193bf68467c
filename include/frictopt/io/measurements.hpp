// SPDX-License-Identifier: MIT
// Measurement files of `frictopt identify` (format in docs/identification.md) and the
// mapping of a case's [identification] table onto study::Identification::Options.
#pragma once

#include <filesystem>
#include <vector>

#include "frictopt/io/case_description.hpp"
#include "frictopt/study/identification.hpp"

namespace frictopt::io {

/// Reads a measurement CSV: a header `quantity,location,value,sigma`, then one row per measured
/// value; blank lines and lines starting with '#' are skipped. `location` is a contact-node
/// index (`12`), a point on Γ_c (`x=0.25;0.5`, 2D `x=0.25`) or, for totals, empty or `all`.
/// Each Measurement's label is "path:line". Throws InvalidInput for a missing or unreadable
/// file, a wrong header, a row with the wrong number of fields, an unknown quantity, a
/// malformed location or number, or sigma <= 0, naming file, line and field.
[[nodiscard]] std::vector<study::Measurement> read_measurements(const std::filesystem::path& path);

/// Writes measurements in the format read_measurements reads (shortest round-trip numbers);
/// a header comment line `# <comment>` first when `comment` is not empty. Atomic replace.
void write_measurements(const std::filesystem::path& path, const std::vector<study::Measurement>& measurements,
                        const std::string& comment = "");

}  // namespace frictopt::io
