#include "solvers/rank_sum.h"

#include <petscvec.h>

#include "core/check.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_messages.h"

namespace kerf {

struct RankSum::Petsc {
  Vec owned = nullptr;       // the sum, each rank holding its range
  Vec all = nullptr;         // the whole sum on this rank
  VecScatter to_all = nullptr;
  std::vector<PetscInt> rows;  // the entries this rank adds
  std::vector<PetscScalar> values;  // their values, gathered for the call
  Index size = 0;  // entries of the vectors summed
  ~Petsc() {
    if (to_all) VecScatterDestroy(&to_all);
    if (all) VecDestroy(&all);
    if (owned) VecDestroy(&owned);
  }
};

RankSum::RankSum(Index size, Index owned_begin, Index owned_end, const std::vector<Index>& touched)
    : petsc_(std::make_unique<Petsc>()) {
  ensure_petsc_initialized();
  petsc_->size = size;
  check_petsc(VecCreateMPI(PETSC_COMM_WORLD, owned_end - owned_begin, size, &petsc_->owned), "VecCreateMPI");
  check_petsc(VecScatterCreateToAll(petsc_->owned, &petsc_->to_all, &petsc_->all), "VecScatterCreateToAll");
  petsc_->rows.assign(touched.begin(), touched.end());
  petsc_->values.resize(touched.size());
}

RankSum::~RankSum() = default;

void RankSum::sum(Vector& v) const {
  KERF_CHECK(v.size() == petsc_->size, "internal: a sum over ranks of ", v.size(), " entries; expected ",
             petsc_->size);
  std::vector<PetscInt>& rows = petsc_->rows;
  std::vector<PetscScalar>& values = petsc_->values;
  for (std::size_t k = 0; k < rows.size(); ++k) values[k] = v[rows[k]];
  Vec owned = petsc_->owned, all = petsc_->all;
  check_petsc(VecZeroEntries(owned), "VecZeroEntries");
  check_petsc(VecSetValues(owned, static_cast<PetscInt>(rows.size()), rows.data(), values.data(), ADD_VALUES),
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

std::vector<std::vector<double>> values_of_every_rank(const std::vector<double>& mine, const RankShare& ranks) {
  if (!ranks.distributed()) return {mine};
  return gather_from_every_rank(mine);
}

}  // namespace kerf
