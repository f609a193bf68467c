// SPDX-License-Identifier: MIT
// The case's [contact] table and its [contact.friction] (docs/case-format.md, "[contact]"): the
// friction law — a polygon whose vertices carry their own coefficients, an ellipse, a disc, or
// none — as the case spells it. Private to io; called by case_file.cpp.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "frictopt/contact/friction_law.hpp"
#include "frictopt/core/enum_table.hpp"
#include "toml_reader.hpp"

namespace frictopt::io::detail {

// The shape of the friction set as a case file spells it ([contact.friction].kind). It is the
// syntax of the table, not a second friction-law type: read_friction turns it into a
// contact::FrictionLaw at once, and read_identification_section needs it for the parameter names
// (2D "isotropic" is the interval law, "none" names no coefficient).
enum class FrictionKind { kNone, kIsotropic, kPolygon, kEllipse, kEllipseExact, kDiscExact };
inline constexpr auto kFrictionKindNames = frictopt::detail::make_enum_table<FrictionKind>(
    std::pair{FrictionKind::kNone, "none"}, std::pair{FrictionKind::kIsotropic, "isotropic"},
    std::pair{FrictionKind::kPolygon, "polygon"}, std::pair{FrictionKind::kEllipse, "ellipse"},
    std::pair{FrictionKind::kEllipseExact, "ellipse_exact"}, std::pair{FrictionKind::kDiscExact, "disc_exact"});

// [contact.friction] as the case spells it, and the law it defines.
struct Friction {
  FrictionKind kind = FrictionKind::kNone;
  contact::FrictionLaw law = contact::FrictionLaw::disc(0.0);
  std::size_t num_vertices = 0;  ///< 3D "polygon": the length of mu_vertices
};


/// [contact] (law) and [contact.friction], or nullopt without [contact]. Throws InvalidInput
/// naming the field, its value and the expectation.
std::optional<Friction> read_contact_section(const TableReader& top, std::string_view origin, int dim);

}  // namespace frictopt::io::detail
