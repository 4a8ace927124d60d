#pragma once
#include <memory>

#include "solvers/linear_solver.h"

namespace kerf {

/// CHOLMOD supernodal Cholesky (SuiteSparse); the symbolic analysis is done once.
std::unique_ptr<LinearSolver> make_cholmod_solver();

}  // namespace kerf
