// SPDX-License-Identifier: MIT
// Measurement files of `frictopt identify` (format in docs/identification.md) and the
// mapping of a case's [identification] table onto study::Identification::Options.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
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

/// Sets `m`'s location from its CSV spelling (`12`, `x=0.25;0.5`, empty or `all` for a total),
/// for m.quantity; throws InvalidInput "where: location = ...; expected ..." otherwise. Shared by
/// the CSV reader and the case file's inline [[identification.measurement]] rows.
void parse_location(study::Measurement& m, std::string_view location, const std::string& where);

/// One [[identification.experiment]] table's loads as a study experiment (name, scales,
/// orientation), its measurements left empty for the caller to give.
[[nodiscard]] study::IdentificationExperiment experiment_loads(const IdentificationExperimentSetup& setup);

/// The experiments of a case's [identification] table with their measurements: each experiment's
/// CSV rows (read now) followed by its inline rows; without [[identification.experiment]] tables,
/// one experiment, "case", with the case's own loads and the table's measurements. Throws
/// InvalidInput naming `origin` when the table gives no measurement at all (no file and no inline
/// row), and as read_measurements for a bad file.
[[nodiscard]] std::vector<study::IdentificationExperiment> identification_experiments(const IdentificationSetup& setup,
                                                                                      std::string_view origin);

/// Writes measurements in the format read_measurements reads (shortest round-trip numbers);
/// a header comment line `# <comment>` first when `comment` is not empty. Atomic replace.
void write_measurements(const std::filesystem::path& path, const std::vector<study::Measurement>& measurements,
                        const std::string& comment = "");

}  // namespace frictopt::io
