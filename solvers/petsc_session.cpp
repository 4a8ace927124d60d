#include "solvers/petsc_session.h"

#include <petscsys.h>

#include <cstdlib>
#include <string>

#include "core/check.h"

namespace kerf {
namespace {

void check(PetscErrorCode code, const char* call) {
  KERF_CHECK(code == 0, "petsc: ", call, " failed (code ", code, ")");
}

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_SIZE") != nullptr;
}

}  // namespace

void ensure_petsc_initialized() {
  PetscBool initialized = PETSC_FALSE;
  check(PetscInitialized(&initialized), "PetscInitialized");
  if (initialized) return;
  check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
  check(PetscInitializeNoArguments(), "PetscInitializeNoArguments");
  std::atexit([] { PetscFinalize(); });
}

MpiRanks mpi_ranks() {
  if (!launched_by_mpi()) return {};
  ensure_petsc_initialized();
  PetscMPIInt rank = 0, size = 1;
  check(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  check(MPI_Comm_size(PETSC_COMM_WORLD, &size), "MPI_Comm_size");
  return {rank, size};
}

}  // namespace kerf
