// SPDX-License-Identifier: MIT
// The mesh of a body definition, from whichever producer the definition names.
#pragma once

#include "frictopt/mesh/mesh.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// The structured grid of definition.shape, height and resolution (mesh::StructuredMesh), or,
/// with definition.imported_mesh, the imported mesh with the design motion of its patch
/// (mesh::with_design_motion: patch nodes along the foundation normal by the Bézier surface, the
/// rest by the once-per-mesh extension, which holds the Dirichlet parts and, with contact, the
/// contact surface off the patch). Throws InvalidInput as those producers do, and for a
/// design patch that is not part of the contact surface.
mesh::Mesh build_mesh(const BodyDefinition& definition);

}  // namespace frictopt::study
