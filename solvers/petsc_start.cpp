// PETSc started, its errors, the ranks: inside the PETSc module.
#include <petscsys.h>

#include <cstdlib>
#include <string>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {

void petsc_check(int code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw Error(std::string("petsc: ") + call + " failed: " + (text ? text : "unknown error") + " (code " +
              std::to_string(code) + ")");
}

void start_petsc() {
  PetscBool initialized = PETSC_FALSE;
  petsc_check(PetscInitialized(&initialized), "PetscInitialized");
  if (initialized) return;
  // kerf reports its own errors; PETSc must not take over signals.
  petsc_check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
  petsc_check(PetscInitializeNoArguments(), "PetscInitializeNoArguments");
  std::atexit([] { PetscFinalize(); });
}

RankShare petsc_ranks() {
  start_petsc();
  PetscMPIInt rank = 0, size = 1;
  petsc_check(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  petsc_check(MPI_Comm_size(PETSC_COMM_WORLD, &size), "MPI_Comm_size");
  return {rank, size};
}

void petsc_barrier() { petsc_check(PetscBarrier(nullptr), "PetscBarrier"); }

void petsc_abort(int code) { MPI_Abort(PETSC_COMM_WORLD, code); }

}  // namespace kerf
