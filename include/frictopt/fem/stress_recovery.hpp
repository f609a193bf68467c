// SPDX-License-Identifier: MIT
// Cauchy stress and von Mises stress from a displacement field, per element and per node.
#pragma once

#include <Eigen/Core>

#include "frictopt/fem/material.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {

/// Stresses as 6-component symmetric tensors (xx, yy, zz, xy, yz, xz) — the order ParaView
/// expects — in Pa. In 2D plane strain σ_zz = λ(ε_xx + ε_yy); plane stress σ_zz = 0.
struct StressField {
  Eigen::MatrixXd element;             ///< num_elements × 6, at the element centre
  Eigen::MatrixXd nodal;               ///< num_nodes × 6, corner values averaged over the elements at a node
  Eigen::VectorXd element_von_mises;   ///< num_elements
  Eigen::VectorXd nodal_von_mises;     ///< num_nodes
};

/// Recovers stresses for positions X (num_nodes × dim) and full displacement u (num_dofs).
StressField recover_stresses(const mesh::Mesh& mesh, const IsotropicMaterial& material,
                             const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u);

/// von Mises stress of a 6-component tensor (xx, yy, zz, xy, yz, xz).
double von_mises(const Eigen::Ref<const Eigen::Matrix<double, 6, 1>>& s);

}  // namespace frictopt::fem
