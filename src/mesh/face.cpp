// SPDX-License-Identifier: MIT
#include "frictopt/mesh/face.hpp"

#include <array>
#include <string>
#include <utility>

#include "frictopt/core/enum_table.hpp"
#include "frictopt/core/error.hpp"

namespace frictopt::mesh {
namespace {
constexpr frictopt::detail::EnumTable<Face, 6> kFaceNames{{{
    {Face::kLeft, "left"},
    {Face::kRight, "right"},
    {Face::kFront, "front"},
    {Face::kBack, "back"},
    {Face::kBottom, "bottom"},
    {Face::kTop, "top"},
}}};
}  // namespace

std::string_view to_string(Face face) { return kFaceNames.name(face); }

Face parse_face(std::string_view name) { return kFaceNames.parse(name, "face"); }

}  // namespace frictopt::mesh
