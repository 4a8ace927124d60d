#pragma once
// The collective calls of core/mpi_context.h, through PETSc vectors and
// scatters (kerf passes no message of its own), and the context that holds them.
#include <span>
#include <vector>

#include "core/mpi_context.h"

namespace kerf {

/// Rank 0's values on every rank (each passes its own; only rank 0's are
/// read): a PETSc vector held by rank 0, gathered to all. Collective.
std::vector<double> send_from_first_rank(std::vector<double> values);

/// Rank 0's parts[r] on rank r: rank 0's lists in one PETSc vector held by
/// rank 0, scattered to a vector whose rank r holds list r. Collective.
std::vector<double> send_parts_from_first_rank(std::vector<std::vector<double>> parts);

/// Every rank's `mine` (any length) in rank order, on every rank. Collective.
std::vector<std::vector<double>> gather_from_every_rank(std::vector<double> mine);

/// Every rank's `values` (the same length on each) added up, on every rank:
/// each rank adds its nonzero entries into a PETSc vector (ADD_VALUES), which
/// is then gathered to all. Collective.
void sum_on_every_rank(std::span<double> values);

/// The run's context among `ranks`: its collective calls through PETSc and
/// its graphs partitioned by PT-Scotch (solvers/graph_partition.h); a
/// serial context (no calls) on one rank.
MpiContext petsc_mpi_context(RankShare ranks);

}  // namespace kerf
