// SPDX-License-Identifier: MIT
#include "distributed_stiffness.hpp"

#include <algorithm>

#include "fem/element_kernels.hpp"
#include "frictopt/mesh/elements.hpp"
#include "petsc_check.hpp"

namespace frictopt::petsc::detail {

DistributedStiffness::DistributedStiffness(const fem::LinearElasticity& fem)
    : fem_(fem), dim_(fem.mesh().dim()) {
  const mesh::Mesh& mesh = fem.mesh();
  PetscMPIInt rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  // Contiguous node ranges: the structured grid numbers nodes lexicographically, so a range is
  // a slab of node layers and the communication is the slab faces (docs/scaling.md).
  const long long n = mesh.num_nodes();
  first_node_ = static_cast<int>(n * rank / size);
  end_node_ = static_cast<int>(n * (rank + 1) / size);
  const auto& elements = mesh.elements();
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    if (owns_node(elements(e, 0))) elements_.push_back(static_cast<int>(e));

  // Exact block preallocation: the nodes sharing an element with each owned node.
  const int local_nodes = end_node_ - first_node_;
  std::vector<std::vector<int>> adjacency(static_cast<std::size_t>(local_nodes));
  for (Eigen::Index e = 0; e < elements.rows(); ++e)
    for (Eigen::Index a = 0; a < elements.cols(); ++a) {
      const int node = elements(e, a);
      if (!owns_node(node)) continue;
      auto& list = adjacency[static_cast<std::size_t>(node - first_node_)];
      for (Eigen::Index b = 0; b < elements.cols(); ++b) list.push_back(elements(e, b));
    }
  std::vector<PetscInt> diagonal(static_cast<std::size_t>(local_nodes)), off(static_cast<std::size_t>(local_nodes));
  for (int i = 0; i < local_nodes; ++i) {
    auto& list = adjacency[static_cast<std::size_t>(i)];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    const auto inside = std::count_if(list.begin(), list.end(), [&](int m) { return owns_node(m); });
    diagonal[static_cast<std::size_t>(i)] = static_cast<PetscInt>(inside);
    off[static_cast<std::size_t>(i)] = static_cast<PetscInt>(list.size()) - static_cast<PetscInt>(inside);
    list = {};
  }
  FRICTOPT_PETSC_CALL(MatCreate(PETSC_COMM_WORLD, &K_));
  FRICTOPT_PETSC_CALL(MatSetSizes(K_, local_nodes * dim_, local_nodes * dim_, PETSC_DETERMINE, PETSC_DETERMINE));
  FRICTOPT_PETSC_CALL(MatSetBlockSize(K_, dim_));
  FRICTOPT_PETSC_CALL(MatSetType(K_, MATAIJ));  // MATMPIAIJ on several ranks, MATSEQAIJ on one
  FRICTOPT_PETSC_CALL(MatXAIJSetPreallocation(K_, dim_, diagonal.data(), off.data(), nullptr, nullptr));
  FRICTOPT_PETSC_CALL(MatSetOption(K_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  FRICTOPT_PETSC_CALL(MatCreateVecs(K_, &f_, nullptr));

  // Rigid-body modes from the reference coordinates (3 in 2D, 6 in 3D): GAMG builds its
  // coarse spaces from them (MatNullSpaceCreateRigidBody).
  Vec coordinates;
  FRICTOPT_PETSC_CALL(VecDuplicate(f_, &coordinates));
  FRICTOPT_PETSC_CALL(VecSetBlockSize(coordinates, dim_));
  PetscScalar* c = nullptr;
  FRICTOPT_PETSC_CALL(VecGetArray(coordinates, &c));
  const Eigen::MatrixXd& X0 = mesh.reference_positions();
  for (int node = first_node_; node < end_node_; ++node)
    for (int k = 0; k < dim_; ++k) c[(node - first_node_) * dim_ + k] = X0(node, k);
  FRICTOPT_PETSC_CALL(VecRestoreArray(coordinates, &c));
  FRICTOPT_PETSC_CALL(MatNullSpaceCreateRigidBody(coordinates, &near_null_));
  FRICTOPT_PETSC_CALL(VecDestroy(&coordinates));
  FRICTOPT_PETSC_CALL(MatSetNearNullSpace(K_, near_null_));
}

DistributedStiffness::~DistributedStiffness() {
  MatNullSpaceDestroy(&near_null_);
  VecDestroy(&f_);
  MatDestroy(&K_);
}

Vec DistributedStiffness::create_vector() const {
  Vec v;
  FRICTOPT_PETSC_CALL(VecDuplicate(f_, &v));
  return v;
}

template <class Element>
void DistributedStiffness::assemble_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  using Kernel = fem::detail::ElasticityKernel<Element>;
  const Kernel kernel{fem_.material().lame_lambda(Element::kDim), fem_.material().shear_modulus()};
  const auto& elements = fem_.mesh().elements();
  FRICTOPT_PETSC_CALL(MatZeroEntries(K_));
  Eigen::Matrix<double, Kernel::kDofs, Kernel::kDofs, Eigen::RowMajor> Ke;
  PetscInt nodes[Kernel::kNodes];
  typename Kernel::Coordinates Xe;
  for (int e : elements_) {
    for (int a = 0; a < Kernel::kNodes; ++a) {
      nodes[a] = elements(e, a);
      Xe.row(a) = X.row(elements(e, a));
    }
    Ke = kernel.stiffness(Xe);
    FRICTOPT_PETSC_CALL(MatSetValuesBlocked(K_, Kernel::kNodes, nodes, Kernel::kNodes, nodes, Ke.data(), ADD_VALUES));
  }
  FRICTOPT_PETSC_CALL(MatAssemblyBegin(K_, MAT_FINAL_ASSEMBLY));
  FRICTOPT_PETSC_CALL(MatAssemblyEnd(K_, MAT_FINAL_ASSEMBLY));
}

void DistributedStiffness::assemble(const Eigen::Ref<const Eigen::MatrixXd>& X) {
  mesh::with_element(fem_.mesh().element_kind(), [&](auto element) { assemble_impl<decltype(element)>(X); });
  // The traction load is a surface integral over few facets: computed replicated by fem and
  // the owned part copied.
  const Eigen::VectorXd traction = fem_.traction_load(X);
  PetscScalar* f = nullptr;
  FRICTOPT_PETSC_CALL(VecGetArray(f_, &f));
  for (int dof = first_dof(); dof < end_dof(); ++dof) f[dof - first_dof()] = traction(dof);
  FRICTOPT_PETSC_CALL(VecRestoreArray(f_, &f));
}

}  // namespace frictopt::petsc::detail
