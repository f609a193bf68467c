// SPDX-License-Identifier: MIT
#include "frictopt/mesh/element_kind.hpp"

#include <utility>

#include "frictopt/core/enum_table.hpp"

namespace frictopt::mesh {
namespace {
constexpr auto kElementKindNames = frictopt::detail::make_enum_table<ElementKind>(
    std::pair{ElementKind::kQuad4, "quad4"}, std::pair{ElementKind::kHex8, "hex8"},
    std::pair{ElementKind::kTri3, "tri3"}, std::pair{ElementKind::kTet4, "tet4"});
}  // namespace

std::string_view to_string(ElementKind kind) { return kElementKindNames.name(kind); }

ElementKind parse_element_kind(std::string_view name) { return kElementKindNames.parse(name, "element kind"); }

}  // namespace frictopt::mesh
