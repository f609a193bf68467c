// SPDX-License-Identifier: MIT
#include "frictopt/study/build_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "frictopt/core/error.hpp"
#include "frictopt/mesh/design_extension.hpp"
#include "frictopt/mesh/structured_mesh.hpp"

namespace frictopt::study {

mesh::Mesh build_mesh(const BodyDefinition& definition) {
  if (!definition.imported_mesh)
    return mesh::StructuredMesh(definition.shape, definition.height, definition.resolution).take_mesh();
  const ImportedMeshDefinition& imported = *definition.imported_mesh;
  if (!imported.reference) throw InvalidInput("imported mesh: no mesh was read");
  const mesh::Mesh& reference = *imported.reference;
  const std::string& patch = imported.motion.patch;
  // Γ_d ⊂ Γ_c (spec 07 §5): the gap of a contact node moves with the patch only.
  if (definition.contact) {
    const std::vector<int>& surface = reference.boundary(definition.contact_surface).nodes;
    const std::vector<int>& patch_nodes = reference.boundary(patch).nodes;
    if (!std::includes(surface.begin(), surface.end(), patch_nodes.begin(), patch_nodes.end()))
      throw InvalidInput(fmt::format("{}: the design patch '{}' is not part of the contact surface '{}'; expected a "
                                     "patch whose nodes all lie on the contact surface",
                                     imported.file.string(), patch, definition.contact_surface));
  }
  // The extension holds the Dirichlet parts and the contact surface off the patch (their nodes
  // do not move; patch nodes on them move with the patch): the body's clamps stay where the
  // case puts them, and a contact node off the patch keeps its gap.
  mesh::DesignMotion motion = imported.motion;
  for (const fem::FaceDirichlet& d : definition.dirichlet) motion.fixed.push_back(d.boundary);
  if (definition.contact && definition.contact_surface != patch) motion.fixed.push_back(definition.contact_surface);
  return mesh::with_design_motion(reference, definition.shape, motion);
}

}  // namespace frictopt::study
