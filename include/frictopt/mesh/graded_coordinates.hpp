// SPDX-License-Identifier: MIT
// Column coordinates along one in-plane direction of the structured grid: uniform, or graded
// geometrically toward a refinement interval (issue 18, item 1).
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

}  // namespace frictopt::mesh
