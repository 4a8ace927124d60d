#include "solvers/rank_sum.h"

#include <petscvec.h>

#include "solvers/petsc_session.h"

namespace kerf {

struct RankSum::Petsc {
  Vec owned = nullptr;       // the sum, each rank holding its range
  Vec all = nullptr;         // the whole sum on this rank
  VecScatter to_all = nullptr;
  Vec number = nullptr;      // one entry a rank, for sums of numbers
  std::vector<PetscInt> rows;
  ~Petsc() {
    if (to_all) VecScatterDestroy(&to_all);
    if (all) VecDestroy(&all);
    if (owned) VecDestroy(&owned);
    if (number) VecDestroy(&number);
  }
};

RankSum::RankSum(Index size, Index owned_begin, Index owned_end, std::vector<Index> touched)
    : petsc_(std::make_unique<Petsc>()), touched_(std::move(touched)), values_(touched_.size()) {
  ensure_petsc_initialized();
  check_petsc(VecCreateMPI(PETSC_COMM_WORLD, owned_end - owned_begin, size, &petsc_->owned), "VecCreateMPI");
  check_petsc(VecScatterCreateToAll(petsc_->owned, &petsc_->to_all, &petsc_->all), "VecScatterCreateToAll");
  check_petsc(VecCreateMPI(PETSC_COMM_WORLD, 1, PETSC_DETERMINE, &petsc_->number), "VecCreateMPI");
  petsc_->rows.assign(touched_.begin(), touched_.end());
}

RankSum::~RankSum() = default;

void RankSum::sum(Vector& v) const {
  for (std::size_t k = 0; k < touched_.size(); ++k) values_[k] = v[touched_[k]];
  Vec owned = petsc_->owned, all = petsc_->all;
  check_petsc(VecZeroEntries(owned), "VecZeroEntries");
  check_petsc(VecSetValues(owned, static_cast<PetscInt>(values_.size()), petsc_->rows.data(), values_.data(), ADD_VALUES),
              "VecSetValues");
  check_petsc(VecAssemblyBegin(owned), "VecAssemblyBegin");
  check_petsc(VecAssemblyEnd(owned), "VecAssemblyEnd");
  check_petsc(VecScatterBegin(petsc_->to_all, owned, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  check_petsc(VecScatterEnd(petsc_->to_all, owned, all, INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* whole = nullptr;
  check_petsc(VecGetArrayRead(all, &whole), "VecGetArrayRead");
  v = Eigen::Map<const Vector>(whole, v.size());
  check_petsc(VecRestoreArrayRead(all, &whole), "VecRestoreArrayRead");
}

double RankSum::sum(double x) const {
  PetscScalar* mine = nullptr;
  check_petsc(VecGetArray(petsc_->number, &mine), "VecGetArray");
  mine[0] = x;
  check_petsc(VecRestoreArray(petsc_->number, &mine), "VecRestoreArray");
  PetscScalar total = 0.0;
  check_petsc(VecSum(petsc_->number, &total), "VecSum");
  return total;
}

}  // namespace kerf
