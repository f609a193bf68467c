// SPDX-License-Identifier: MIT
// Floating bodies (docs/experiments.md §5): the rigid-body modes
// the Dirichlet conditions leave free, the DOFs that fix them for a generalized inverse A⁺ of
// the stiffness (as in TFETI: a Cholesky factorization of A with r DOFs held, so that the
// remaining block is nonsingular), and the friction-capacity report of a load that friction
// cannot carry.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/contact/friction_law.hpp"

namespace frictopt::study {

/// The rigid-body motions of a body with node positions X (num_nodes × dim) as full DOF
/// vectors (node-major): 2D 3 columns (translations x1, x2; rotation about the centroid),
/// 3D 6 columns (translations; rotations about the axes through the centroid).
[[nodiscard]] Eigen::MatrixXd rigid_body_modes(const Eigen::Ref<const Eigen::MatrixXd>& X);

/// The rigid motions that leave every prescribed DOF at rest and move every tie group (a loading
/// plate's direction, fem::DofMap) as one: an orthonormal basis R (num_dofs × r, r = 0 when the
/// conditions hold the body) of {R₀k : (R₀k)_d = 0 for all prescribed d, (R₀k)_d equal over
/// each group}, R₀ = rigid_body_modes(X). A R = 0 for the stiffness A of the free DOFs.
[[nodiscard]] Eigen::MatrixXd free_rigid_modes(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                               const std::vector<int>& prescribed_dofs,
                                               const std::vector<std::vector<int>>& ties = {});

/// Whether every column of `modes` (full DOF vectors, node-major) is a translation: the same
/// vector at every node, so that it does not depend on the design. A floating body whose free
/// modes include a rotation has no sensitivity here (docs/theory/loading-plate.md §3).
[[nodiscard]] bool modes_are_translations(const Eigen::Ref<const Eigen::MatrixXd>& modes, int dim);

/// r = modes.cols() DOFs, none prescribed and none on `excluded_nodes` (the contact nodes),
/// on which the modes are linearly independent, chosen by a column-pivoted QR of the modes'
/// rows (the best-conditioned choice of the greedy pivoting; far-apart DOFs for rotations).
/// Holding them at 0 removes the kernel: the stiffness of the other DOFs is SPD and its
/// inverse, extended by zero, is a generalized inverse A⁺. Throws InvalidInput when fewer than
/// r independent candidate DOFs exist (a body whose every node is a contact node).
[[nodiscard]] std::vector<int> fixing_dofs(const Eigen::Ref<const Eigen::MatrixXd>& modes,
                                           const std::vector<int>& prescribed_dofs,
                                           const std::vector<int>& excluded_nodes, int dim);

/// "" when the net tangential load F_t (the friction force the contact must supply, Σq) lies
/// in P·W; otherwise "tangential force |F_t| N at θ exceeds the friction capacity μ(θ)·P = … by
/// x %" (μ(θ) the radial function of W in the direction of F_t). P <= 0: the loads do not press
/// the body onto the foundation. 2D: F_t has one component (the second is 0).
[[nodiscard]] std::string friction_capacity_excess(const contact::FrictionLaw& law,
                                                   const Eigen::Vector2d& tangential, double normal,
                                                   int dim);

}  // namespace frictopt::study
