// SPDX-License-Identifier: MIT
// The mesh of a body definition, from whichever producer the definition names.
#pragma once

#include <string>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/mesh.hpp"
#include "frictopt/study/body_definition.hpp"

namespace frictopt::study {

/// The structured grid of definition.shape, height and resolution (mesh::StructuredMesh), or,
/// with definition.imported_mesh, the imported mesh with the design motion of its patch
/// (mesh::with_design_motion: patch nodes along the foundation normal by the Bézier surface, the
/// rest by the once-per-mesh extension, which holds the Dirichlet parts and, with contact, the
/// contact surface off the patch). Throws InvalidInput as those producers do, and for a
/// design patch that is not part of the contact surface, and for an imported body whose
/// Dirichlet parts leave a rigid-body motion free (check_rigid_modes_removed).
mesh::Mesh build_mesh(const BodyDefinition& definition);

/// Throws InvalidInput naming `file` and the Dirichlet groups when the prescribed DOFs of
/// `dirichlet` leave a rigid-body motion of `mesh` free (3D: 3 translations and 3 rotations;
/// 2D: 2 and 1), i.e. the stiffness matrix would be singular (issue 11 item 9).
void check_rigid_modes_removed(const mesh::Mesh& mesh, const std::vector<fem::FaceDirichlet>& dirichlet,
                               const std::string& file);

}  // namespace frictopt::study
