#pragma once
#include <memory>

#include "solvers/linear_solver.h"

namespace kerf {

/// Eigen's conjugate gradients with a diagonal preconditioner (backend "cg").
std::unique_ptr<LinearSolver> make_eigen_cg_solver(double relative_tolerance);
/// Eigen's simplicial LDL^T (backend "ldlt").
std::unique_ptr<LinearSolver> make_eigen_ldlt_solver();

}  // namespace kerf
