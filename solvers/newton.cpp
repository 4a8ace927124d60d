#include "solvers/newton.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

double free_dot(const FreeDofs& free, const Vector& du_free, const Vector& r) {
  double s = 0.0;
  for (Index i = 0; i < free.free_count(); ++i) s += du_free[i] * r[free.free_dofs()[i]];
  return s;
}

using StepTo = std::function<void(double)>;

/// The old rule, where the step is not a descent direction of the energy (an
/// indefinite or unsymmetric tangent) or the boundary moves: halve the step
/// (at most 6 times) while the residual does not decrease or, while the
/// boundary moves (norms before and after are not comparable), while it is
/// not finite.
double backtrack(const FreeDofs& free, double norm, bool moves_boundary, const ResidualFunction& residual,
                 const StepTo& step_to, Vector& trial, Vector& r_trial) {
  double step = 1.0;
  for (int cut = 0; cut < 6; ++cut) {
    step_to(step);
    residual(trial, r_trial, false);
    const double trial_norm = free_norm(free, r_trial);
    if (std::isfinite(trial_norm) && (moves_boundary || trial_norm < norm)) break;
    step *= 0.5;
  }
  return step;
}

/// The step length s along du. The whole step when it lowers the residual's
/// norm (as the residual-norm rule always did). Else, where the energy stops
/// decreasing along du: the residual's component along the step, g(s) = du .
/// r(u + s du) (for a hyperelastic body the energy's derivative along du),
/// falls to half its size at s = 0 (Crisfield's line search): s = 1 when g(1)
/// meets that or is still negative, else regula falsi (Illinois) on the
/// bracket [0, 1], at most 6 residuals, keeping the best s. A residual on the
/// far side of an inverted element (NaN) halves the bracket's end first. The
/// residual-norm rule alone (backtrack) made a floppy cantilever's first
/// increments take 20 iterations of steps cut to 1/64.
double energy_line_search(const FreeDofs& free, const Vector& du_free, double norm, double slope,
                          const ResidualFunction& residual, const StepTo& step_to, Vector& trial, Vector& r_trial) {
  constexpr double enough = 0.5;
  constexpr int evaluations = 6;
  auto g = [&](double s) {
    step_to(s);
    residual(trial, r_trial, false);
    const double value = free_dot(free, du_free, r_trial);
    return std::isfinite(value) ? value : std::numeric_limits<double>::infinity();
  };
  double a = 0.0, ga = slope, b = 1.0, gb = g(b);
  if (std::isfinite(gb) && free_norm(free, r_trial) < norm) return b;
  int used = 1;
  for (; !std::isfinite(gb) && used < evaluations; ++used) gb = g(b *= 0.5);
  if (!std::isfinite(gb)) return b;
  if (gb <= enough * -slope) return b;  // still descending at s = b, or near the stationary point
  double best = b, best_g = std::abs(gb);
  int side = 0;  // Illinois: which end was kept last
  for (; used < evaluations; ++used) {
    const double s = std::clamp(b - gb * (b - a) / (gb - ga), a + 0.01 * (b - a), b - 0.01 * (b - a));
    const double gs = g(s);
    if (std::abs(gs) < best_g) best = s, best_g = std::abs(gs);
    if (std::abs(gs) <= enough * -slope) break;
    if (gs > 0.0) {
      b = s, gb = gs;
      if (side == 1) ga *= 0.5;
      side = 1;
    } else {
      a = s, ga = gs;
      if (side == -1) gb *= 0.5;
      side = -1;
    }
  }
  return best;
}

/// r(u) and the tangent at u: false (the result saying why) when the
/// tangent could not be factorized.
bool tangent_and_residual(const ResidualFunction& residual, const Vector& u, Vector& r, NewtonResult& result) {
  try {
    residual(u, r, true);
    return true;
  } catch (const FactorizationFailed& e) {
    result.status = NewtonStatus::factorization_failed;
    result.failure = e.what();
    return false;
  }
}

/// The convergence and divergence tests on a residual norm (no boundary moving).
std::optional<NewtonStatus> residual_test(const NewtonOptions& options, double norm, double reference,
                                          double absolute, int iteration) {
  if (norm == 0.0 || norm <= options.tolerance * reference) return NewtonStatus::converged_relative;
  if (norm <= absolute) return NewtonStatus::converged_absolute;
  if (iteration > 1 && norm > options.divergence_tolerance * reference) return NewtonStatus::diverged_residual;
  return std::nullopt;
}

}  // namespace

