#include "solvers/petsc_solver.h"

#include "solvers/petsc_module.h"

namespace kerf {

std::unique_ptr<LinearSolver> make_petsc_solver(const std::string& options, double relative_tolerance) {
  return petsc_module().solver(options, relative_tolerance);
}

}  // namespace kerf
