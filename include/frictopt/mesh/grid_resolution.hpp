// SPDX-License-Identifier: MIT
// The resolution of a structured grid (what a case's [mesh] table gives).
#pragma once

#include <array>
#include <optional>

#include "frictopt/mesh/element_kind.hpp"

namespace frictopt::mesh {

/// How the layers are spaced vertically (docs/case-format.md, "Vertical grading").
enum class VerticalGrading {
  kPower,   ///< ŝ_k = (k/n_vertical)^grading: one power law over the whole height
  kContact  ///< equal layers down to fine_depth, geometric growth above (contact_layer_coordinates)
};

/// Grid resolution: cells along x1, (x2 in 3D,) and the vertical direction.
struct GridResolution {
  std::array<int, 3> cells{1, 1, 1};  ///< (n1, n2, n_vertical); n2 is ignored in 2D
  /// Vertical bias toward the contact surface: layer k sits at ŝ_k = (k/n_vertical)^grading,
  /// so grading > 1 refines near the bottom where the contact stresses concentrate. In [1, 10].
  double grading = 1.0;
  /// kPower (default) uses `grading`; kContact keeps the layers as thin as the layer count
  /// allows down to fine_depth below the contact surface, where the contact stresses are set
  /// (the Hertz pressure is governed by the stress field to a depth of about the contact radius),
  /// and lets them grow by at most vertical_growth per layer to the top.
  VerticalGrading vertical_grading = VerticalGrading::kPower;
  double fine_depth = 0.0;       ///< [m], kContact only: depth of the equal fine layers, in (0, height)
  double vertical_growth = 1.2;  ///< kContact only: largest ratio of neighbouring layer thicknesses, in (1, 2]
  /// In-plane grading (docs/case-format.md): 1 keeps the columns uniform (x_i = L·i/n). growth > 1
  /// puts uniform cells inside refine_box and cells growing geometrically, by a ratio of at most
  /// `growth` between neighbours, from the box to the sides (graded_coordinates.hpp). In [1, 2].
  double growth = 1.0;
  /// [x1min, x1max, x2min, x2max] in metres (the x2 pair is unused in 2D); without it and with
  /// growth > 1, the centred box of a third of each extent (kDefaultRefineFraction).
  std::optional<std::array<double, 4>> refine_box{};
  /// The cells (docs/case-format.md, "[mesh] element"): kTensorProduct, the grid's Q1 cells, or
  /// kSimplex, every grid cell split into P1 simplices sharing the grid's nodes (each hexahedron
  /// into 6 tetrahedra around its diagonal from the lowest to the highest corner, each quadrilateral into 2
  /// triangles), the same nodes, design motion and boundary sets.
  ElementFamily element_family = ElementFamily::kTensorProduct;
};

/// The default refinement box is the central 1/3 of each in-plane extent.
inline constexpr double kDefaultRefineFraction = 1.0 / 3.0;

}  // namespace frictopt::mesh
