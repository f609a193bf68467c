// SPDX-License-Identifier: MIT
// Test helper: the nodes on the boundary of a mesh, from its cells alone.
#pragma once

#include <algorithm>
#include <vector>

#include "frictopt/mesh/cad_export.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::mesh::testing {

// The nodes on the boundary of the body, found from the cells (the facets of one cell only,
// mesh::exterior_facets), so that the test does not depend on how the .geo names its boundary parts.
inline std::vector<int> boundary_nodes(const Mesh& mesh) {
  const Connectivity facets = exterior_facets(mesh);
  std::vector<int> nodes(facets.data(), facets.data() + facets.size());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace frictopt::mesh::testing
