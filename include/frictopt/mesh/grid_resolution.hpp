// SPDX-License-Identifier: MIT
// The resolution of a structured grid (what a case's [mesh] table gives).
#pragma once

#include <array>

namespace frictopt::mesh {

/// Grid resolution: cells along x1, (x2 in 3D,) and the vertical direction.
struct GridResolution {
  std::array<int, 3> cells{1, 1, 1};  ///< (n1, n2, n_vertical); n2 is ignored in 2D
  /// Vertical bias toward the contact surface: layer k sits at ŝ_k = (k/n_vertical)^grading,
  /// so grading > 1 refines near the bottom where the contact stresses concentrate. In [1, 10].
  double grading = 1.0;
};

}  // namespace frictopt::mesh
