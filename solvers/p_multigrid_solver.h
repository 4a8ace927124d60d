#pragma once
#include <memory>

#include "solvers/linear_solver.h"

namespace kerf {

/// Conjugate gradients preconditioned by a two-level p-multigrid V-cycle
/// (backend "p_multigrid"): Chebyshev-Jacobi smoothing on the quadratic cells'
/// matrix, the linear functions of the same mesh (set_prolongation) as the
/// coarse space, their Galerkin matrix P^T A P factorized by CHOLMOD.
std::unique_ptr<LinearSolver> make_p_multigrid_solver(double relative_tolerance);

}  // namespace kerf
