# SPDX-License-Identifier: MIT
# PETSc with its MPI (the petsc module, docs/petsc-engine.md). Debian's petsc-dev ships a pkg-config file
# (PETSc) but no CMake config, and its headers include mpi.h, which the pkg-config flags do not
# name: MPI comes from CMake's FindMPI. Defines PkgConfig::PETSC and MPI::MPI_C, PETScMPI_FOUND,
# PETSC_VERSION and FRICTOPT_MPIEXEC (mpiexec, for the tests).
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(PETSC QUIET IMPORTED_TARGET GLOBAL PETSc)
endif()
find_package(MPI QUIET COMPONENTS C)
find_program(FRICTOPT_MPIEXEC NAMES mpiexec mpirun)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(PETScMPI REQUIRED_VARS PETSC_FOUND MPI_C_FOUND VERSION_VAR PETSC_VERSION)
