#include "solvers/rank_sum.h"

#include "solvers/petsc_module.h"
#include "solvers/rank_messages.h"

namespace kerf {

RankSum::RankSum(Index size, Index owned_begin, Index owned_end, const std::vector<Index>& touched)
    : engine_(petsc_module().rank_sum(size, owned_begin, owned_end, touched)) {}

RankSum::~RankSum() = default;

void RankSum::sum(Vector& v) const { engine_->sum(v); }

std::vector<std::vector<double>> values_of_every_rank(const std::vector<double>& mine, const RankShare& ranks) {
  if (!ranks.distributed()) return {mine};
  return gather_from_every_rank(mine);
}

}  // namespace kerf
