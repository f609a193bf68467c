// SPDX-License-Identifier: MIT
// Dirichlet conditions (Γ_u) and surface tractions (Γ_p), and the numbering of free DOFs.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {

/// u_c = value_c on every node of the boundary set `boundary` for each listed component c
/// (docs/theory/problem.md §4).
struct FaceDirichlet {
  std::string boundary = "left";  ///< name of a mesh::BoundarySet
  std::vector<int> components;   ///< empty = all components
  Eigen::VectorXd displacement;  ///< size dim; empty = zero [m]
};

/// A dead surface traction (force per current area, [Pa]) on a boundary set (Γ_p).
struct FaceTraction {
  std::string boundary = "top";  ///< name of a mesh::BoundarySet
  Eigen::VectorXd traction;  ///< size dim
};

/// Prescribed degrees of freedom as (dof, value) pairs; dof = node·dim + component.
struct PrescribedDofs {
  std::vector<int> dofs;
  std::vector<double> values;
};

/// Expands boundary conditions into prescribed DOFs (later conditions overwrite earlier ones at
/// shared nodes). Throws InvalidInput for a component outside [0, dim), a displacement of the
/// wrong size or a boundary name the mesh does not have.
PrescribedDofs expand_dirichlet(const mesh::Mesh& mesh, const std::vector<FaceDirichlet>& conditions);

/// Numbering of the free DOFs: free(dof) is the row in the reduced system or −1.
class DofMap {
 public:
  DofMap(int num_dofs, const PrescribedDofs& prescribed);
  int num_dofs() const { return static_cast<int>(free_index_.size()); }
  int num_free() const { return static_cast<int>(free_dofs_.size()); }
  int free_index(int dof) const { return free_index_[dof]; }
  bool is_free(int dof) const { return free_index_[dof] >= 0; }
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  /// Values of all DOFs with the prescribed ones set and the free ones zero.
  const Eigen::VectorXd& prescribed_values() const { return prescribed_values_; }
  /// Full vector from free values (prescribed values inserted).
  Eigen::VectorXd expand(const Eigen::Ref<const Eigen::VectorXd>& free_values) const;
  /// Full vector from free values with zero at the prescribed DOFs: for adjoints and state
  /// variations, which vanish where the displacement is prescribed.
  Eigen::VectorXd expand_homogeneous(const Eigen::Ref<const Eigen::VectorXd>& free_values) const;
  /// Free part of a full vector.
  Eigen::VectorXd restrict(const Eigen::Ref<const Eigen::VectorXd>& full) const;

 private:
  std::vector<int> free_index_;
  std::vector<int> free_dofs_;
  Eigen::VectorXd prescribed_values_;
};

}  // namespace frictopt::fem
