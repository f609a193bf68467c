// SPDX-License-Identifier: MIT
// The case-file section of friction identification (docs/identification.md): [identification]
// with its parameters, robust loss and iteration limit, the measurements — a CSV file named by
// `measurements` and/or inline [[identification.measurement]] rows — and optionally several
// [[identification.experiment]] tables, each with its own load scales, specimen orientation and
// measurements. Called once from parse_case after [contact], the loads and the constraints are
// read (the parameter names depend on the friction kind, the scale lists on the load tables).
// Schema: docs/case-format.md.
#pragma once

#include <cstddef>
#include <string_view>

#include "frictopt/io/case_description.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

/// Reads [identification] (if present) into c.identification. `friction_kind` is
/// [contact.friction].kind as spelled in the file (empty: the case has no [contact]);
/// `num_vertices` the length of a 3D polygon's mu_vertices. Throws InvalidInput
/// "origin:line: field = value; expected ..." for bad input: [identification] without [contact],
/// an unknown parameter for the kind, bad bounds, a bad inline measurement (quantity, location,
/// value, sigma), experiments together with top-level measurements, duplicate experiment names,
/// a scale list of the wrong length, an experiment without measurements, a turned 2D law.
void read_identification_section(const TableReader& top, std::string_view origin, CaseDescription& c,
                                 std::string_view friction_kind, std::size_t num_vertices);

}  // namespace frictopt::io::detail
