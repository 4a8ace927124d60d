#include "solvers/rank_messages.h"

#include "solvers/graph_partition.h"
#include "solvers/petsc_module.h"

namespace kerf {

std::vector<double> send_from_first_rank(std::vector<double> values) {
  return petsc_module().send_from_first_rank(std::move(values));
}

std::vector<double> send_parts_from_first_rank(std::vector<std::vector<double>> parts) {
  return petsc_module().send_parts_from_first_rank(std::move(parts));
}

std::vector<std::vector<double>> gather_from_every_rank(std::vector<double> mine) {
  return petsc_module().gather_from_every_rank(std::move(mine));
}

void sum_on_every_rank(std::span<double> values) { petsc_module().sum_on_every_rank(values); }

MpiContext petsc_mpi_context(RankShare ranks) {
  if (!ranks.distributed()) return MpiContext{ranks};
  return MpiContext{ranks, &send_from_first_rank, &send_parts_from_first_rank, &gather_from_every_rank,
                    &ptscotch_parts, &sum_on_every_rank};
}

}  // namespace kerf