NewtonResult newton_solve(ImplicitSystem& system, const NewtonOptions& options, const ResidualFunction& residual,
                          const NewtonScales& scales, const std::vector<DirichletDof>& prescribed, Vector& u,
                          const std::string& where) {
  const FreeDofs& free = system.free();
  const bool linear = system.mechanics().is_linear();
  Vector r, trial, r_trial;
  // What the constrained dofs still have to move (zero on free dofs).
  Vector jump = Vector::Zero(u.size());
  for (const DirichletDof& d : prescribed) jump[d.dof] = d.value - u[d.dof];
  NewtonResult result;
  double reference = scales.step_load;
  for (int iteration = 1;; ++iteration) {
    stop_if_interrupted("at Newton iteration ", iteration, " of ", where);
    if (!tangent_and_residual(residual, u, r, result)) return result;
    const double norm = free_norm(free, r);
    result.residual = norm;
    if (!std::isfinite(norm)) {
      result.status = NewtonStatus::diverged_nan;
      return result;
    }
    const bool moves_boundary = jump.squaredNorm() > 0.0;
    if (moves_boundary) r += system.system_times(jump);  // the linearised effect of the jump
    // The first residual sets the scale; when it is zero (a prescribed motion
    // that the linearisation does not feel yet, as a sphere not yet touching),
    // the first nonzero one.
    if (iteration == 1 || reference == 0.0) reference = std::max({reference, norm, free_norm(free, r)});
    result.reference = reference;
    const double absolute =
        options.absolute_tolerance.value_or(absolute_floor_fraction * std::max(scales.load_scale, reference));
    if (!moves_boundary) {
      if (auto ended = residual_test(options, norm, reference, absolute, iteration)) {
        result.status = *ended;
        return result;
      }
    }
    if (iteration > options.max_iterations) {
      result.status = NewtonStatus::not_converged;
      return result;
    }
    Vector du_free;
    try {
      du_free = system.solve(-free.restrict_vector(r), where);  // may factorize a stale matrix
    } catch (const FactorizationFailed& e) {
      result.status = NewtonStatus::factorization_failed;
      result.failure = e.what();
      return result;
    }
    result.iterations = iteration;
    auto step_to = [&](double step) {
      trial = u + step * jump;
      for (Index i = 0; i < free.free_count(); ++i) trial[free.free_dofs()[i]] += step * du_free[i];
    };
    double step = 1.0;
    step_to(step);
    if (!moves_boundary && du_free.norm() <= options.step_tolerance * free_norm(free, trial)) {
      // The whole Newton step is below the tolerance of u: what is left of the
      // residual is round-off (or the step's own size), not an error in u.
      u = trial;
      result.status = NewtonStatus::converged_step;
      return result;
    }
    if (options.line_search && !linear && options.max_iterations > 1) {
      const double slope = moves_boundary ? 0.0 : free_dot(free, du_free, r);
      step = slope < 0.0 ? energy_line_search(free, du_free, norm, slope, residual, step_to, trial, r_trial)
                         : backtrack(free, norm, moves_boundary, residual, step_to, trial, r_trial);
      step_to(step);
    }
    u = trial;
    jump *= 1.0 - step;  // a cut step leaves the rest of the jump for the next iteration
    if (!u.allFinite()) {
      result.status = NewtonStatus::diverged_nan;
      return result;
    }
    if (options.max_iterations == 1) {
      u += jump;  // one linearised solve: the boundary ends where it is prescribed
      result.status = NewtonStatus::one_solve;
      return result;
    }
  }
}

std::string describe(const NewtonResult& result, const NewtonOptions& options) {
  std::ostringstream why;
  const double relative = result.reference > 0.0 ? result.residual / result.reference : 0.0;
  switch (result.status) {
    case NewtonStatus::diverged_nan:
      why << "Newton diverged: the residual or the displacement became NaN or infinite at iteration "
          << result.iterations + 1;
      return why.str();
    case NewtonStatus::diverged_residual:
      why << "Newton diverged: the residual grew to " << result.residual << " N, " << relative
          << " times the first (divergence_tolerance " << options.divergence_tolerance << ") at iteration "
          << result.iterations + 1;
      return why.str();
    case NewtonStatus::factorization_failed:
      return result.failure;
    case NewtonStatus::not_converged:
      why << "Newton did not converge in " << options.max_iterations << " iterations (residual " << result.residual
          << " N, " << relative << " relative; tolerance " << options.tolerance << ")";
      return why.str();
    default:
      why << "Newton converged in " << result.iterations << " iterations (residual " << result.residual << " N)";
      return why.str();
  }
}

}  // namespace kerf
