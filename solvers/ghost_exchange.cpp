#include "solvers/ghost_exchange.h"

#include "solvers/petsc_module.h"

namespace kerf {

GhostExchange::GhostExchange(Index global_size, Index own_count, std::span<const Index> ghosts)
    : own_count_(own_count),
      ghost_count_(static_cast<Index>(ghosts.size())),
      engine_(petsc_module().ghost_exchange(global_size, own_count, ghosts)) {}

GhostExchange::~GhostExchange() = default;

void GhostExchange::sum_and_share(Vector& local) const { engine_->sum_and_share(local); }

void GhostExchange::gather(const Vector& local, std::span<const Index> entries, Vector& whole) const {
  engine_->gather(local, entries, whole);
}

void GhostExchange::gather_all(const Vector& local, Vector& whole) const { engine_->gather_all(local, whole); }

}  // namespace kerf
