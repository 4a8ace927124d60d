#include "solvers/central_difference.h"
#include "solvers/implicit_steppers.h"
#include "solvers/stepper.h"

namespace kerf {

std::unique_ptr<Stepper> make_stepper(MechanicalSystem& mechanics, const Scene& scene, RunReport& report,
                                      const Vector& carried_mode) {
  if (scene.solve.analysis == Analysis::static_analysis) return make_static_stepper(mechanics, scene, report);
  switch (scene.solve.integrator) {
    case Integrator::implicit_euler:
      return make_implicit_euler_stepper(mechanics, scene, report);
    case Integrator::newmark:
      return make_newmark_stepper(mechanics, scene, report);
    case Integrator::central_difference:
      return make_central_difference_stepper(mechanics, scene, report, carried_mode);
  }
  return nullptr;
}

}  // namespace kerf
