// SPDX-License-Identifier: MIT
// Column coordinates along one in-plane direction of the structured grid: uniform, or graded
// geometrically toward a refinement interval (docs/case-format.md, "In-plane grading"), and the
// layer heights of the vertical grading "contact".
#pragma once

#include <string>
#include <vector>

namespace frictopt::mesh {

/// x_i = length·i/cells, i = 0..cells (the formula of the uniform grid, bit for bit).
std::vector<double> uniform_coordinates(double length, int cells);

/// Graded coordinates 0 = x_0 < … < x_cells = length along one direction:
///  - [lo, hi] holds m uniform cells of size h = (hi − lo)/m, so lo and hi are grid lines exactly;
///  - each side [0, lo] and [hi, length] holds k cells of sizes h·r, h·r², …, h·r^k with
///    1 <= r <= growth solved so that they fill the side exactly (no cell smaller than h).
/// m is the largest count for which both sides can be filled so (the finest box cells the total
/// allows); the remaining cells go to the side whose ratio is larger. Adjacent cells thus differ
/// by a ratio in [1, growth]. `field` names the direction in messages, e.g. "mesh.cells[0]".
/// Throws InvalidInput when lo/hi are outside [0, length] or lo >= hi, when growth is not in
/// (1, 2], or when `cells` are too few (or a box edge is closer to a side than one box cell).
std::vector<double> graded_coordinates(double length, int cells, double lo, double hi, double growth,
                                       const std::string& field);

/// Layer heights 0 = z_0 < … < z_layers = height of the vertical grading "contact"
/// (docs/case-format.md, "Vertical grading"): equal layers of thickness t = fine_depth/m from the
/// contact surface down to the depth fine_depth, then layers growing by a ratio r in [1, growth]
/// per layer up to the top, filling it exactly. m is the largest count the layers allow (the
/// thinnest fine layers), as in graded_coordinates with the refinement interval [0, fine_depth].
/// Throws InvalidInput naming mesh.fine_depth (not in (0, height)), mesh.vertical_growth (not in
/// (1, 2]) or mesh.cells[vertical] (too few layers to reach the top).
std::vector<double> contact_layer_coordinates(double height, int layers, double fine_depth, double growth);

}  // namespace frictopt::mesh
