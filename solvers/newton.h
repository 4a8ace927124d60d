#pragma once
// Newton's method with a backtracking line search on the free dofs, with the
// convergence tests of PETSc's SNES: a relative residual, an absolute floor
// set from the problem's load scale, and the size of the Newton step; it
// stops early on NaN or a residual grown past a multiple of the first. It
// reports how it ended instead of throwing, so a stepper can retry with a
// smaller increment. With max_iterations = 1 it makes one linearised solve and
// accepts it (SOFA's EulerImplicitSolver does this), without checking convergence.
#include <functional>
#include <string>

#include "solvers/implicit_system.h"

namespace kerf {

/// r(u) over all dofs. When `tangent` is true the callback also refreshes and
/// factorizes the system matrix at u (through the ImplicitSystem).
using ResidualFunction = std::function<void(const Vector& u, Vector& r, bool tangent)>;

enum class NewtonStatus {
  converged_relative,  // |r| <= tolerance * reference
  converged_absolute,  // |r| <= the absolute floor
  converged_step,      // the Newton step below step_tolerance of |u|: the residual is as small as it gets
  one_solve,           // max_iterations = 1: one linearised solve, accepted unchecked
  diverged_nan,        // the residual or u became NaN or infinite
  diverged_residual,   // |r| grew past divergence_tolerance * reference
  not_converged,       // max_iterations reached
  factorization_failed,  // the tangent could not be factorized at some iterate (FactorizationFailed)
};

struct NewtonResult {
  NewtonStatus status = NewtonStatus::not_converged;
  int iterations = 0;       // linear solves made
  double residual = 0.0;    // final free-dof residual norm (N)
  double reference = 0.0;   // what the relative test compared with (N)
  std::string failure;      // the factorization's message when it failed
  bool converged() const {
    return status == NewtonStatus::converged_relative || status == NewtonStatus::converged_absolute ||
           status == NewtonStatus::converged_step || status == NewtonStatus::one_solve;
  }
};

/// The forces the tests compare with: `step_load` (N), the load of this step,
/// with the first residual the relative reference; `load_scale` (N), the whole
/// problem's load (its full external load, or the first residual of a
/// displacement-driven run), which the absolute floor is a fraction of.
struct NewtonScales {
  double step_load = 0.0;
  double load_scale = 0.0;
};

/// The absolute floor when solve.newton.absolute_tolerance is not set: this
/// fraction of the load scale (two orders below the relative tolerance).
constexpr double absolute_floor_fraction = 1.0e-10;

/// Solves r(u) = 0 with the constrained dofs of u moved to `prescribed`. The
/// first iteration takes the jump of the prescribed values into the linear
/// solve (A_ff du_f = -(r_f + A_fc du_c)), so it spreads into the body instead
/// of crushing the cells next to the moved boundary. Returns how it ended;
/// when it did not converge u is left where it stopped (the caller restores
/// it). A failed factorization ends it too (a smaller increment may pass);
/// other failures of a linear solve throw, naming `where`.
NewtonResult newton_solve(ImplicitSystem& system, const NewtonOptions& options, const ResidualFunction& residual,
                          const NewtonScales& scales, const std::vector<DirichletDof>& prescribed, Vector& u,
                          const std::string& where);

/// Why a Newton solve stopped, for a message ("did not converge in 25
/// iterations (residual 3e-3 N, 0.8 relative; tolerance 1e-8)").
std::string describe(const NewtonResult& result, const NewtonOptions& options);

}  // namespace kerf
