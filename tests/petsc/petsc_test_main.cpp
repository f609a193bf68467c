// SPDX-License-Identifier: MIT
// GoogleTest main of the petsc tests: the process's PetscSession lives around RUN_ALL_TESTS, as
// in the command line's main (PETSc is initialized by the first test that needs it).
#include <gtest/gtest.h>

#include "frictopt/petsc/petsc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const frictopt::petsc::PetscSession session;
  return RUN_ALL_TESTS();
}
