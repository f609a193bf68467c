// SPDX-License-Identifier: MIT
// A rigid loading plate (docs/theory/loading-plate.md): a boundary set moved rigidly by a
// prescribed total force. In each force-driven direction every node of the set shares one
// unknown (the plate's translation, a DofMap tie); the force enters as the load of that
// unknown, so the body carries exactly the prescribed force whatever the design.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/fem/node_selection.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {

struct LoadingPlate {
  std::string boundary = "top";  ///< name of a mesh::BoundarySet (a box face or a Gmsh group)
  Eigen::VectorXd force;         ///< size dim: the total force [N] in the tied directions (0 elsewhere)
  std::vector<int> tied;         ///< force-driven directions (one unknown each), sorted
  std::vector<int> held;         ///< directions held at zero displacement, sorted
  std::string field = "plate[0]";  ///< how messages name it (the case's table)
};

/// The tie groups of the plates (DofMap): one per plate and tied direction, the DOFs
/// node·dim + c of the plate's nodes.
[[nodiscard]] std::vector<std::vector<int>> plate_ties(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates);

/// Appends the held directions of the plates (zero displacement) to `prescribed`.
void add_plate_held_dofs(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates, PrescribedDofs& prescribed);

/// The plates' forces as nodal forces (each total force split equally over the plate's nodes):
/// through Pᵀ the tied unknown receives exactly the total.
[[nodiscard]] std::vector<NodalForce> plate_nodal_forces(const std::vector<LoadingPlate>& plates);

/// Throws InvalidInput naming the plate's field for: an unknown boundary set (the message lists
/// the mesh's), a force of the wrong size or not finite, a direction out of range, held and
/// tied at once, a nonzero force in a direction that is not tied, a plate without any tied or
/// held direction, a plate DOF that `prescribed` (the [[dirichlet]] tables and constraints)
/// fixes, a node on `contact_surface` (empty: none), or a node shared by two plates in one
/// direction.
void validate_plates(const mesh::Mesh& mesh, const std::vector<LoadingPlate>& plates, const PrescribedDofs& prescribed,
                     const std::string& contact_surface);

/// What a plate does at a state: its translation (the tied unknowns; 0 in held directions; the
/// mean of the nodes' displacements in the other directions) and the total force it applies to
/// the body, Σ over its nodes of the residual A_full u − l_traction (= the prescribed force in a
/// tied direction at equilibrium; the reaction in a held one).
struct PlateReading {
  std::string boundary;
  Eigen::VectorXd displacement;  ///< [m], size dim
  Eigen::VectorXd force;         ///< [N], size dim
  Eigen::VectorXd prescribed;    ///< the prescribed force [N] (tied directions; 0 elsewhere)
  std::vector<int> tied, held;
};

[[nodiscard]] PlateReading read_plate(const mesh::Mesh& mesh, const LoadingPlate& plate,
                                      const Eigen::Ref<const Eigen::VectorXd>& displacement,
                                      const Eigen::Ref<const Eigen::VectorXd>& residual);

/// "x", "y", "z" for 0, 1, 2.
[[nodiscard]] std::string direction_name(int c);

}  // namespace frictopt::fem
