# SPDX-License-Identifier: MIT
# Every third-party package frictopt uses, found in one place (docs/architecture.md §1). Which module
# links which package is said in that module's src/<module>/CMakeLists.txt; the installed
# package config (cmake/frictoptConfig.cmake.in) finds again only what the requested
# components need. The Debian packages behind these are listed in scripts/install-deps.sh.

# Every module: dense linear algebra.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# shape, mesh, fem, sensitivity, cost, study, io, linalg, apps: message formatting (private).
find_package(fmt REQUIRED)
# linalg: the sparse Cholesky backend and the dense kernels (private). Debian's SuiteSparse 5.x
# ships no CMake config; CHOLMOD is found through our small module cmake/FindCholmod.cmake.
find_package(Cholmod REQUIRED)
# mesh: the Gmsh library reads .msh files and meshes .geo files (docs/meshes.md; private). Debian's
# libgmsh-dev ships no CMake config: cmake/FindGmsh.cmake finds gmsh.h and libgmsh.
find_package(Gmsh REQUIRED)
# The generic libblas/liblapack names, which Debian's alternatives point at OpenBLAS — the BLAS
# that CHOLMOD itself is linked against. Without a vendor FindBLAS may pick ATLAS
# (libf77blas + libatlas) when it is installed; linked ahead of libblas it also captured
# CHOLMOD's dgemm/dsyrk/dtrsm, which made the supernodal factorization twice as slow.
if(NOT DEFINED BLA_VENDOR)
  set(BLA_VENDOR Generic)
endif()
find_package(BLAS REQUIRED)
find_package(LAPACK REQUIRED)
# OpenBLAS itself, linked as the first needed library of every executable and module
# (frictopt_link_openblas_first in cmake/FrictoptModule.cmake). Debian's libceres.so needs
# ATLAS' libf77blas.so.3 (and libatlas.so.3) besides liblapack.so.3; in the dynamic linker's
# breadth-first lookup order ATLAS' dgemm_/dsyrk_/dtrsm_ came before OpenBLAS', and CHOLMOD's
# supernodal factorization ran on them 2-2.6x slower (docs/benchmarks.md, "Which BLAS").
# libopenblas.so.0 is the runtime name (package libopenblas0-pthread; no -dev package needed).
option(FRICTOPT_REQUIRE_OPENBLAS "Refuse to configure without OpenBLAS (libopenblas.so.0)" ON)
find_library(FRICTOPT_OPENBLAS_LIBRARY NAMES libopenblas.so.0 openblas
             DOC "OpenBLAS, linked first into every frictopt executable and module")
if(NOT FRICTOPT_OPENBLAS_LIBRARY)
  if(FRICTOPT_REQUIRE_OPENBLAS)
    message(FATAL_ERROR "frictopt: OpenBLAS (libopenblas.so.0) not found; install libopenblas0-pthread "
                        "(scripts/install-deps.sh), give -DFRICTOPT_OPENBLAS_LIBRARY=/path/libopenblas.so.0, "
                        "or -DFRICTOPT_REQUIRE_OPENBLAS=OFF to build on whatever BLAS the system resolves "
                        "(the test LoadedBlas.IsOpenBlas then fails)")
  endif()
  message(WARNING "frictopt: OpenBLAS not found; CHOLMOD and LAPACK use whatever BLAS the loader finds first")
endif()
# study: identification (least squares, covariance; docs/identification.md).
find_package(Ceres REQUIRED)
# io: case files (TOML), VTK XML output, JSON.
find_package(tomlplusplus REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(VTK REQUIRED COMPONENTS CommonCore CommonDataModel IOXML)
# io: FCLIB export (HDF5; docs/contact.md, "FCLIB export"). Debian's libfclib-dev ships a CMake config
# (FCLIB::fclib, which finds the HDF5 C and HL libraries itself). CMake's FindHDF5 (called by
# fclib's config) probes the HDF5 compiler wrappers with a C try_compile, so C must be enabled;
# no C source is compiled.
enable_language(C)
find_package(fclib 3 CONFIG REQUIRED)
set_target_properties(FCLIB::fclib PROPERTIES IMPORTED_GLOBAL TRUE)  # tests/io reads files back

# petsc (optional, FRICTOPT_WITH_PETSC): the distributed engine, found through pkg-config and
# FindMPI by our module cmake/FindPETScMPI.cmake (AUTO: built when found; ON: required).
set(FRICTOPT_HAVE_PETSC OFF)
if(NOT FRICTOPT_WITH_PETSC STREQUAL "OFF")
  if(FRICTOPT_WITH_PETSC STREQUAL "ON")
    find_package(PETScMPI REQUIRED)
  else()
    find_package(PETScMPI)
  endif()
  if(PETScMPI_FOUND)
    set(FRICTOPT_HAVE_PETSC ON)
    message(STATUS "frictopt: PETSc ${PETSC_VERSION} found; the PETSc engine is built")
  else()
    message(STATUS "frictopt: PETSc not found; the PETSc engine is not built (FRICTOPT_WITH_PETSC=AUTO)")
  endif()
  set(FRICTOPT_PACKAGE_OF_PkgConfig::PETSC "PETScMPI")
  set(FRICTOPT_PACKAGE_OF_MPI::MPI_C "PETScMPI")
endif()

if(FRICTOPT_BUILD_APPS)
  find_package(CLI11 REQUIRED)  # the command line's argument parser
endif()
if(FRICTOPT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(FRICTOPT_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# What an installed frictopt must find again for each third-party target its modules link
# (find_dependency arguments; read by cmake/FrictoptInstall.cmake).
set(FRICTOPT_PACKAGE_OF_Eigen3::Eigen "Eigen3;3.4;NO_MODULE")
set(FRICTOPT_PACKAGE_OF_fmt::fmt "fmt")
set(FRICTOPT_PACKAGE_OF_SuiteSparse::cholmod "Cholmod")
set(FRICTOPT_PACKAGE_OF_Gmsh::gmsh "Gmsh")
set(FRICTOPT_PACKAGE_OF_BLAS::BLAS "BLAS")
set(FRICTOPT_PACKAGE_OF_LAPACK::LAPACK "LAPACK")
set(FRICTOPT_PACKAGE_OF_Ceres::ceres "Ceres")
set(FRICTOPT_PACKAGE_OF_tomlplusplus::tomlplusplus "tomlplusplus")
set(FRICTOPT_PACKAGE_OF_nlohmann_json::nlohmann_json "nlohmann_json;3")
set(FRICTOPT_PACKAGE_OF_FCLIB::fclib "fclib;3;CONFIG")
foreach(_vtk_module CommonCore CommonDataModel IOXML)
  set(FRICTOPT_PACKAGE_OF_VTK::${_vtk_module} "VTK;COMPONENTS;CommonCore;CommonDataModel;IOXML")
endforeach()
