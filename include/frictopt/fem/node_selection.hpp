// SPDX-License-Identifier: MIT
// Point and node-set conditions (docs/experiments.md §3): nodal forces on nodes chosen by
// coordinates (the nearest node within a tolerance), by a box, or by a named boundary set; and the
// load vector of one face traction, so that a loading program can scale each [[load]] separately.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {

/// Which nodes a condition acts on. Exactly one of the three selectors is set. Coordinates are
/// those of the reference configuration X_ref (the structured grid's box before the Bézier
/// morph moves nodes vertically; docs/case-format.md).
struct NodeSelector {
  /// The node nearest to this point (size dim); it must lie within `tolerance` of it.
  std::optional<Eigen::VectorXd> point;
  double tolerance = 0.0;  ///< [m], for `point`; >= 0
  /// Every node with box_min <= X_ref <= box_max componentwise (size dim each).
  std::optional<Eigen::VectorXd> box_min, box_max;
  /// Every node of this named boundary set of the mesh.
  std::optional<std::string> boundary;
};

/// The selected node indices, increasing. Throws InvalidInput naming `field` when the selector
/// is malformed (none or several selectors, wrong sizes), no node lies within the tolerance
/// (the message gives the nearest node and its distance), a box holds no node, or the boundary
/// set does not exist.
[[nodiscard]] std::vector<int> select_nodes(const mesh::Mesh& mesh, const NodeSelector& selector,
                                            const std::string& field);

/// A force on selected nodes: `force` (size dim) [N] in total, split equally over the nodes
/// (one node: a point force).
struct NodalForce {
  NodeSelector where;
  Eigen::VectorXd force;
};

/// A prescribed displacement on selected nodes (a point or node-set Dirichlet condition).
struct NodalConstraint {
  NodeSelector where;
  std::vector<int> components;   ///< empty = all
  Eigen::VectorXd displacement;  ///< size dim; empty = zero [m]
};

/// Appends the DOFs of `constraints` to `prescribed` (which holds the face conditions). Throws
/// InvalidInput naming "constraint[i]" for a bad selector, component or size, or a DOF that
/// `prescribed` (a [[dirichlet]] face or an earlier constraint) already fixes.
void add_nodal_constraints(const mesh::Mesh& mesh, const std::vector<NodalConstraint>& constraints,
                           PrescribedDofs& prescribed);

/// The full load vector (num_dofs) of the nodal forces. Throws InvalidInput naming
/// "force[i]" for a bad selector, a force of the wrong size, or a nonzero component on a DOF
/// that `dofs` prescribes (a force on a constrained component does no work and would vanish).
[[nodiscard]] Eigen::VectorXd nodal_force_load(const mesh::Mesh& mesh, const DofMap& dofs,
                                               const std::vector<NodalForce>& forces);

/// The full load vector (num_dofs) ∫_Γ N_a t dS of one face traction at node positions X
/// (the same facet quadrature as LinearElasticity). Throws InvalidInput for an unknown face or a
/// traction of the wrong size.
[[nodiscard]] Eigen::VectorXd face_traction_load(const mesh::Mesh& mesh,
                                                 const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                 const FaceTraction& traction);

}  // namespace frictopt::fem
