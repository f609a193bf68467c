// SPDX-License-Identifier: MIT
// Names of the six faces of the box-like body; one table gives their spellings.
#pragma once

#include <string_view>

namespace frictopt::mesh {

/// Faces of the body: left/right are x1 = 0 / x1 = a, front/back are x2 = 0 / x2 = b (3D only),
/// bottom is the Bézier contact surface Γ_c, top is the flat face x_dim = C4.
enum class Face { kLeft, kRight, kFront, kBack, kBottom, kTop };

std::string_view to_string(Face face);
/// Inverse of to_string; throws InvalidInput listing the accepted names.
Face parse_face(std::string_view name);

}  // namespace frictopt::mesh
