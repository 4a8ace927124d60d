#include "solvers/rank_numbers.h"

#include <petscvec.h>

#include "solvers/petsc_session.h"

namespace kerf {

struct RankNumbers::Petsc {
  Vec numbers = nullptr;  // one entry a rank
  ~Petsc() {
    if (numbers) VecDestroy(&numbers);
  }
};

RankNumbers::RankNumbers() : petsc_(std::make_unique<Petsc>()) {
  ensure_petsc_initialized();
  check_petsc(VecCreateMPI(PETSC_COMM_WORLD, 1, PETSC_DETERMINE, &petsc_->numbers), "VecCreateMPI");
}

RankNumbers::~RankNumbers() = default;

void RankNumbers::set_mine(double x) const {
  PetscScalar* mine = nullptr;
  check_petsc(VecGetArray(petsc_->numbers, &mine), "VecGetArray");
  mine[0] = x;
  check_petsc(VecRestoreArray(petsc_->numbers, &mine), "VecRestoreArray");
}

double RankNumbers::sum(double x) const {
  set_mine(x);
  PetscScalar total = 0.0;
  check_petsc(VecSum(petsc_->numbers, &total), "VecSum");
  return total;
}

double RankNumbers::smallest(double x) const {
  set_mine(x);
  PetscReal least = 0.0;
  check_petsc(VecMin(petsc_->numbers, nullptr, &least), "VecMin");
  return least;
}

}  // namespace kerf
