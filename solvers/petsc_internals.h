#pragma once
// Inside the PETSc module only (solvers/petsc_module.h is the door): what its
// table gives, over PETSc.
#include <petscvec.h>

#include "solvers/petsc_module.h"

namespace kerf {

/// Throws naming the PETSc (or MPI) call and PETSc's message when `code` is not 0.
void petsc_check(int code, const char* call);
/// Starts PETSc once (no signal handlers: kerf reports its own errors); finalized at exit.
void start_petsc();
RankShare petsc_ranks();
void petsc_barrier();
void petsc_abort(int code);
/// `from` scattered forward into `to`, whose first `size` entries on this rank are then copied into `out`.
void petsc_scatter_into(VecScatter scatter, Vec from, Vec to, Index size, Vector& out);

std::vector<double> petsc_send_from_first_rank(std::vector<double> values);
std::vector<double> petsc_send_parts_from_first_rank(std::vector<std::vector<double>> parts);
std::vector<std::vector<double>> petsc_gather_from_every_rank(std::vector<double> mine);
void petsc_sum_on_every_rank(std::span<double> values);
std::vector<int> petsc_ptscotch_parts(std::span<const Index> offsets, std::span<const Index> neighbours, int parts);

std::unique_ptr<LinearSolver> petsc_ksp_solver(const std::string& options, double relative_tolerance);
std::unique_ptr<RankNumbers::Engine> petsc_rank_numbers();
std::unique_ptr<RankSum::Engine> petsc_rank_sum(Index size, Index owned_begin, Index owned_end,
                                               const std::vector<Index>& touched);
std::unique_ptr<GhostExchange::Engine> petsc_ghost_exchange(Index global_size, Index own_count,
                                                            std::span<const Index> ghosts);

}  // namespace kerf
