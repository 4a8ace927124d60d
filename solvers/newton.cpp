#include "solvers/newton.h"

#include <cmath>
#include <sstream>

#include "core/check.h"
#include "core/interrupt.h"

namespace kerf {
namespace {

double free_norm(const FreeDofs& free, const Vector& r) {
  double s = 0.0;
  for (Index d : free.free_dofs()) s += r[d] * r[d];
  return std::sqrt(s);
}

}  // namespace

NewtonResult newton_solve(ImplicitSystem& system, const NewtonOptions& options, const ResidualFunction& residual,
                          double force_scale, const std::vector<DirichletDof>& prescribed, Vector& u,
                          const std::string& where) {
  const FreeDofs& free = system.free();
  const bool linear = system.mechanics().is_linear();
  Vector r, trial, r_trial;
  // What the constrained dofs still have to move (zero on free dofs).
  Vector jump = Vector::Zero(u.size());
  for (const DirichletDof& d : prescribed) jump[d.dof] = d.value - u[d.dof];
  NewtonResult result;
  double reference = force_scale;
  for (int iteration = 1;; ++iteration) {
    stop_if_interrupted("at Newton iteration ", iteration, " of ", where);
    residual(u, r, true);
    double norm = free_norm(free, r);
    KERF_CHECK(std::isfinite(norm), where, ": the residual is NaN or infinite at Newton iteration ", iteration,
               " (the solution diverged; a smaller time step or more load steps may help)");
    const bool moves_boundary = jump.squaredNorm() > 0.0;
    if (moves_boundary) r += system.system_times(jump);  // the linearised effect of the jump
    // The first residual sets the scale; when it is zero (a prescribed motion
    // that the linearisation does not feel yet, as a sphere not yet touching),
    // the first nonzero one.
    if (iteration == 1 || reference == 0.0) reference = std::max({reference, norm, free_norm(free, r)});
    result.residual = norm;
    if (!moves_boundary && (norm <= options.tolerance * reference || norm == 0.0)) return result;
    if (iteration > options.max_iterations) {
      std::ostringstream why;
      why << where << ": Newton did not converge in " << options.max_iterations << " iterations (residual "
          << norm << " N, " << norm / reference << " relative; tolerance " << options.tolerance
          << "); try a smaller time step, more load steps, or more iterations";
      throw Error(why.str());
    }
    Vector du_free = system.solve(-free.restrict_vector(r), where);
    result.iterations = iteration;
    auto step_to = [&](double step) {
      trial = u + step * jump;
      for (Index i = 0; i < free.free_count(); ++i) trial[free.free_dofs()[i]] += step * du_free[i];
    };
    double step = 1.0;
    step_to(step);
    if (options.line_search && !linear && options.max_iterations > 1) {
      // Halve the step (at most 6 times) while the residual does not decrease,
      // or, while the boundary moves (norms before and after are not comparable),
      // while it is not finite.
      for (int cut = 0; cut < 6; ++cut) {
        residual(trial, r_trial, false);
        double trial_norm = free_norm(free, r_trial);
        if (std::isfinite(trial_norm) && (moves_boundary || trial_norm < norm)) break;
        step *= 0.5;
        step_to(step);
      }
    }
    u = trial;
    jump *= 1.0 - step;  // a cut step leaves the rest of the jump for the next iteration
    KERF_CHECK(u.allFinite(), where, ": the displacement became NaN or infinite at Newton iteration ", iteration);
    if (options.max_iterations == 1) {
      u += jump;  // one linearised solve: the boundary ends where it is prescribed
      return result;
    }
  }
}

}  // namespace kerf
