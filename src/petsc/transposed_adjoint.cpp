// SPDX-License-Identifier: MIT
#include "transposed_adjoint.hpp"

#include <fmt/format.h>

#include "petsc_check.hpp"

namespace frictopt::petsc::detail {

TransposedAdjoint::TransposedAdjoint(MatNullSpace near_null_space, PetscOptions database, double relative_tolerance,
                                     int max_iterations)
    : near_null_space_(near_null_space) {
  FRICTOPT_PETSC_CALL(KSPCreate(PETSC_COMM_WORLD, &ksp_));
  // The state's defaults (docs/petsc-engine.md): Jᵀ is as non-symmetric as J where nodes slip.
  FRICTOPT_PETSC_CALL(KSPSetType(ksp_, KSPGMRES));
  FRICTOPT_PETSC_CALL(KSPGMRESSetRestart(ksp_, 100));
  PC pc;
  FRICTOPT_PETSC_CALL(KSPGetPC(ksp_, &pc));
  FRICTOPT_PETSC_CALL(PCSetType(pc, PCGAMG));
  FRICTOPT_PETSC_CALL(KSPSetTolerances(ksp_, relative_tolerance, 0.0, PETSC_DEFAULT, max_iterations));
  // The engine's options database: an expert's -pc_type/-ksp_type choice serves both solves.
  FRICTOPT_PETSC_CALL(PetscObjectSetOptions(reinterpret_cast<PetscObject>(ksp_), database));
  FRICTOPT_PETSC_CALL(PetscObjectSetOptions(reinterpret_cast<PetscObject>(pc), database));
  FRICTOPT_PETSC_CALL(KSPSetFromOptions(ksp_));
}

TransposedAdjoint::~TransposedAdjoint() { KSPDestroy(&ksp_); }

TransposedAdjoint::Solve TransposedAdjoint::solve(Mat J, Vec b, Vec psi) {
  Solve out;
  Mat Jt = nullptr;
  FRICTOPT_PETSC_CALL(MatTranspose(J, MAT_INITIAL_MATRIX, &Jt));
  FRICTOPT_PETSC_CALL(MatSetNearNullSpace(Jt, near_null_space_));
  FRICTOPT_PETSC_CALL(KSPSetOperators(ksp_, Jt, Jt));
  FRICTOPT_PETSC_CALL(VecSet(psi, 0.0));
  FRICTOPT_PETSC_CALL(KSPSolve(ksp_, b, psi));
  PetscInt its = 0;
  FRICTOPT_PETSC_CALL(KSPGetIterationNumber(ksp_, &its));
  out.iterations = static_cast<int>(its);
  FRICTOPT_PETSC_CALL(KSPGetConvergedReason(ksp_, &out.reason));
  {
    KSPType ksp_type;
    PC pc;
    PCType pc_type;
    FRICTOPT_PETSC_CALL(KSPGetType(ksp_, &ksp_type));
    FRICTOPT_PETSC_CALL(KSPGetPC(ksp_, &pc));
    FRICTOPT_PETSC_CALL(PCGetType(pc, &pc_type));
    out.krylov_type = fmt::format("{}+{}", ksp_type ? ksp_type : "?", pc_type ? pc_type : "?");
  }
  // The true residual (GMRES monitors the preconditioned one).
  Vec r = nullptr;
  FRICTOPT_PETSC_CALL(VecDuplicate(b, &r));
  FRICTOPT_PETSC_CALL(MatMult(Jt, psi, r));
  FRICTOPT_PETSC_CALL(VecAXPY(r, -1.0, b));
  PetscReal residual = 0.0, rhs = 0.0;
  FRICTOPT_PETSC_CALL(VecNorm(r, NORM_2, &residual));
  FRICTOPT_PETSC_CALL(VecNorm(b, NORM_2, &rhs));
  out.relative_residual = rhs > 0 ? residual / rhs : 0.0;
  FRICTOPT_PETSC_CALL(VecDestroy(&r));
  // Release Jᵀ and its AMG hierarchy until the next subgradient.
  FRICTOPT_PETSC_CALL(KSPReset(ksp_));
  FRICTOPT_PETSC_CALL(MatDestroy(&Jt));
  return out;
}

}  // namespace frictopt::petsc::detail
