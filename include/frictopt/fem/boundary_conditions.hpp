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

/// Numbering of the unknowns of the reduced system: free(dof) is the row in the reduced system
/// or −1 (prescribed). Tied DOFs (docs/theory/loading-plate.md): each group of `ties` shares one
/// unknown — a loading plate's translation in one direction — so the reduced vectors are
/// u_red with u_full = P u_red + u_d, P the 0/1 prolongation (one 1 per free or tied row). The
/// reduced stiffness is PᵀAP and the reduced load Pᵀf (restrict_forces); a group's unknown takes
/// the row of its first DOF in the numbering.
class DofMap {
 public:
  /// Throws InvalidInput for a DOF out of range, a tied DOF that is prescribed or in two groups,
  /// or an empty group.
  DofMap(int num_dofs, const PrescribedDofs& prescribed, const std::vector<std::vector<int>>& ties = {});
  int num_dofs() const { return static_cast<int>(free_index_.size()); }
  int num_free() const { return static_cast<int>(free_dofs_.size()); }
  int free_index(int dof) const { return free_index_[dof]; }
  bool is_free(int dof) const { return free_index_[dof] >= 0; }
  /// One DOF per unknown: the DOF itself, or a tied group's first DOF.
  const std::vector<int>& free_dofs() const { return free_dofs_; }
  /// The tie groups as given (each the DOFs sharing one unknown); empty without ties.
  const std::vector<std::vector<int>>& ties() const { return ties_; }
  /// For unknown i: the index of its tie group, or −1 for an untied free DOF.
  int tie_of(int free_index) const { return tie_of_.empty() ? -1 : tie_of_[static_cast<std::size_t>(free_index)]; }
  /// Values of all DOFs with the prescribed ones set and the free ones zero.
  const Eigen::VectorXd& prescribed_values() const { return prescribed_values_; }
  /// Full vector from free values (prescribed values inserted): u = P u_red + u_d.
  Eigen::VectorXd expand(const Eigen::Ref<const Eigen::VectorXd>& free_values) const;
  /// Full vector from free values with zero at the prescribed DOFs (P u_red): for adjoints and
  /// state variations, which vanish where the displacement is prescribed.
  Eigen::VectorXd expand_homogeneous(const Eigen::Ref<const Eigen::VectorXd>& free_values) const;
  /// The unknowns of a full displacement-like vector: the value at each unknown's DOF (exact
  /// for a vector of the form P u_red + u_d, e.g. a state or a rigid motion the ties allow).
  Eigen::VectorXd restrict(const Eigen::Ref<const Eigen::VectorXd>& full) const;
  /// The reduced force of a full force-like vector (loads, residuals, cost gradients with
  /// respect to u): Pᵀ f, the sum over each tied group; the free entries without ties.
  Eigen::VectorXd restrict_forces(const Eigen::Ref<const Eigen::VectorXd>& full) const;

 private:
  std::vector<int> free_index_;
  std::vector<int> free_dofs_;
  std::vector<std::vector<int>> ties_;
  std::vector<int> tie_of_;  // per unknown; empty without ties
  Eigen::VectorXd prescribed_values_;
};

}  // namespace frictopt::fem
