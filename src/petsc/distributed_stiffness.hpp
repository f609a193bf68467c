// SPDX-License-Identifier: MIT
// The stiffness of a replicated mesh assembled distributed into a PETSc MATMPIAIJ (private to
// the petsc module; docs/petsc-engine.md): rows are whole nodes (block size dim, node-major
// DOFs as in fem), rank r owns a contiguous range of nodes, and each rank computes the element
// matrices of the elements whose first node it owns (fem's Q1 kernel), so an element is
// computed once and most of its entries land in local rows.
#pragma once

#include <petscmat.h>

#include <Eigen/Core>
#include <vector>

#include "frictopt/fem/linear_elasticity.hpp"

namespace frictopt::petsc::detail {

/// Lifetime: `fem` (and its mesh) must outlive this object. Collective on PETSC_COMM_WORLD.
class DistributedStiffness {
 public:
  /// Partitions the nodes, preallocates the matrix exactly (block adjacency of the owned
  /// nodes) and attaches the rigid-body modes of the reference mesh as near-null space.
  explicit DistributedStiffness(const fem::LinearElasticity& fem);
  ~DistributedStiffness();
  DistributedStiffness(const DistributedStiffness&) = delete;
  DistributedStiffness& operator=(const DistributedStiffness&) = delete;

  /// K(X) over all DOFs (no boundary conditions) and the traction load f(X) (full, owned part).
  void assemble(const Eigen::Ref<const Eigen::MatrixXd>& X);
  Mat matrix() const { return K_; }
  Vec load() const { return f_; }
  /// A new vector with the matrix's layout (caller destroys it).
  Vec create_vector() const;
  /// Owned nodes [first_node, end_node) and DOFs [first_dof, end_dof).
  int first_node() const { return first_node_; }
  int end_node() const { return end_node_; }
  int first_dof() const { return first_node_ * dim_; }
  int end_dof() const { return end_node_ * dim_; }
  bool owns_node(int node) const { return node >= first_node_ && node < end_node_; }
  /// Elements this rank computes.
  int num_local_elements() const { return static_cast<int>(elements_.size()); }
  /// Rigid-body modes (attach to every operator whose preconditioner is AMG).
  MatNullSpace near_null_space() const { return near_null_; }

 private:
  template <class Element> void assemble_impl(const Eigen::Ref<const Eigen::MatrixXd>& X);

  const fem::LinearElasticity& fem_;
  int dim_;
  int first_node_ = 0, end_node_ = 0;
  std::vector<int> elements_;  // element indices computed here
  Mat K_ = nullptr;
  Vec f_ = nullptr;
  MatNullSpace near_null_ = nullptr;
};

}  // namespace frictopt::petsc::detail
