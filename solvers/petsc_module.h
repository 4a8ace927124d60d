#pragma once
// The PETSc module (libkerf_petsc.so, core/module_loader.h): all kerf asks of
// PETSc and, through it, MPI. Loaded the first time a run needs it (mpirun
// started the process, or the scene asks for solve.linear_solver: petsc): a
// serial run never loads PETSc's hundred libraries.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/module_loader.h"
#include "core/rank_share.h"
#include "solvers/ghost_exchange.h"
#include "solvers/linear_solver.h"
#include "solvers/rank_numbers.h"
#include "solvers/rank_sum.h"

namespace kerf {

struct PetscModule {
  ModuleStamp stamp;
  // petsc_session.h: PETSc started (once), its errors, this rank, the ranks' barrier and abort.
  void (*start)();
  void (*check)(int code, const char* call);
  RankShare (*ranks)();
  void (*barrier)();
  void (*abort)(int code);  // MPI_Abort: ends the job
  // rank_messages.h and graph_partition.h
  std::vector<double> (*send_from_first_rank)(std::vector<double> values);
  std::vector<double> (*send_parts_from_first_rank)(std::vector<std::vector<double>> parts);
  std::vector<std::vector<double>> (*gather_from_every_rank)(std::vector<double> mine);
  void (*sum_on_every_rank)(std::span<double> values);
  std::vector<int> (*ptscotch_parts)(std::span<const Index> offsets, std::span<const Index> neighbours, int parts);
  // petsc_solver.h
  std::unique_ptr<LinearSolver> (*solver)(const std::string& options, double relative_tolerance);
  // The engines of RankNumbers, RankSum and GhostExchange (their constructors' arguments).
  std::unique_ptr<RankNumbers::Engine> (*rank_numbers)();
  std::unique_ptr<RankSum::Engine> (*rank_sum)(Index size, Index owned_begin, Index owned_end,
                                               const std::vector<Index>& touched);
  std::unique_ptr<GhostExchange::Engine> (*ghost_exchange)(Index global_size, Index own_count,
                                                           std::span<const Index> ghosts);
};

/// The module's table, loaded on the first call (with its libraries' symbols
/// global: Open MPI's own plugins need them).
const PetscModule& petsc_module();

}  // namespace kerf
