#include "solvers/petsc_session.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>
#include <thread>

#include "core/check.h"
#include "solvers/petsc_module.h"

namespace kerf {
namespace {

bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr ||
         std::getenv("PMI_SIZE") != nullptr;
}

}  // namespace

void check_petsc(int code, const char* call) {
  if (code != 0) petsc_module().check(code, call);
}

void ensure_petsc_initialized() { petsc_module().start(); }

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
  petsc_module().abort(code);
  std::_Exit(code);  // MPI_Abort does not return; should it, nothing may wait for this rank
}

void wait_for_every_rank() { petsc_module().barrier(); }

RankShare mpi_ranks() {
  if (!launched_by_mpi()) return {};
  return petsc_module().ranks();
}

}  // namespace kerf
