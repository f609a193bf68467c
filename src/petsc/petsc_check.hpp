// SPDX-License-Identifier: MIT
// PETSc error codes turned into frictopt's error types (private to the petsc module). PETSc's
// own handler would print a traceback to stderr; the session installs the returning handler,
// so a failed call reports here, once, with PETSc's message.
#pragma once

#include <petscsys.h>

#include <string>

namespace frictopt::petsc::detail {

/// Throws NumericalFailure "PETSc: <call> failed: <PETSc's message> (error code n)".
[[noreturn]] void throw_petsc_error(const char* call, PetscErrorCode code);

}  // namespace frictopt::petsc::detail

#define FRICTOPT_PETSC_CALL(expr)                                                          \
  do {                                                                                     \
    const PetscErrorCode frictopt_petsc_code_ = (expr);                                    \
    if (frictopt_petsc_code_ != 0) ::frictopt::petsc::detail::throw_petsc_error(#expr, frictopt_petsc_code_); \
  } while (0)
