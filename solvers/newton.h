#pragma once
// Newton's method with a backtracking line search on the free dofs. With
// max_iterations = 1 it makes one linearised solve and accepts it (SOFA's
// EulerImplicitSolver does this), without checking convergence.
#include <functional>
#include <string>

#include "solvers/implicit_system.h"

namespace kerf {

/// r(u) over all dofs. When `tangent` is true the callback also refreshes and
/// factorizes the system matrix at u (through the ImplicitSystem).
using ResidualFunction = std::function<void(const Vector& u, Vector& r, bool tangent)>;

struct NewtonResult {
  int iterations = 0;
  double residual = 0.0;   // final free-dof residual norm (N)
};

/// Solves r(u) = 0 with the constrained dofs of u moved to `prescribed`. The
/// first iteration takes the jump of the prescribed values into the linear
/// solve (A_ff du_f = -(r_f + A_fc du_c)), so it spreads into the body instead
/// of crushing the cells next to the moved boundary.
/// `force_scale` (N) sets the convergence reference together with the first residual.
/// Throws naming `where` on NaN, a failed solve, or no convergence.
NewtonResult newton_solve(ImplicitSystem& system, const NewtonOptions& options, const ResidualFunction& residual,
                          double force_scale, const std::vector<DirichletDof>& prescribed, Vector& u,
                          const std::string& where);

}  // namespace kerf
