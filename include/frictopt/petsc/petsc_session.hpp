// SPDX-License-Identifier: MIT
// The process's PETSc/MPI lifetime as an RAII guard (docs/petsc-engine.md): the command line
// creates one PetscSession in main(); PETSc (and MPI) are initialized only when an engine first
// needs them, so a run with engine = "direct" never calls MPI_Init and needs no mpirun.
#pragma once

#include <string>

namespace frictopt::petsc {

/// Owns PetscInitialize/PetscFinalize for the process. At most one exists at a time.
/// Construction does nothing but register the guard; require() initializes PETSc on first use
/// (without command-line arguments: PETSc options come from a case's [solver] petsc_options
/// or the PETSC_OPTIONS environment variable), and the destructor finalizes it if it was
/// initialized. Not thread-safe (PETSc is used from the main thread only).
class PetscSession {
 public:
  PetscSession();
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  /// Initializes PETSc if needed. Throws InvalidInput when no PetscSession exists (a program
  /// that uses the PETSc engine must create one in main) and NumericalFailure when
  /// PetscInitialize fails.
  static void require();
  /// True when PETSc has been initialized by the current session.
  static bool initialized();
  /// Rank in PETSC_COMM_WORLD (0 when not initialized) and the number of ranks (1).
  static int rank();
  static int size();
  /// The MPI rank this process was launched as, read from the launcher's environment
  /// (OpenMPI, MPICH/PMI, Slurm) without initializing MPI; 0 when not launched by mpirun.
  static int launcher_rank();
  static int launcher_size();
  /// Rank 0's `text` on every rank (MPI_Bcast over PETSC_COMM_WORLD); initializes PETSc if
  /// needed (collective: every rank calls it). How rank 0, which owns a run directory, hands
  /// the files of a run to the other ranks (optimize --resume under mpirun).
  static void broadcast_from_rank0(std::string& text);
};

}  // namespace frictopt::petsc
