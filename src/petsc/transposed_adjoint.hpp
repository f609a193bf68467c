// SPDX-License-Identifier: MIT
// The one linear solve of the PETSc engine's adjoint (docs/petsc-engine.md, "Subgradient"):
// Jᵀψ = b with J the generalized Jacobian of the semismooth Newton system at the converged
// state (private to the petsc module). Jᵀ is formed explicitly (MatTranspose: O(nnz), a small
// fraction of one Krylov solve) rather than solved by KSPSolveTranspose, because the default
// preconditioner (GAMG with Chebyshev smoothers) does not apply its transpose in every PETSc
// version; explicit Jᵀ gets the same AMG as the state's steps, set up on the adjoint operator.
#pragma once

#include <petscksp.h>

#include <string>

namespace frictopt::petsc::detail {

/// Owns the adjoint's KSP (GMRES(100) + GAMG by default, the rigid-body near-null space
/// attached, every KSP/PC option of the engine's database applied). Jᵀ and the AMG hierarchy
/// live only during solve(): the memory peak of a subgradient is the state's plus one matrix
/// and one hierarchy. Collective on PETSC_COMM_WORLD.
class TransposedAdjoint {
 public:
  struct Solve {
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    int iterations = 0;
    double relative_residual = 0.0;  ///< ‖Jᵀψ − b‖₂ / ‖b‖₂ (0 when b = 0)
    std::string krylov_type;         ///< e.g. "gmres+gamg"
  };

  TransposedAdjoint(MatNullSpace near_null_space, PetscOptions database, double relative_tolerance, int max_iterations);
  ~TransposedAdjoint();
  TransposedAdjoint(const TransposedAdjoint&) = delete;
  TransposedAdjoint& operator=(const TransposedAdjoint&) = delete;

  /// ψ = J⁻ᵀ b (ψ's initial value is ignored: the solve starts from zero).
  Solve solve(Mat J, Vec b, Vec psi);

 private:
  KSP ksp_ = nullptr;
  MatNullSpace near_null_space_;
};

}  // namespace frictopt::petsc::detail
