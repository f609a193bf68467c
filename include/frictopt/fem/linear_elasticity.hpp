// SPDX-License-Identifier: MIT
// Linear elasticity on the morphed mesh: assembly with a fixed sparsity pattern, factorization
// through linalg::SpdSolver with one symbolic analysis per mesh, and the shape-derivative kernel.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "frictopt/core/status.hpp"
#include "frictopt/fem/boundary_conditions.hpp"
#include "frictopt/fem/material.hpp"
#include "frictopt/linalg/spd_solver.hpp"
#include "frictopt/mesh/mesh.hpp"

namespace frictopt::fem {

/// A(α) u = l(α) on the free DOFs of a Mesh (element kernels are templates over the mesh's
/// element class; Q1 with 2×2(×2) Gauss today), 2D plane strain or stress per unit thickness,
/// or 3D.
///
/// Conventions: full vectors have mesh.num_dofs() entries, node-major (node·dim + component);
/// "free" vectors follow dofs().free_dofs(). The reduced load contains the tractions on Γ_p and
/// the lifting −A_fd u_d of nonzero Dirichlet values, so for a full u with u_d prescribed,
///   A_ff u_f − l_f = (A_full u − l_traction)_f.
/// Lifetime: `mesh` must outlive this object. The sparsity pattern and the symbolic analysis
/// are built once; assemble() and factorize() are per design. Not thread-safe.
class LinearElasticity {
 public:
  /// Throws InvalidInput for an invalid material or traction vectors of the wrong size.
  /// `solver` chooses the SpdSolver backend that factorizes the stiffness. `ties`: groups of
  /// DOFs that share one unknown (DofMap; loading plates), so that the assembled stiffness and
  /// load are PᵀA_fullP and Pᵀl (docs/theory/loading-plate.md).
  LinearElasticity(const mesh::Mesh& mesh, const IsotropicMaterial& material,
                   const PrescribedDofs& dirichlet, std::vector<FaceTraction> tractions,
                   linalg::SpdSolver::Options solver = {}, const std::vector<std::vector<int>>& ties = {});

  const mesh::Mesh& mesh() const { return mesh_; }
  const DofMap& dofs() const { return dofs_; }
  const IsotropicMaterial& material() const { return material_; }

  /// Assembles A(X) and l(X) for node positions X (num_nodes × dim), reusing the pattern.
  void assemble(const Eigen::Ref<const Eigen::MatrixXd>& X);
  const Eigen::SparseMatrix<double>& stiffness() const { return A_; }  ///< free × free, full symmetric storage
  const Eigen::VectorXd& load() const { return l_; }                   ///< free
  /// Orders these free-DOF indices last in the factorization (before the first factorize):
  /// the trailing block of L is then the Cholesky factor of the Schur complement onto them
  /// (linalg::SpdSolver::trailing_factor), e.g. the contact DOFs for the Delassus matrix.
  /// Requires factorization().supports_trailing_factor().
  void set_trailing_dofs(std::vector<int> free_indices);
  /// Factorizes the last assembled A (symbolic analysis on the first call, or after a failed
  /// one). A failed analysis or factorization is a status; factorization().message() says why.
  [[nodiscard]] Status factorize();
  const linalg::SpdSolver& factorization() const { return *solver_; }
  /// Replaces the solver behind factorization() by `solver` (already able to solve, e.g. the
  /// PETSc engine's Krylov solves, docs/petsc-engine.md); factorize() is then not called by the
  /// owner.
  void set_factorization(std::unique_ptr<linalg::SpdSolver> solver) { solver_ = std::move(solver); }
  /// A floating body (study/floating_body.hpp): the rigid motions the conditions leave free (full
  /// DOF vectors, orthonormal, zero at the user's prescribed DOFs) that the factorized system
  /// holds by its fixing DOFs; `translations` says whether each is a translation (then it does
  /// not depend on the design). The sensitivity reads them (sensitivity::AdjointSensitivity:
  /// the adjoint bordered by the equilibrium rows, docs/theory/loading-plate.md §3).
  void set_free_modes(Eigen::MatrixXd modes, bool translations) {
    free_modes_ = std::move(modes);
    free_modes_translations_ = translations;
  }
  const Eigen::MatrixXd& free_modes() const { return free_modes_; }
  bool free_modes_are_translations() const { return free_modes_translations_; }
  /// The full displacement for the assembled load: u_f = A⁻¹ l, u_d prescribed.
  Eigen::VectorXd solve() const;

