// SPDX-License-Identifier: MIT
// Test helper: the nodes on the boundary of a Q1 mesh, from its cells alone.
#pragma once

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "frictopt/mesh/mesh.hpp"

namespace frictopt::mesh::testing {

// The nodes on the boundary of the body, found from the cells (a facet of one cell only), so
// that the test does not depend on how the .geo names its boundary parts.
inline std::vector<int> boundary_nodes(const Mesh& mesh) {
  const int dim = mesh.dim();
  const Connectivity& cells = mesh.elements();
  // Local facets of the VTK quad (edges) and hexahedron (faces).
  const std::vector<std::vector<int>> facets =
      dim == 2 ? std::vector<std::vector<int>>{{0, 1}, {1, 2}, {2, 3}, {3, 0}}
               : std::vector<std::vector<int>>{{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                               {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::map<std::vector<int>, int> count;
  for (Eigen::Index e = 0; e < cells.rows(); ++e)
    for (const auto& f : facets) {
      std::vector<int> key;
      for (int a : f) key.push_back(cells(e, a));
      std::sort(key.begin(), key.end());
      ++count[key];
    }
  std::set<int> nodes;
  for (const auto& [key, n] : count)
    if (n == 1) nodes.insert(key.begin(), key.end());
  return {nodes.begin(), nodes.end()};
}

}  // namespace frictopt::mesh::testing
