#include "solvers/rank_numbers.h"

#include "solvers/petsc_module.h"

namespace kerf {

RankNumbers::RankNumbers() : engine_(petsc_module().rank_numbers()) {}

RankNumbers::~RankNumbers() = default;

double RankNumbers::sum(double x) const { return engine_->sum(x); }

double RankNumbers::smallest(double x) const { return engine_->smallest(x); }

}  // namespace kerf