  /// Full traction load vector l_traction(X) (num_dofs), without Dirichlet lifting.
  Eigen::VectorXd traction_load(const Eigen::Ref<const Eigen::MatrixXd>& X) const;
  /// Full residual A_full(X) u − l_traction(X) (num_dofs), element by element: at prescribed
  /// DOFs these are the reaction forces; at contact DOFs, minus the contact forces.
  Eigen::VectorXd residual(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) const;

  /// The shape-derivative kernel: ∇_α [pᵀ(A_full(α) u − l_traction(α))] for fixed full vectors
  /// u, p (d entries), = Vᵀ ∂/∂X[…], computed element by element (never a 3-tensor). With p
  /// zero on prescribed DOFs this is the α-derivative of the reduced residual tested with p —
  /// the term Ξᵀp of the adjoint sensitivity (docs/theory/sensitivity.md §6).
  Eigen::VectorXd shape_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                   const Eigen::Ref<const Eigen::VectorXd>& u,
                                   const Eigen::Ref<const Eigen::VectorXd>& p) const;
  /// The forward (Jacobian-vector) counterpart: d/dε [A_full(X + ε dX) u − l_traction(X + ε dX)]
  /// (num_dofs) for a node motion dX (num_nodes × dim), e.g. dX = V h reshaped.
  Eigen::VectorXd residual_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u,
                                      const Eigen::Ref<const Eigen::MatrixXd>& dX) const;
  /// The same derivative with respect to the node coordinates X (num_dofs, node-major).
  Eigen::VectorXd coordinate_derivative(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                        const Eigen::Ref<const Eigen::VectorXd>& u,
                                        const Eigen::Ref<const Eigen::VectorXd>& p) const;

  /// Strain energy ½ uᵀ A_full u [J] and work of the tractions l_tractionᵀ u [J] (full u).
  double strain_energy(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) const;
  double external_work(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) const;

 private:
  template <class Element> void assemble_impl(const Eigen::Ref<const Eigen::MatrixXd>& X);
  template <class Element> Eigen::VectorXd residual_impl(const Eigen::Ref<const Eigen::MatrixXd>& X, const Eigen::Ref<const Eigen::VectorXd>& u) const;
  template <class Element> Eigen::VectorXd coordinate_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                                const Eigen::Ref<const Eigen::VectorXd>& u,
                                                                const Eigen::Ref<const Eigen::VectorXd>& p) const;
  template <class Element> Eigen::VectorXd residual_derivative_impl(const Eigen::Ref<const Eigen::MatrixXd>& X,
                                                              const Eigen::Ref<const Eigen::VectorXd>& u,
                                                              const Eigen::Ref<const Eigen::MatrixXd>& dX) const;
  template <class Element> Eigen::VectorXd traction_load_impl(const Eigen::Ref<const Eigen::MatrixXd>& X) const;
  void build_pattern();

  const mesh::Mesh& mesh_;
  IsotropicMaterial material_;
  DofMap dofs_;
  std::vector<FaceTraction> tractions_;
  Eigen::SparseMatrix<double> A_;
  Eigen::VectorXd l_;
  std::vector<int> scatter_;  // per element, per (local i, local j): index into A_'s values or −1
  linalg::SpdSolver::Options solver_options_;
  std::unique_ptr<linalg::SpdSolver> solver_;
  std::vector<int> trailing_;
  Eigen::MatrixXd free_modes_;
  bool free_modes_translations_ = true;
};

}  // namespace frictopt::fem
