// SPDX-License-Identifier: MIT
#include "frictopt/petsc/petsc_session.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "frictopt/core/error.hpp"
#include "petsc_check.hpp"

namespace frictopt::petsc {
namespace {
PetscSession* g_session = nullptr;  // the registered guard (at most one)
bool g_initialized_here = false;    // PetscInitialize was called by the guard

int environment_int(std::initializer_list<const char*> names, int fallback) {
  for (const char* name : names)
    if (const char* value = std::getenv(name)) return std::atoi(value);
  return fallback;
}
}  // namespace

namespace detail {
void throw_petsc_error(const char* call, PetscErrorCode code) {
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw NumericalFailure(fmt::format("PETSc: {} failed: {} (error code {})", call, text ? text : "unknown error",
                                     static_cast<int>(code)));
}
}  // namespace detail

PetscSession::PetscSession() {
  if (g_session != nullptr) throw InvalidInput("PetscSession: a session exists already; create one per process");
  g_session = this;
}

PetscSession::~PetscSession() {
  if (g_initialized_here) {
    PetscFinalize();
    g_initialized_here = false;
  }
  g_session = nullptr;
}

void PetscSession::require() {
  if (g_initialized_here) return;
  if (g_session == nullptr)
    throw InvalidInput("the PETSc engine needs a frictopt::petsc::PetscSession in main(); none exists");
  // No argv: frictopt's own command line is parsed by CLI11; PETSc options come from the case
  // ([solver] petsc_options) or the PETSC_OPTIONS environment variable.
  if (PetscInitializeNoArguments() != 0) throw NumericalFailure("PETSc: PetscInitialize failed");
  g_initialized_here = true;
  // Errors come back as codes (FRICTOPT_PETSC_CALL reports them); no traceback on stderr
  // unless FRICTOPT_PETSC_TRACEBACK is set (a debugging aid, docs/petsc-engine.md).
  if (!std::getenv("FRICTOPT_PETSC_TRACEBACK")) PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
}

bool PetscSession::initialized() { return g_initialized_here; }

int PetscSession::rank() {
  if (!g_initialized_here) return 0;
  PetscMPIInt r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

int PetscSession::size() {
  if (!g_initialized_here) return 1;
  PetscMPIInt s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

int PetscSession::launcher_rank() {
  return environment_int({"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK", "SLURM_PROCID"}, 0);
}

int PetscSession::launcher_size() {
  return environment_int({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS"}, 1);
}

void PetscSession::broadcast_from_rank0(std::string& text) {
  require();
  unsigned long long size = text.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, PETSC_COMM_WORLD);
  text.resize(size);
  // In chunks: MPI counts are int.
  constexpr std::size_t kChunk = std::size_t{1} << 30;
  for (std::size_t offset = 0; offset < size; offset += kChunk)
    MPI_Bcast(text.data() + offset, static_cast<int>(std::min<std::size_t>(kChunk, size - offset)), MPI_CHAR, 0,
              PETSC_COMM_WORLD);
}

}  // namespace frictopt::petsc
