#pragma once
#include <memory>
#include <string>

#include "solvers/linear_solver.h"

namespace kerf {

/// PETSc KSP on a parallel AIJ matrix with ownership ranges; `options` go to
/// PETSc's options database, and options PETSc never used are reported as errors.
/// Initialises PETSc on first use only.
std::unique_ptr<LinearSolver> make_petsc_solver(const std::string& options, double relative_tolerance);

}  // namespace kerf
