#include "core/check.h"
#include "solvers/cholmod_solver.h"
#include "solvers/eigen_solvers.h"
#include "solvers/linear_solver.h"
#include "solvers/p_multigrid_solver.h"
#include "solvers/petsc_solver.h"

namespace kerf {

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options, RunReport& report) {
  if (*linear_backend(options.kind).stage) report.add_stage(linear_backend(options.kind).stage);
  switch (options.kind) {
    case LinearSolverKind::cholmod:
      return make_cholmod_solver();
    case LinearSolverKind::petsc:
      return make_petsc_solver(options.petsc_options, options.relative_tolerance);
    case LinearSolverKind::cg:
      return make_eigen_cg_solver(options.relative_tolerance);
    case LinearSolverKind::ldlt:
      return make_eigen_ldlt_solver();
    case LinearSolverKind::p_multigrid:
      return make_p_multigrid_solver(options.relative_tolerance);
  }
  throw Error("unknown linear solver");
}

}  // namespace kerf
