#include "solvers/petsc_session.h"

#include <petscsys.h>
#include <petscvec.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include "core/check.h"

namespace kerf {
namespace {

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_SIZE") != nullptr;
}

}  // namespace

void check_petsc(int code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw Error(std::string("petsc: ") + call + " failed: " + (text ? text : "unknown error") + " (code " +
              std::to_string(code) + ")");
}

void ensure_petsc_initialized() {
  PetscBool initialized = PETSC_FALSE;
  check_petsc(PetscInitialized(&initialized), "PetscInitialized");
  if (initialized) return;
  // kerf reports its own errors; PETSc must not take over signals.
  check_petsc(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "PetscOptionsSetValue");
  check_petsc(PetscInitializeNoArguments(), "PetscInitializeNoArguments");
  std::atexit([] { PetscFinalize(); });
}

void stop_every_rank(const RankShare& ranks, int code, const std::string& message, bool shared,
                     const std::function<void()>& if_alone) {
  // mpirun ends the other ranks of an aborted job with SIGTERM: this rank is
  // stopping, so that must end it rather than ask it to stop (InterruptScope).
  std::signal(SIGTERM, SIG_DFL);
  std::signal(SIGINT, SIG_DFL);
  if (ranks.rank != 0) {
    // Rank 0 met it too and ends this process with the job; waiting is not
    // ordering (nothing here is printed first), only a guard against a hang.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (shared && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    try {
      if (if_alone) if_alone();
    } catch (const std::exception& e) {
      std::cerr << "kerf: error: rank " << ranks.rank << ": " << e.what() << std::endl;
    }
  }
  // One write: std::cerr writes each piece at once, and mpirun's abort banner
  // (another process, same terminal) could land between them.
  const std::string line =
      "kerf: error: " + (ranks.rank != 0 ? "rank " + std::to_string(ranks.rank) + ": " : "") + message + "\n";
  std::cerr << line << std::flush;
  MPI_Abort(PETSC_COMM_WORLD, code);
  std::_Exit(code);  // MPI_Abort does not return; should it, nothing may wait for this rank
}

void wait_for_every_rank() { check_petsc(PetscBarrier(nullptr), "PetscBarrier"); }

RankShare mpi_ranks() {
  if (!launched_by_mpi()) return {};
  ensure_petsc_initialized();
  PetscMPIInt rank = 0, size = 1;
  check_petsc(MPI_Comm_rank(PETSC_COMM_WORLD, &rank), "MPI_Comm_rank");
  check_petsc(MPI_Comm_size(PETSC_COMM_WORLD, &size), "MPI_Comm_size");
  return {rank, size};
}

}  // namespace kerf
