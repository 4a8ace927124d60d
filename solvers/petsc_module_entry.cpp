// The PETSc module's one exported symbol: its table (solvers/petsc_module.h).
#include "solvers/petsc_internals.h"

KERF_MODULE_ENTRY const kerf::PetscModule* kerf_petsc_module() {
  using namespace kerf;
  static const PetscModule table{{version, sizeof(PetscModule)},
                                 start_petsc,
                                 petsc_check,
                                 petsc_ranks,
                                 petsc_barrier,
                                 petsc_abort,
                                 petsc_send_from_first_rank,
                                 petsc_send_parts_from_first_rank,
                                 petsc_gather_from_every_rank,
                                 petsc_sum_on_every_rank,
                                 petsc_ptscotch_parts,
                                 petsc_ksp_solver,
                                 petsc_rank_numbers,
                                 petsc_rank_sum,
                                 petsc_ghost_exchange};
  return &table;
}
