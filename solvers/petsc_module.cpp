#include "solvers/petsc_module.h"

namespace kerf {

const PetscModule& petsc_module() {
  static const PetscModule& table =
      load_module<PetscModule>("petsc", "for MPI ranks or solve.linear_solver: petsc", /*global=*/true);
  return table;
}

}  // namespace kerf
