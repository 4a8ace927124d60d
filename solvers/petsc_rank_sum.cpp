// RankSum's engine: a parallel vector assembled with ADD_VALUES, then
// gathered to every rank. Inside the PETSc module.
#include <petscvec.h>

#include "core/check.h"
#include "solvers/petsc_internals.h"

namespace kerf {
namespace {

class PetscRankSum final : public RankSum::Engine {
 public:
  PetscRankSum(Index size, Index owned_begin, Index owned_end, const std::vector<Index>& touched)
      : rows_(touched.begin(), touched.end()), values_(touched.size()), size_(size) {
    start_petsc();
    petsc_check(VecCreateMPI(PETSC_COMM_WORLD, owned_end - owned_begin, size, &owned_), "VecCreateMPI");
    petsc_check(VecScatterCreateToAll(owned_, &to_all_, &all_), "VecScatterCreateToAll");
  }
  ~PetscRankSum() override {
    if (to_all_) VecScatterDestroy(&to_all_);
    if (all_) VecDestroy(&all_);
    if (owned_) VecDestroy(&owned_);
  }

  void sum(Vector& v) const override {
    KERF_CHECK(v.size() == size_, "internal: a sum over ranks of ", v.size(), " entries; expected ", size_);
    for (std::size_t k = 0; k < rows_.size(); ++k) values_[k] = v[rows_[k]];
    petsc_check(VecZeroEntries(owned_), "VecZeroEntries");
    petsc_check(VecSetValues(owned_, static_cast<PetscInt>(rows_.size()), rows_.data(), values_.data(), ADD_VALUES),
                "VecSetValues");
    petsc_check(VecAssemblyBegin(owned_), "VecAssemblyBegin");
    petsc_check(VecAssemblyEnd(owned_), "VecAssemblyEnd");
    petsc_scatter_into(to_all_, owned_, all_, v.size(), v);
  }

 private:
  Vec owned_ = nullptr;  // the sum, each rank holding its range
  Vec all_ = nullptr;    // the whole sum on this rank
  VecScatter to_all_ = nullptr;
  std::vector<PetscInt> rows_;                // the entries this rank adds
  mutable std::vector<PetscScalar> values_;  // their values, gathered for the call (reused by every call)
  Index size_ = 0;                           // entries of the vectors summed
};

}  // namespace

std::unique_ptr<RankSum::Engine> petsc_rank_sum(Index size, Index owned_begin, Index owned_end,
                                               const std::vector<Index>& touched) {
  return std::make_unique<PetscRankSum>(size, owned_begin, owned_end, touched);
}

}  // namespace kerf
