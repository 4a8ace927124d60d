#include "solvers/newton.h"

#include <cmath>
#include <sstream>

#include "core/check.h"

namespace kerf {
namespace {

double free_norm(const FreeDofs& free, const Vector& r) {
  double s = 0.0;
  for (Index d : free.free_dofs()) s += r[d] * r[d];
  return std::sqrt(s);
}

}  // namespace

NewtonResult newton_solve(ImplicitSystem& system, const NewtonOptions& options, const ResidualFunction& residual,
                          double force_scale, Vector& u, const std::string& where) {
  const FreeDofs& free = system.free();
  const bool linear = system.body().is_linear();
  Vector r, trial, r_trial;
  NewtonResult result;
  double reference = force_scale;
  for (int iteration = 1;; ++iteration) {
    residual(u, r, true);
    double norm = free_norm(free, r);
    KERF_CHECK(std::isfinite(norm), where, ": the residual is NaN or infinite at Newton iteration ", iteration,
               " (the solution diverged; a smaller time step or more load steps may help)");
    if (iteration == 1) reference = std::max(reference, norm);
    result.residual = norm;
    if (norm <= options.tolerance * reference || norm == 0.0) return result;
    if (iteration > options.max_iterations) {
      std::ostringstream why;
      why << where << ": Newton did not converge in " << options.max_iterations << " iterations (residual "
          << norm << " N, " << norm / reference << " relative; tolerance " << options.tolerance
          << "); try a smaller time step, more load steps, or more iterations";
      throw Error(why.str());
    }
    Vector du_free = system.solve(-free.restrict_vector(r), where);
    result.iterations = iteration;
    double step = 1.0;
    trial = u;
    for (Index i = 0; i < free.free_count(); ++i) trial[free.free_dofs()[i]] += du_free[i];
    if (options.line_search && !linear && options.max_iterations > 1) {
      // Halve the step while the residual norm does not decrease (at most 6 times).
      for (int cut = 0; cut < 6; ++cut) {
        residual(trial, r_trial, false);
        double trial_norm = free_norm(free, r_trial);
        if (std::isfinite(trial_norm) && trial_norm < norm) break;
        step *= 0.5;
        trial = u;
        for (Index i = 0; i < free.free_count(); ++i) trial[free.free_dofs()[i]] += step * du_free[i];
      }
    }
    u = trial;
    KERF_CHECK(u.allFinite(), where, ": the displacement became NaN or infinite at Newton iteration ", iteration);
    if (options.max_iterations == 1) return result;
  }
}

}  // namespace kerf
