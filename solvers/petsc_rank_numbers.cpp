// RankNumbers' engine: a PETSc vector of one entry a rank. Inside the PETSc module.
#include <petscvec.h>

#include "solvers/petsc_internals.h"

namespace kerf {
namespace {

class PetscRankNumbers final : public RankNumbers::Engine {
 public:
  PetscRankNumbers() {
    start_petsc();
    petsc_check(VecCreateMPI(PETSC_COMM_WORLD, 1, PETSC_DETERMINE, &numbers_), "VecCreateMPI");
  }
  ~PetscRankNumbers() override {
    if (numbers_) VecDestroy(&numbers_);
  }

  double sum(double x) const override {
    set_mine(x);
    PetscScalar total = 0.0;
    petsc_check(VecSum(numbers_, &total), "VecSum");
    return total;
  }

  double smallest(double x) const override {
    set_mine(x);
    PetscReal least = 0.0;
    petsc_check(VecMin(numbers_, nullptr, &least), "VecMin");
    return least;
  }

 private:
  void set_mine(double x) const {  // this rank's entry
    PetscScalar* mine = nullptr;
    petsc_check(VecGetArray(numbers_, &mine), "VecGetArray");
    mine[0] = x;
    petsc_check(VecRestoreArray(numbers_, &mine), "VecRestoreArray");
  }

  Vec numbers_ = nullptr;  // one entry a rank
};

}  // namespace

std::unique_ptr<RankNumbers::Engine> petsc_rank_numbers() { return std::make_unique<PetscRankNumbers>(); }

}  // namespace kerf
