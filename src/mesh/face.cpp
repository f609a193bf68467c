// SPDX-License-Identifier: MIT
#include "frictopt/mesh/face.hpp"

#include <array>
#include <string>
#include <utility>

#include "frictopt/core/error.hpp"

namespace frictopt::mesh {
namespace {
constexpr std::array<std::pair<Face, std::string_view>, 6> kFaceNames{{
    {Face::kLeft, "left"},
    {Face::kRight, "right"},
    {Face::kFront, "front"},
    {Face::kBack, "back"},
    {Face::kBottom, "bottom"},
    {Face::kTop, "top"},
}};
}  // namespace

std::string_view to_string(Face face) {
  for (const auto& [value, name] : kFaceNames)
    if (value == face) return name;
  return "unknown";
}

Face parse_face(std::string_view name) {
  std::string accepted;
  for (const auto& [value, spelling] : kFaceNames) {
    if (spelling == name) return value;
    accepted += (accepted.empty() ? "" : ", ") + std::string(spelling);
  }
  throw InvalidInput("face '" + std::string(name) + "' is unknown; expected one of " + accepted);
}

}  // namespace frictopt::mesh
