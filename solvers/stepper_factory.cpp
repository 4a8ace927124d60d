#include "solvers/central_difference.h"
#include "solvers/implicit_steppers.h"
#include "solvers/stepper.h"

namespace kerf {

StepperSettings stepper_settings(const Scene& scene) {
  return {scene.solve, scene.material.damping_mass, scene.material.damping_stiffness,
          scene.locate("solve.dt").describe()};
}

std::unique_ptr<Stepper> make_stepper(MechanicalSystem& mechanics, const StepperSettings& settings, RunReport& report,
                                      const Vector& carried_mode) {
  const SolveOptions& solve = settings.solve;
  if (solve.analysis == Analysis::static_analysis) return make_static_stepper(mechanics, solve, report);
  switch (solve.integrator) {
    case Integrator::implicit_euler:
      return make_implicit_euler_stepper(mechanics, settings, report);
    case Integrator::newmark:
      return make_newmark_stepper(mechanics, settings, report);
    case Integrator::central_difference:
      return make_central_difference_stepper(mechanics, settings, report, carried_mode);
  }
  return nullptr;
}

}  // namespace kerf
